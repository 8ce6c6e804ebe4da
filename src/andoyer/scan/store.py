"""The Zarr store of a scan: laid out once, filled chunk by chunk, resumable.

Layout (one xarray dataset)
---------------------------
* dims: the swept parameters (storage names of :data:`~andoyer.scan.config.STORAGE_NAMES`:
  ``mu``, ``h_level``, ``M_level``, ``A``, ``B``, ``C``), then the task's own dims
  (``orbit``, ``crossing``, ``component`` for sections);
* every variable of the task, with the swept dims in front; Zarr chunks = the scan's
  chunks along the swept dims, whole along the task's dims, so one task writes whole
  Zarr chunks;
* ``done`` (swept dims, bool): the points whose data are written. It is written *after*
  the data of its chunk, so a chunk interrupted while being written has no mark and is
  recomputed on resume; Zarr writes each chunk file atomically (temporary file, then
  rename), so no file is ever half-written;
* every chunk of every array carries a CRC-32C checksum (Zarr's ``crc32c`` codec, after
  Zstandard compression) and every chunk is written, even one of fill values, so a
  point marked done whose chunk file is missing or whose bytes changed is detected:
  :func:`verify` names such points, a resume computes them again and
  :func:`open_store` (``andoyer atlas``) refuses the store until then;
* ``empty`` (swept dims, bool): points where the task had nothing to compute (e.g. the
  energy level does not meet the section); their data are fill values;
* ``e1, e2, e3`` coordinates over the swept moments when the centre of mass follows them
  (Hess bodies); attrs: the full configuration (``scan_config``, canonical JSON), body,
  engine, tolerances, version.

The store is initialised in a temporary directory beside the target and renamed into
place, so a store either does not exist or has its complete layout. Only one process
writes (the one that runs the scan): workers return their results to it. Metadata files
(``zarr.json``) that are truncated, not UTF-8 or not JSON are named as such.
"""

from __future__ import annotations

import json
import os
import shutil
import uuid
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from andoyer._version import __version__
from andoyer.atomic import named_when_full
from andoyer.errors import DamagedFileError, DamagedStoreWarning
from andoyer.scan.config import PARAMETER_ATTRS, STORAGE_NAMES, ScanConfig
from andoyer.scan.damage import CHECKSUM, Damage, damage_summary, read_metadata, verify
from andoyer.scan.tasks import TASKS, Empty

__all__ = ["Schema", "Variable", "Damage", "point_schema", "initialise", "check_store", "prepare",
           "write_chunk", "store_schema", "done_mask", "verify", "open_store", "FLAGS",
           "CHECKSUM"]

#: Bookkeeping variables of the store (not task data).
FLAGS = ("done", "empty")
_BODY_COORDS = ("e1", "e2", "e3")


def _codecs() -> dict[str, Any]:
    """Encoding of every array: Zstandard, then Zarr's CRC-32C checksum codec."""
    from zarr.codecs import Crc32cCodec, ZstdCodec

    return {"compressors": (ZstdCodec(level=0), Crc32cCodec())}


@dataclass(frozen=True)
class Variable:
    """One variable of a point's result: its task dims, shape, dtype and attrs.

    Attributes
    ----------
    dims : tuple of str
        Its task dimensions.
    shape : tuple of int
        Its shape along them.
    dtype : numpy.dtype
        Its type.
    attrs : mapping
        Its attributes (units, long name).
    """

    dims: tuple[str, ...]
    shape: tuple[int, ...]
    dtype: np.dtype[Any]
    attrs: Mapping[str, Any]

    @property
    def blank(self) -> Any:
        """Value of a point with no data: NaN, 0 or False (what Zarr holds unwritten)."""
        if self.dtype.kind in "fc":
            return np.nan
        return False if self.dtype.kind == "b" else 0


@dataclass(frozen=True)
class Schema:
    """The variables of one point's result, and the task coordinates shared by all.

    Attributes
    ----------
    variables : mapping of str to Variable
        The variables of a point's result.
    coords : mapping of str to xarray.Variable
        The task's coordinates shared by every point.
    """

    variables: Mapping[str, Variable]
    coords: Mapping[str, xr.Variable]


def _case_collisions(names: Sequence[str]) -> list[tuple[str, str]]:
    seen: dict[str, str] = {}
    out = []
    for n in names:
        if n.lower() in seen and seen[n.lower()] != n:
            out.append((seen[n.lower()], n))
        seen.setdefault(n.lower(), n)
    return out


def point_schema(ds: xr.Dataset, fixed_coords: Sequence[str]) -> Schema:
    """The schema of a task's result, from its first computed point.

    Coordinates listed in ``fixed_coords`` are kept as coordinates; other numeric
    coordinates may change from point to point and become variables ``<name>_values``.

    Parameters
    ----------
    ds : xarray.Dataset
        The first computed point's result.
    fixed_coords : sequence of str
        Coordinates that are the same at every point.
    """
    renamed: dict[str, str] = {}
    variables: dict[str, Variable] = {}
    coords: dict[str, xr.Variable] = {}
    for name, c in ds.coords.items():
        name = str(name)
        if c.dtype.kind not in "biufc":
            continue  # labels (strings) are kept in the variables' attrs by the tasks
        if name in fixed_coords:
            coords[name] = c.variable
        else:
            renamed[name] = f"{name}_values"
    for name, v in {**{str(k): ds[k] for k in ds.data_vars},
                    **{new: ds[old] for old, new in renamed.items()}}.items():
        if v.dtype.kind not in "biufc":
            raise ValueError(f"variable {name!r} of dtype {v.dtype} cannot be scanned "
                             "(numbers and booleans only)")
        variables[name] = Variable(tuple(map(str, v.dims)), tuple(v.shape), v.dtype,
                                   dict(v.attrs))
    return Schema(variables, coords)


def _check_names(cfg: ScanConfig, schema: Schema) -> None:
    names = [*cfg.dims, *schema.variables, *schema.coords, *FLAGS, *_BODY_COORDS]
    clash = [n for n in schema.variables if n in (*cfg.dims, *FLAGS, *_BODY_COORDS)]
    if clash:
        raise ValueError(f"the task's variable {clash[0]!r} has the name of a scan dim or "
                         "flag; rename it in the task")
    pairs = _case_collisions(names)
    if pairs:
        a, b = pairs[0]
        raise ValueError(f"names {a!r} and {b!r} differ only by case: they would collide "
                         "in a Zarr store on a case-insensitive file system")


def _body_coords(cfg: ScanConfig) -> dict[str, tuple[tuple[str, ...], Any, dict[str, str]]]:
    """``e1, e2, e3`` over the swept moments and turn (a Hess body's r follows A, B, C
    and epsilon)."""
    moments = [k for k in cfg.swept if k in ("A", "B", "C", "epsilon")]
    if cfg.body_kind != "hess" or not moments:
        return {}
    shape = tuple(len(cfg.values(k)) for k in moments)
    e = np.empty((*shape, 3))
    for index in np.ndindex(*shape):
        values = cfg.fixed | {"mu": cfg.values("mu")[0]}
        values.update({k: cfg.values(k)[i] for k, i in zip(moments, index, strict=True)})
        e[index] = cfg.body_at(values).r
    dims = tuple(STORAGE_NAMES[k] for k in moments)
    return {f"e{i + 1}": (dims, e[..., i],
                          {"long_name": f"centre of mass direction, body axis {i + 1}",
                           "equation": "(1), (2)", "units": "1"}) for i in range(3)}


def _attrs(cfg: ScanConfig, first_attrs: Mapping[str, Any]) -> dict[str, Any]:
    from andoyer.integrate.results import provenance

    values = cfg.fixed | {k: cfg.values(k)[0] for k in cfg.swept}
    body = cfg.body_at(values)
    kind = TASKS[cfg.task]
    attrs = provenance(body, **{k: first_attrs[k] for k in kind.static_attrs
                                if k in first_attrs})
    for k in cfg.swept:
        if k in ("A", "B", "C", "mu"):
            attrs[f"body_{k}"] = f"swept: coordinate {STORAGE_NAMES[k]}"
    if cfg.body_kind == "hess" and any(k in cfg.swept for k in ("A", "B", "C", "epsilon")):
        for k in _BODY_COORDS:
            attrs[f"body_{k}"] = f"swept: coordinate {k}"
    if cfg.task in ("section", "chaos_map"):
        from andoyer.integrate import Section

        attrs.update(Section.parse(dict(cfg.task_options)["section"]).attrs())
    for k, v in cfg.fixed.items():
        if k in ("h", "M"):
            attrs[STORAGE_NAMES[k]] = v
    attrs.update(
        title=f"andoyer parameter scan: {kind.doc}, over "
              f"{' x '.join(f'{STORAGE_NAMES[k]}[{len(cfg.values(k))}]' for k in cfg.swept)}",
        scan_config=cfg.to_json(),
        scan_task=cfg.task,
        scan_dims=json.dumps(list(cfg.dims)),
        engine=cfg.integrator.engine,
        rtol=cfg.integrator.rtol,
        atol=cfg.integrator.atol,
        threads="each task runs single-threaded in its worker (results do not depend on "
                "the number of workers)",
        completion="done marks the points whose data are written (written after the "
                   "data); empty marks points with nothing to compute (fill values)",
        andoyer_version=__version__,
    )
    return attrs


def initialise(path: Path, cfg: ScanConfig, schema: Schema, first_attrs: Mapping[str, Any],
               *, overwrite: bool) -> None:
    """Write the store's layout (coordinates, attrs, every variable full of fill values).

    Built in a temporary directory beside ``path`` and renamed into place.

    Parameters
    ----------
    path : pathlib.Path
        The store to create.
    cfg : ScanConfig
        The scan.
    schema : Schema
        The variables of a point's result.
    first_attrs : mapping
        The attributes of the first result (the static ones go to the store).
    overwrite : bool
        Replace an existing scan store.
    """
    import dask.array as da

    _check_names(cfg, schema)
    grid = cfg.shape
    chunks = cfg.chunks
    data: dict[str, Any] = {}
    for name, v in schema.variables.items():
        data[name] = (cfg.dims + v.dims,
                      da.full(grid + v.shape, v.blank, dtype=v.dtype, chunks=chunks + v.shape),
                      dict(v.attrs))
    for flag, long in (("done", "the point's data are written"),
                       ("empty", "the task had nothing to compute at this point")):
        data[flag] = (cfg.dims, da.zeros(grid, dtype=bool, chunks=chunks),
                      {"long_name": long})
    coords: dict[str, Any] = {}
    for k in cfg.swept:
        sym, long, eq, units = PARAMETER_ATTRS[k]
        coords[STORAGE_NAMES[k]] = (STORAGE_NAMES[k], np.array(cfg.values(k)),
                                    {"symbol": sym, "long_name": long, "equation": eq,
                                     "units": units})
    coords.update(schema.coords)
    coords.update(_body_coords(cfg))
    ds = xr.Dataset(data, coords=coords, attrs=_attrs(cfg, first_attrs) | {
        "chunk_checksums": CHECKSUM})
    tmp = path.parent / f".{path.name}.init-{uuid.uuid4().hex[:8]}"
    try:
        with warnings.catch_warnings(), named_when_full(path):
            # Consolidated metadata (one read to open the store) is a zarr-python
            # extension of format 3; xarray and zarr read it.
            warnings.filterwarnings("ignore", message=".*[Cc]onsolidated metadata.*")
            ds.to_zarr(tmp, mode="w-", compute=False, consolidated=True,
                       encoding={str(k): _codecs() for k in ds.variables},
                       write_empty_chunks=True)
        if path.exists():
            if not overwrite:
                raise ValueError(f"{path} appeared while the scan started; use another store")
            _remove_store(path)
        os.rename(tmp, path)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp)


def _is_scan_store(path: Path) -> bool:
    """Whether ``path`` holds an andoyer scan store (its metadata must be readable)."""
    if not (path / "zarr.json").is_file():
        return False
    return "scan_config" in read_metadata(path / "zarr.json").get("attributes", {})


def _remove_store(path: Path) -> None:
    try:
        ours = _is_scan_store(path)
    except DamagedFileError as exc:
        raise DamagedFileError(f"{exc}; cannot tell whether {path} is an andoyer scan "
                               "store: refusing to remove it; remove it yourself or "
                               "choose another store path") from None
    if not ours:
        raise ValueError(f"{path} exists and is not an andoyer scan store: refusing to "
                         "remove it; choose another store path")
    shutil.rmtree(path)


def _open(path: Path) -> xr.Dataset:
    for file in sorted(path.rglob("zarr.json")):
        read_metadata(file)
    try:
        return xr.open_zarr(path, consolidated=True)
    except (ValueError, KeyError, OSError) as exc:
        raise DamagedFileError(f"{path}: not a readable Zarr store ({exc})") from None


def open_store(path: str | os.PathLike[str]) -> xr.Dataset:
    """A scan store as a lazy dataset, once :func:`verify` found all its data.

    Parameters
    ----------
    path : str or os.PathLike
        The store.

    Raises
    ------
    DamagedFileError
        Naming the damaged points or files; a resume of the scan (same configuration
        and store) computes damaged points again.
    ValueError
        ``path`` is not an andoyer scan store.
    """
    path = Path(path)
    if not _is_scan_store(path):
        raise ValueError(f"{path} is not an andoyer scan store (no zarr.json with a "
                         "scan_config); give the store written by andoyer scan")
    damage = verify(path)
    if damage:
        raise DamagedFileError(
            f"{path}: {len(damage)} chunk(s) marked done have lost their data: "
            f"{damage_summary(damage)}; run the scan again with the same configuration and "
            "store to compute them again")
    return _open(path)


def _differences(old: Mapping[str, Any], new: Mapping[str, Any], prefix: str = ""
                 ) -> list[str]:
    out = []
    for k in dict.fromkeys([*old, *new]):
        a, b = old.get(k, "(absent)"), new.get(k, "(absent)")
        if isinstance(a, Mapping) and isinstance(b, Mapping):
            out += _differences(a, b, f"{prefix}{k}.")
        elif a != b:
            out.append(f"{prefix}{k}: {a!r} in the store, {b!r} now")
    return out


def check_store(path: str | os.PathLike[str], cfg: ScanConfig, *, overwrite: bool) -> None:
    """Refuse a store path the scan cannot use, before any work (nothing is written).

    Refused (``ValueError``, naming the path): a path whose folder does not exist, an
    existing file or folder that is not an andoyer scan store, and, without
    ``overwrite``, a scan store of another configuration or andoyer version; a scan
    store whose metadata is damaged raises ``DamagedFileError``.

    Parameters
    ----------
    path : str or os.PathLike
        The store.
    cfg : ScanConfig
        The scan it must belong to.
    overwrite : bool
        Whether a store of another scan may be replaced.

    Examples
    --------
    >>> import tempfile
    >>> from andoyer.scan.config import load_config
    >>> cfg = load_config({"parameters": {"mu": [0.01, 0.1], "h": 0.3},
    ...                    "task": {"kind": "section", "n_orbits": 2, "n_crossings": 3}})
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     check_store(Path(tmp) / "new.zarr", cfg, overwrite=False)  # absent: fine
    ...     check_store(tmp, cfg, overwrite=False)
    Traceback (most recent call last):
    ...
    ValueError: ... exists and is not an andoyer scan store; choose another store path
    """
    _checked(Path(path), cfg, overwrite)


def _checked(path: Path, cfg: ScanConfig, overwrite: bool) -> xr.Dataset | None:
    """:func:`check_store`; the store opened where it is resumed, else None."""
    if not path.parent.exists():
        raise ValueError(f"folder {str(path.parent)!r} of the store does not exist; create it")
    if not path.exists():
        return None
    try:
        ours = _is_scan_store(path)
    except DamagedFileError as exc:
        raise DamagedFileError(f"{exc}; the store cannot be resumed: remove it yourself "
                               "or choose another store path") from None
    if not ours:
        raise ValueError(f"{path} exists and is not an andoyer scan store; choose another "
                         "store path")
    if overwrite:
        return None
    ds = _open(path)
    old = ds.attrs.get("scan_config", "{}")
    if old != cfg.to_json():
        diff = _differences(json.loads(old), cfg.to_dict())
        raise ValueError(
            f"the store {path} was made by another configuration "
            f"({'; '.join(diff[:4]) or 'a different layout'}); use a new store path, or "
            "--overwrite (overwrite=True) to start it again")
    if ds.attrs.get("andoyer_version") != __version__:
        raise ValueError(
            f"the store {path} was written by andoyer {ds.attrs.get('andoyer_version')}, "
            f"this is {__version__}: resuming would mix results of two versions; use a new "
            "store path, or --overwrite (overwrite=True)")
    return ds


def prepare(path: Path, cfg: ScanConfig, *, overwrite: bool) -> np.ndarray | None:
    """Check an existing store against ``cfg`` (:func:`check_store`): its ``done`` mask,
    or None if absent.

    With ``overwrite`` an existing scan store is replaced when the new one is laid out
    (nothing is removed before). Leftover temporary files of an interrupted run
    (``*.partial`` of Zarr) are removed.

    Parameters
    ----------
    path : pathlib.Path
        The store.
    cfg : ScanConfig
        The scan it must belong to.
    overwrite : bool
        Whether a store of another scan may be replaced.
    """
    ds = _checked(path, cfg, overwrite)
    if ds is None:
        return None
    for partial in path.rglob("*.partial"):
        partial.unlink(missing_ok=True)
    done = np.asarray(ds["done"].values, dtype=bool)
    damage = verify(path)
    if damage:
        warnings.warn(f"{path}: {len(damage)} chunk(s) marked done have lost their data, "
                      f"computed again: {damage_summary(damage)}", DamagedStoreWarning,
                      stacklevel=3)
        for d in damage:  # unmarked first, so no reader trusts them meanwhile
            slices = cfg.block_slices(d.block)
            done[slices] = False
            shape = tuple(sl.stop - sl.start for sl in slices)
            xr.Dataset({"done": (cfg.dims, np.zeros(shape, dtype=bool))}).to_zarr(
                path, region=dict(zip(cfg.dims, slices, strict=True)), mode="r+",
                consolidated=False, write_empty_chunks=True)
    return done


def store_schema(path: Path, cfg: ScanConfig) -> Schema:
    """The schema of the task's variables, read back from an existing store.

    Parameters
    ----------
    path : pathlib.Path
        The store.
    cfg : ScanConfig
        The scan.
    """
    ds = _open(path)
    n = len(cfg.dims)
    variables = {str(k): Variable(tuple(map(str, v.dims[n:])), tuple(v.shape[n:]), v.dtype,
                                  dict(v.attrs))
                 for k, v in ds.data_vars.items() if k not in FLAGS}
    return Schema(variables, {})


def done_mask(path: Path) -> np.ndarray:
    """The ``done`` flags of a store.

    Parameters
    ----------
    path : pathlib.Path
        The store.
    """
    return np.asarray(_open(path)["done"].values, dtype=bool)


def write_chunk(path: Path, cfg: ScanConfig, schema: Schema, block: tuple[int, ...],
                points: Sequence[xr.Dataset | Empty]) -> None:
    """Write the results of one chunk into its region, then mark it done.

    Parameters
    ----------
    path : pathlib.Path
        The store.
    cfg : ScanConfig
        The scan.
    schema : Schema
        The variables of a point's result.
    block : tuple of int
        The chunk's index in the grid of chunks.
    points : sequence of xarray.Dataset or Empty
        One result per point of the chunk, in C order.
    """
    slices = cfg.block_slices(block)
    shape = tuple(s.stop - s.start for s in slices)
    if len(points) != int(np.prod(shape)):
        raise RuntimeError(f"chunk {block}: {len(points)} results for {shape} points")
    empty = np.array([isinstance(p, Empty) for p in points]).reshape(shape)
    data: dict[str, Any] = {}
    for name, v in schema.variables.items():
        arr = np.full(shape + v.shape, v.blank, dtype=v.dtype)
        flat = arr.reshape((-1, *v.shape))
        for i, p in enumerate(points):
            if isinstance(p, Empty):
                continue
            src = _lookup(p, name)
            if tuple(map(str, src.dims)) != v.dims or src.shape != v.shape:
                raise RuntimeError(
                    f"chunk {block}: variable {name!r} has dims {src.dims} {src.shape} at "
                    f"one point and {v.dims} {v.shape} in the store")
            flat[i] = src.values
        data[name] = (cfg.dims + v.dims, arr)
    data["empty"] = (cfg.dims, empty)
    region = dict(zip(cfg.dims, slices, strict=True))
    with named_when_full(path):  # a chunk cut by a full disk is not marked done
        # Every chunk is written, fill values too: a missing chunk file is then a loss.
        xr.Dataset(data).to_zarr(path, region=region, mode="r+", consolidated=False,
                                 write_empty_chunks=True)
        # Only now is the chunk complete.
        xr.Dataset({"done": (cfg.dims, np.ones(shape, dtype=bool))}).to_zarr(
            path, region=region, mode="r+", consolidated=False, write_empty_chunks=True)


def _lookup(ds: xr.Dataset, name: str) -> xr.DataArray:
    """Variable ``name`` of a point's result (``X_values`` is its coordinate ``X``)."""
    if name in ds.data_vars:
        return ds[name]
    if name.endswith("_values") and name[:-len("_values")] in ds.coords:
        return ds.coords[name[:-len("_values")]]
    raise RuntimeError(f"a point's result lacks the variable {name!r} of the store")
