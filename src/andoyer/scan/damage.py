"""The integrity of a scan store: every chunk of every point marked done checked.

Every chunk of a scan store carries a CRC-32C checksum (Zarr's ``crc32c`` codec, after
Zstandard compression) and is written even when it holds fill values only, so a point
marked done whose chunk file is missing or whose bytes changed is detected: :func:`verify`
names such points (:class:`Damage`); :mod:`andoyer.scan.store` computes them again on
resume and refuses to open the store until then. Metadata files (``zarr.json``) that are
truncated, not UTF-8 or not JSON are named as such (:func:`read_metadata`).
"""

from __future__ import annotations

import itertools
import json
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from andoyer.errors import DamagedFileError

__all__ = ["CHECKSUM", "Damage", "damage_summary", "read_metadata", "verify"]

#: Store attribute saying that every chunk has a checksum and is written even when it
#: holds fill values only (so a missing chunk file of a done point is a loss).
CHECKSUM = "crc32c"


def read_metadata(file: Path) -> dict[str, Any]:
    """A ``zarr.json``, read; a truncated, non-UTF-8 or non-JSON file is named.

    Parameters
    ----------
    file : pathlib.Path
        The metadata file (``zarr.json``) of a store, group or array.

    Returns
    -------
    dict
        Its content (Zarr format 3 metadata).

    Raises
    ------
    DamagedFileError
        The file is not UTF-8, not JSON (truncated or changed) or not Zarr format 3.
    """
    try:
        text = file.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise DamagedFileError(f"{file}: not UTF-8 text (byte {exc.object[exc.start]:#04x} "
                               f"at offset {exc.start}): damaged, or not Zarr metadata"
                               ) from None
    try:
        meta = json.loads(text)
    except json.JSONDecodeError as exc:
        cut = exc.pos >= len(text.rstrip()) or not text.rstrip().endswith("}")
        what = (f"truncated (ends after {len(text)} bytes, inside the JSON)" if cut else
                f"not valid JSON ({exc.msg} at line {exc.lineno}, column {exc.colno})")
        raise DamagedFileError(f"{file}: {what}: the Zarr metadata is damaged") from None
    if not isinstance(meta, dict) or meta.get("zarr_format") != 3:
        raise DamagedFileError(f"{file}: not Zarr format 3 metadata")
    return meta


@dataclass(frozen=True)
class Damage:
    """A chunk of a point (or block of points) marked done whose data are lost.

    Attributes
    ----------
    block : tuple of int
        The chunk's index along the swept dims (one scan task).
    points : list of dict
        The parameter values (storage names) of the points of the chunk.
    variable : str
        The array whose chunk is missing or damaged.
    problem : str
        ``"missing"`` or what decoding said (e.g. a checksum mismatch).
    """

    block: tuple[int, ...]
    points: list[dict[str, float]]
    variable: str
    problem: str

    def describe(self) -> str:
        at = "; ".join(", ".join(f"{k} = {v:g}" for k, v in p.items())
                       for p in self.points)
        return f"point {at}: {self.variable} {self.problem}"


def _checksum_problem(file: Path) -> str | None:
    """What is wrong with a chunk file written with the ``crc32c`` codec, if anything.

    The codec appends the CRC-32C of the encoded bytes (4 bytes, little-endian); the
    check is Zarr's own (:class:`zarr.codecs.Crc32cCodec`), done here on the raw file so
    that no chunk is decompressed.
    """
    import google_crc32c  # Zarr's checksum library (what its crc32c codec calls)

    try:
        data = file.read_bytes()
    except FileNotFoundError:
        return "is missing (its chunk file was deleted)"
    if len(data) < 4 or np.uint32(google_crc32c.value(data[:-4])).tobytes() != data[-4:]:
        return "is damaged (its bytes do not match their CRC-32C checksum)"
    return None


def _decode_problem(arr: Any, key: tuple[int, ...]) -> str | None:
    try:
        arr.get_block_selection(key)
    except Exception as exc:  # whatever the codecs raise on bytes they cannot decode
        return f"is damaged ({type(exc).__name__}: {exc})"
    return None


def verify(path: str | os.PathLike[str]) -> list[Damage]:
    """Check every chunk of every point marked done: present, and its checksum right.

    Parameters
    ----------
    path : path of a scan store

    Returns
    -------
    list of Damage
        Empty when every point marked done has all its data. Stores written before
        checksums (no ``chunk_checksums`` attr) are checked by decoding their chunks.

    Raises
    ------
    DamagedFileError
        When the store's metadata, coordinates or ``done`` flags themselves are damaged
        (no point can then be trusted).
    """
    import zarr

    path = Path(path)
    for file in sorted(path.rglob("zarr.json")):
        read_metadata(file)
    attrs = read_metadata(path / "zarr.json").get("attributes", {})
    dims = [str(d) for d in json.loads(str(attrs.get("scan_dims", "[]")))]
    strict = attrs.get("chunk_checksums") == CHECKSUM
    group = zarr.open_group(path, mode="r", use_consolidated=False)
    arrays = dict(group.arrays())
    if "done" not in arrays or any(d not in arrays for d in dims):
        raise DamagedFileError(f"{path}: arrays of the scan store are missing (done or a "
                               "swept coordinate): start the scan again with --overwrite")

    def whole(name: str, what: str, missing_ok: bool = False) -> np.ndarray:
        arr = arrays[name]
        problems = (_checksum_problem(path / name / arr.metadata.encode_chunk_key(key))
                    for key in np.ndindex(*arr.cdata_shape)) if strict else iter(())
        problem = next((p for p in problems
                        if p and not (missing_ok and p.startswith("is missing"))), None)
        try:
            values = np.asarray(arr[...])
        except Exception as exc:
            problem = problem or f"is damaged ({type(exc).__name__}: {exc})"
        if problem:
            raise DamagedFileError(f"{path / name}: {what}: {problem[3:]}; no point can be "
                                   "trusted: start the scan again with --overwrite")
        return values

    coords = {d: whole(d, f"the coordinate {d}") for d in dims}
    # A done chunk never written means "not done" (written only once its data are).
    done = whole("done", "the done flags", missing_ok=True).astype(bool)
    block = tuple(arrays["done"].chunks)
    n = len(dims)
    data = {name: arr for name, arr in arrays.items()
            if name not in coords and name != "done"
            and tuple(getattr(arr.metadata, "dimension_names", None) or ())[:n] == tuple(dims)}
    out: list[Damage] = []
    for b in np.ndindex(*arrays["done"].cdata_shape):
        region = tuple(slice(i * c, (i + 1) * c) for i, c in zip(b, block, strict=True))
        if not done[region].any():
            continue
        for name, arr in data.items():
            problem = None
            for rest in np.ndindex(*arr.cdata_shape[n:]):
                key = (*b, *rest)
                problem = (_checksum_problem(path / name / arr.metadata.encode_chunk_key(key))
                           if strict else _decode_problem(arr, key))
                if problem:
                    break
            if problem:
                points = [{d: float(coords[d][i]) for d, i in zip(dims, index, strict=True)}
                          for index in itertools.product(
                              *(range(r.start, min(r.stop, len(coords[d])))
                                for r, d in zip(region, dims, strict=True)))]
                out.append(Damage(tuple(map(int, b)), points, name, problem))
    return out


def damage_summary(damage: Sequence[Damage], limit: int = 3) -> str:
    """The first ``limit`` damaged chunks described, and how many more there are.

    Parameters
    ----------
    damage : sequence of Damage
        What :func:`verify` found.
    limit : int
        How many chunks to describe.

    Returns
    -------
    str
        One ``describe()`` per chunk, separated by ``;``.
    """
    text = "; ".join(d.describe() for d in damage[:limit])
    return text + (f"; and {len(damage) - limit} more" if len(damage) > limit else "")
