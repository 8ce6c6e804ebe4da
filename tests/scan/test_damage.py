"""Damaged inputs are named: scan stores, their metadata, configuration files, full disks.

A store records a CRC-32C checksum per chunk (Zarr's ``crc32c`` codec) and writes every
chunk; :func:`andoyer.scan.store.verify` checks every point marked done. A lost or
damaged point is named, computed again by a resume and refused by ``andoyer atlas``.
Truncated, non-UTF-8 and foreign files are named with what is wrong with them; a full
disk says "no space left on <path>" and leaves nothing half-written.
"""

from __future__ import annotations

import errno
import json
import random
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from andoyer.cli import main
from andoyer.errors import DamagedFileError, DamagedStoreWarning, NoSpaceError
from andoyer.scan import load_config, run_scan
from andoyer.scan.store import CHECKSUM, open_store, verify

# Three points along mu, one task each; 2 orbits x 3 crossings (seconds to run).
SMALL = {"parameters": {"mu": [0.01, 0.1, 0.3], "h": 0.3},
         "task": {"kind": "section", "n_orbits": 2, "n_crossings": 3},
         "integrator": {"engine": "numba"}}


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> Path:
    store = tmp_path_factory.mktemp("damage") / "reference.zarr"
    run_scan(SMALL, store, scheduler="serial", progress=False)
    return store


@pytest.fixture
def store(reference, tmp_path) -> Path:
    copy = tmp_path / "s.zarr"
    shutil.copytree(reference, copy)
    return copy


def _chunk(store: Path, variable: str, point: int) -> Path:
    """The chunk file of ``variable`` at the point ``mu[point]`` (task dims whole)."""
    meta = json.loads((store / variable / "zarr.json").read_text())
    rest = "/".join("0" * (len(meta["shape"]) - 1))
    return store / variable / "c" / str(point) / rest if rest else \
        store / variable / "c" / str(point)


def _data_variables(store: Path) -> list[str]:
    ds = xr.open_zarr(store)
    return [str(k) for k in ds.data_vars if "mu" in ds[k].dims and k != "done"]


def _same(a: Path, b: Path) -> None:
    da, db = xr.open_zarr(a).load(), xr.open_zarr(b).load()
    for name in da.variables:
        assert np.array_equal(da[name].values, db[name].values,
                              equal_nan=da[name].dtype.kind == "f"), name


# ---------------------------------------------------------------------- the layout
def test_every_array_has_a_checksum_and_every_chunk_is_written(reference):
    assert xr.open_zarr(reference).attrs["chunk_checksums"] == CHECKSUM
    for meta in reference.rglob("zarr.json"):
        node = json.loads(meta.read_text())
        if node.get("node_type") == "array":
            assert {"name": "crc32c"} in node["codecs"], meta
    for name in _data_variables(reference):
        for point in range(3):
            assert _chunk(reference, name, point).is_file(), (name, point)
    assert verify(reference) == []


# ---------------------------------------------------------------------- the examples
def test_atlas_refuses_a_done_point_that_lost_its_chunks(store, tmp_path, capsys):
    """Before: an empty panel, "3 of 3 points done", exit 0."""
    for name in _data_variables(store):
        _chunk(store, name, 1).unlink()
    with pytest.raises(SystemExit) as exc:
        main(["atlas", str(store), "--out", str(tmp_path / "a.png")])
    err = capsys.readouterr().err
    assert exc.value.code == 2
    assert "point mu = 0.1" in err and "is missing" in err and "run the scan again" in err
    assert not (tmp_path / "a.png").exists()


def test_garbage_chunk_bytes_are_named_not_an_internal_error(store, tmp_path, capsys):
    """Before: "internal error"."""
    _chunk(store, "theta1", 2).write_bytes(b"garbage" * 20)
    with pytest.raises(SystemExit) as exc:
        main(["atlas", str(store), "--out", str(tmp_path / "a.png")])
    err = capsys.readouterr().err
    assert exc.value.code == 2 and "internal error" not in err
    assert "point mu = 0.3: theta1 is damaged (its bytes do not match their CRC-32C" in err


@pytest.mark.parametrize("where", ["zarr.json", "theta1/zarr.json", "done/zarr.json"])
def test_a_truncated_zarr_json_is_named(store, tmp_path, capsys, where):
    """Before: a bare JSON parser message naming no file."""
    meta = store / where
    meta.write_bytes(meta.read_bytes()[:200])
    with pytest.raises(SystemExit) as exc:
        main(["atlas", str(store), "--out", str(tmp_path / "a.png")])
    assert exc.value.code == 2
    assert f"{meta}: truncated (ends after 200 bytes" in capsys.readouterr().err


def test_resume_names_and_recomputes_lost_and_damaged_points(store, reference):
    _chunk(store, "G3", 0).unlink()
    _chunk(store, "empty", 1).write_bytes(b"\x00" * 9)
    ok = _chunk(store, "theta1", 2).read_bytes()
    with pytest.warns(DamagedStoreWarning, match=r"2 chunk\(s\).*point mu = 0.01: G3 is "
                                                 r"missing.*point mu = 0.1: empty is damaged"):
        report = run_scan(SMALL, store, scheduler="serial", progress=False)
    assert (report.resumed, report.computed) == (1, 2)
    assert _chunk(store, "theta1", 2).read_bytes() == ok  # the good point untouched
    assert verify(store) == []
    _same(store, reference)
    open_store(store)


def test_full_disk_while_writing_a_chunk_leaves_it_unmarked(reference, tmp_path,
                                                            monkeypatch):
    store = tmp_path / "full.zarr"
    write = xr.Dataset.to_zarr
    calls = []

    def full(self, *args, **kwargs):
        calls.append(1)
        if len(calls) == 4:  # layout, chunk 0 data and mark, then chunk 1 data
            raise OSError(errno.ENOSPC, "No space left on device")
        return write(self, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_zarr", full)
    with pytest.raises(NoSpaceError, match=f"no space left on {store}"):
        run_scan(SMALL, store, scheduler="serial", progress=False)
    monkeypatch.setattr(xr.Dataset, "to_zarr", write)
    assert xr.open_zarr(store).done.values.tolist() == [True, False, False]
    report = run_scan(SMALL, store, scheduler="serial", progress=False)
    assert (report.resumed, report.computed) == (1, 2)
    _same(store, reference)


def test_cli_says_no_space_left_on_the_path(capsys, monkeypatch, tmp_path):
    from andoyer.io import netcdf

    def full(self, path, **kwargs):
        Path(path).write_bytes(b"half")
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", full)
    monkeypatch.setattr("andoyer.atomic.FULL_BELOW", 1 << 62)  # every disk looks full
    out = tmp_path / "o.nc"
    with pytest.raises(SystemExit) as exc:
        main(["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "1", "--n-out", "3",
              "--engine", "numba", "--out", str(out)])
    assert exc.value.code == 4
    assert f"error: no space left on {out}" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []  # nothing half-written
    assert netcdf.write_netcdf  # the writer the command used


# ---------------------------------------------------------------------- configuration
def test_non_utf8_and_foreign_configurations_name_the_file(tmp_path):
    cases = {
        "latin1.toml": '[task]\nkind = "section"\n# caf\xe9\n'.encode("latin-1"),
        "image.toml": b"\x89PNG\r\n\x1a\n" + bytes(range(256)),
        "truncated.toml": b'[parameters]\nmu = [0.01, 0.',
        "store.toml": json.dumps({"zarr_format": 3}).encode(),
    }
    for name, data in cases.items():
        (tmp_path / name).write_bytes(data)
        with pytest.raises(ValueError, match=f"^{tmp_path / name}: ") as exc:
            load_config(tmp_path / name)
        assert "codec" not in str(exc.value), str(exc.value)
    with pytest.raises(DamagedFileError, match="not UTF-8 text .byte 0xe9"):
        load_config(tmp_path / "latin1.toml")
    (tmp_path / "folder.toml").mkdir()
    with pytest.raises(ValueError, match="folder.toml' is a folder; give the scan's TOML"):
        load_config(tmp_path / "folder.toml")


# ---------------------------------------------------------------------- hunts
_CORRUPTIONS = {
    "deleted": lambda f, rng: f.unlink(),
    "emptied": lambda f, rng: f.write_bytes(b""),
    "truncated": lambda f, rng: f.write_bytes(f.read_bytes()[:rng.randrange(
        1, max(2, f.stat().st_size))]),
    "one bit flipped": lambda f, rng: _flip(f, rng),
    "replaced": lambda f, rng: f.write_bytes(rng.randbytes(f.stat().st_size)),
}


def _flip(f: Path, rng: random.Random) -> None:
    data = bytearray(f.read_bytes())
    i = rng.randrange(len(data))
    data[i] ^= 1 << rng.randrange(8)
    f.write_bytes(bytes(data))


def _corrupted(store: Path, file: Path, corrupt, rng: random.Random):
    """Context: ``file`` of ``store`` damaged by ``corrupt``, restored afterwards."""
    import contextlib

    @contextlib.contextmanager
    def damaged():
        saved = file.read_bytes()
        corrupt(file, rng)
        try:
            yield
        finally:
            file.write_bytes(saved)
    return damaged()


def test_hunt_every_chunk_of_every_done_point(store):
    """Every data variable x every kind of damage, at a random point: verify names
    exactly that point and variable (a checksum catches even one flipped bit)."""
    rng = random.Random(24)
    names = _data_variables(store)
    assert len(names) >= 10
    for name in names:
        point = rng.randrange(3)
        for kind, corrupt in _CORRUPTIONS.items():
            with _corrupted(store, _chunk(store, name, point), corrupt, rng):
                found = verify(store)
            assert [(d.block, d.variable) for d in found] == [((point,), name)], (
                name, kind, found)
            mu = (0.01, 0.1, 0.3)[point]
            assert found[0].describe().startswith(f"point mu = {mu:g}: {name} is ")
    assert verify(store) == []


def test_hunt_every_metadata_file(store):
    """Every zarr.json x every kind of damage: the store is refused naming the file;
    never a parser's bare message or an internal error."""
    rng = random.Random(7)
    for file in sorted(store.rglob("zarr.json")):
        for kind, corrupt in _CORRUPTIONS.items():
            if kind in ("deleted", "one bit flipped"):
                continue  # a deleted array is absent; a flipped bit may be valid JSON
            with _corrupted(store, file, corrupt, rng), pytest.raises(ValueError) as exc:
                verify(store)
            assert str(file) in str(exc.value), (file, kind, exc.value)
    assert verify(store) == []
