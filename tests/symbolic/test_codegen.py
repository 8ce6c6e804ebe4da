"""The committed kernels are still what the symbolic layer generates (that the import stays
light: tests/test_light_imports.py).

``andoyer.kernels.generated.equations`` is committed so that ``import andoyer`` never runs SymPy.
Here it is regenerated in memory (well, in a temporary file) from
:mod:`andoyer.symbolic` and both versions are evaluated at random points: if someone
edits H, a chart map or the generated file by hand without regenerating, this fails.
"""

from __future__ import annotations

import importlib.util
import inspect
from types import ModuleType

import numpy as np
import pytest

from andoyer.kernels.generated import equations as committed
from andoyer.symbolic.codegen import KERNELS, generate_source

NPTS = 100


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory: pytest.TempPathFactory) -> ModuleType:
    path = tmp_path_factory.mktemp("codegen") / "regenerated_kernels.py"
    path.write_text(generate_source())
    spec = importlib.util.spec_from_file_location("regenerated_kernels", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def kernel_names(module: ModuleType) -> list[str]:
    return sorted(name for name, obj in vars(module).items()
                  if inspect.isfunction(obj) and obj.__module__ == module.__name__)


def random_args(names: list[str], rng: np.random.Generator, n: int) -> list[np.ndarray]:
    """Random values for kernel arguments, by name, inside each chart's regular domain."""
    G = np.exp(rng.uniform(-1.0, 1.0, n))
    s1, s2 = rng.uniform(0.05, 0.95, (2, n))
    values = {
        "G1": rng.normal(size=n), "G2": rng.normal(size=n), "G3": rng.normal(size=n),
        "gamma1": rng.normal(size=n), "gamma2": rng.normal(size=n),
        "gamma3": rng.normal(size=n),
        "l": rng.uniform(0, 2 * np.pi, n), "g": rng.uniform(0, 2 * np.pi, n),
        "G": G, "L": G * (2 * s1 - 1), "M": G * (2 * s2 - 1),
        "theta1": rng.uniform(0, 4 * np.pi, n), "theta2": rng.uniform(0, 2 * np.pi, n),
        "J2": G, "J1": G * s1, "J3": G * (2 * s2 - 1),
        "a": rng.uniform(0.2, 1.0, n), "b": rng.uniform(0.2, 1.0, n),
        "c": rng.uniform(0.2, 1.0, n), "mu": rng.uniform(0.0, 2.0, n),
        "e1": rng.normal(size=n), "e2": rng.normal(size=n), "e3": rng.normal(size=n),
        "phi0": rng.uniform(-np.pi, np.pi, n),
        **{f"q{i}": rng.normal(size=n) for i in range(4)},
    }
    return [values[name] for name in names]


def as_columns(out) -> np.ndarray:
    cols = out if isinstance(out, tuple) else (out,)
    return np.stack(np.broadcast_arrays(*[np.asarray(c, dtype=float) for c in cols]))


def test_same_kernels_as_symbolic_layer(regenerated):
    assert kernel_names(committed) == kernel_names(regenerated)
    assert set(KERNELS) <= set(kernel_names(committed))
    for name, (args, _, _) in KERNELS.items():
        params = list(inspect.signature(getattr(committed, name)).parameters)
        assert params == [str(a) for a in args], name
    assert committed.SECTION_KINDS == regenerated.SECTION_KINDS
    assert committed.EXTRA_SECTION_KINDS == regenerated.EXTRA_SECTION_KINDS


def assert_same(a, b, rtol: float) -> None:
    a, b = as_columns(a), as_columns(b)
    assert a.shape == b.shape
    assert np.all(np.isfinite(a))
    for row_a, row_b in zip(a, b, strict=True):
        np.testing.assert_allclose(row_a, row_b, rtol=rtol,
                                   atol=rtol * float(np.abs(row_b).max()))


@pytest.mark.parametrize("name", [n for n in kernel_names(committed) if n != "section"])
def test_committed_kernel_matches_regenerated(regenerated, name):
    mine, fresh = getattr(committed, name), getattr(regenerated, name)
    names = list(inspect.signature(mine).parameters)
    assert list(inspect.signature(fresh).parameters) == names
    args = random_args(names, np.random.default_rng(list(name.encode())), NPTS)
    assert as_columns(mine(*args)).shape[-1] == NPTS
    assert_same(mine(*args), fresh(*args), rtol=1e-14)


ALL_KINDS = committed.SECTION_KINDS + committed.EXTRA_SECTION_KINDS


@pytest.mark.parametrize("kind", ALL_KINDS)
def test_committed_section_matches_regenerated(regenerated, kind):
    index = ALL_KINDS.index(kind)
    names = list(inspect.signature(committed.section).parameters)
    assert names == list(inspect.signature(regenerated.section).parameters)
    assert names[0] == "kind"
    rng = np.random.default_rng(list(kind.encode()))
    args = random_args([n for n in names[1:] if n not in ("value", "cv", "sv")], rng, NPTS)
    value = rng.uniform(-1.0, 1.0, NPTS)
    args += [value, np.cos(value), np.sin(value)]
    assert_same(committed.section(index, *args), regenerated.section(index, *args),
                rtol=1e-14)


@pytest.fixture(scope="module")
def numba_kernels() -> ModuleType:
    pytest.importorskip("numba")
    import andoyer.kernels.dop853.fields as nk

    return nk


def test_numba_exports_the_generated_kernels(numba_kernels):
    assert set(KERNELS) <= set(numba_kernels.__all__)


@pytest.mark.parametrize("name", sorted(KERNELS))
def test_numba_kernels_agree_with_numpy(numba_kernels, name):
    fast, ref = getattr(numba_kernels, name), getattr(committed, name)
    names = list(inspect.signature(ref).parameters)
    args = random_args(names, np.random.default_rng(17), 20)
    for k in range(20):
        point = [float(v[k]) for v in args]
        assert_same(fast(*point), ref(*point), rtol=1e-13)
