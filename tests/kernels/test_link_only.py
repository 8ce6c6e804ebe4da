"""Helpers compiled into their callers only (:mod:`andoyer.kernels.link_only`).

* a ``kernel_jit`` helper has a link-only library: the caller that uses it runs, the
  helper's own functions are not in the process's machine code, the caller's are; the
  DOP853 and Taylor helpers are link-only and refuse a Python call;
* the Taylor and the DOP853 kernels compiled with Numba's plain pipeline (a fresh
  process with an empty cache and the link-only pipeline switched off) give the same
  floats, bit for bit, as this process's kernels (the link-only helpers are optimised
  once, inside their entry point, instead of once per level: the same results,
  measured on 150 Taylor and 207 DOP853 arrays when it landed).
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numba
import numpy as np
import pytest

from andoyer.kernels import link_only
from andoyer.kernels.common import kernel_jit
from andoyer.kernels.dop853 import attitude, flow, stepper, tangent
from andoyer.kernels.taylor import jets

pytestmark = pytest.mark.skipif(not link_only.supported(),
                                reason="this Numba lacks the internals link_only uses")


def test_a_helper_is_linked_into_its_caller_and_emits_no_code() -> None:
    @kernel_jit
    def helper(x: float) -> float:
        return 2.0 * x + 1.0

    @numba.njit
    def caller(x: float) -> float:
        return helper(x) * 3.0

    assert caller(1.5) == 12.0
    (own,) = helper.overloads.values()
    (user,) = caller.overloads.values()
    assert isinstance(own.library, link_only.LinkOnlyLibrary)
    engine = own.library.codegen._engine
    assert not engine.is_symbol_defined(own.fndesc.mangled_name)
    assert engine.is_symbol_defined(user.fndesc.mangled_name)
    with pytest.raises(TypeError, match="compiled kernels only"):
        helper(1.5)


@pytest.mark.parametrize("helper", [flow.ep_rhs, tangent.tangent_rhs, attitude.attitude_rhs,
                                    stepper._section, jets.horner])
def test_the_kernels_helpers_are_link_only(helper: object) -> None:
    # The DOP853 stepper's helpers and fields, and the Taylor helpers: compiled into the
    # entry points only (W4 cold first call on numba 8.3-8.9 -> 4.5 s CPU), no Python entry.
    assert helper._compiler.pipeline_class is link_only.LinkOnlyCompiler  # type: ignore[attr-defined]
    with pytest.raises(TypeError, match="compiled kernels only"):
        helper(0.0, np.zeros(6), np.zeros(8), np.zeros(6))  # type: ignore[operator]


def test_options_name_the_pipeline() -> None:
    options = link_only.link_only_options()
    assert options["pipeline_class"] is link_only.LinkOnlyCompiler
    assert options["no_cpython_wrapper"] and options["no_cfunc_wrapper"]


ORBITS = [[0.3, 1.1, 0.2, 1.0, -0.4], [1.0, 2.0, 0.5, 0.8, 0.3], [2.0, 0.9, 1.2, 1.5, -1.0]]

RUN = """
from andoyer import RigidBody, from_andoyer
from andoyer.kernels.dop853 import flow as D
from andoyer.kernels.taylor import flow as T
p = np.ascontiguousarray(RigidBody.paper().engine_params, dtype=float)
y0 = np.ascontiguousarray(from_andoyer({orbits}), dtype=float)
if {taylor}:
    z, _ = T.propagate(y0, np.linspace(0.0, 300.0, 31), p, 1e-12, 10**7)
    tc, zc, _, _ = T.locate_crossings(y0, p, 2, 0.0, 1, 20, 1e4, 1e-12, 10**7)
    out = dict(z=z, tc=tc, zc=zc)
else:
    zd, _ = D.EP_FLOW.propagate(y0, np.linspace(0.0, 300.0, 31), p, 1e-12, 1e-12, 10**7)
    out = dict(zd=zd)
"""


def plain_pipeline_arrays(tmp_path: Path, taylor: bool) -> tuple[dict[str, object], object]:
    """This process's arrays (link-only helpers), and the same computed in a fresh
    process with an empty cache and Numba's plain pipeline."""
    ns: dict[str, object] = {"np": np}
    run = RUN.format(orbits=ORBITS, taylor=taylor)
    exec(run, ns)  # this process: the link-only helpers
    script = textwrap.dedent("""
        import numpy as np
        import andoyer.kernels.link_only as L
        L.link_only_options = lambda: {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}
    """) + run + textwrap.dedent(f"""
        from andoyer.kernels.dop853 import stepper
        from andoyer.kernels.taylor import sections as S
        assert S.poly._compiler.pipeline_class is not L.LinkOnlyCompiler
        assert stepper._section._compiler.pipeline_class is not L.LinkOnlyCompiler
        np.savez({str(tmp_path / "plain.npz")!r}, **out)
    """)
    env = {**os.environ, "ANDOYER_CACHE_DIR": str(tmp_path / "cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    subprocess.run([sys.executable, "-c", script], check=True, env=env, timeout=600,
                   capture_output=True)
    return ns["out"], np.load(tmp_path / "plain.npz")  # type: ignore[return-value]


def test_the_plain_pipeline_compiles_the_same_taylor_kernels(tmp_path: Path) -> None:
    mine, plain = plain_pipeline_arrays(tmp_path, taylor=True)
    assert np.isfinite(np.asarray(mine["tc"])).sum() >= 40
    for name in ("z", "tc", "zc"):
        assert np.array_equal(plain[name], mine[name], equal_nan=True), name


def test_the_plain_pipeline_compiles_the_same_dop853_kernels(tmp_path: Path) -> None:
    mine, plain = plain_pipeline_arrays(tmp_path, taylor=False)
    assert np.all(np.isfinite(np.asarray(mine["zd"])))
    assert np.array_equal(plain["zd"], mine["zd"], equal_nan=True)
