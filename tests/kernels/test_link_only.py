"""Helpers compiled into their callers only (:mod:`andoyer.kernels.link_only`).

* a ``kernel_jit`` helper has a link-only library: the caller that uses it runs, the
  helper's own functions are not in the process's machine code, the caller's are;
* the Taylor kernels compiled with Numba's plain pipeline (a fresh process with an
  empty cache and the link-only pipeline switched off) give the same floats, bit for
  bit, as this process's kernels (the link-only helpers are optimised once, inside
  their entry point, instead of once per level: the same results, measured on 146
  arrays when it landed).
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
from andoyer.kernels.taylor_sections import kernel_jit

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


def test_options_name_the_pipeline() -> None:
    options = link_only.link_only_options()
    assert options["pipeline_class"] is link_only.LinkOnlyCompiler
    assert options["no_cpython_wrapper"] and options["no_cfunc_wrapper"]


ORBITS = [[0.3, 1.1, 0.2, 1.0, -0.4], [1.0, 2.0, 0.5, 0.8, 0.3], [2.0, 0.9, 1.2, 1.5, -1.0]]

RUN = """
from andoyer import RigidBody, from_andoyer
from andoyer.kernels import taylor as T
p = np.ascontiguousarray(RigidBody.paper().engine_params, dtype=float)
y0 = np.ascontiguousarray(from_andoyer({orbits}), dtype=float)
z, _ = T.propagate(y0, np.linspace(0.0, 300.0, 31), p, 1e-12, 10**7)
tc, zc, _, _ = T.locate_crossings(y0, p, 2, 0.0, 1, 20, 1e4, 1e-12, 10**7)
"""


def test_the_plain_pipeline_compiles_the_same_kernels(tmp_path: Path) -> None:
    ns: dict[str, object] = {"np": np}
    exec(RUN.format(orbits=ORBITS), ns)  # this process: the link-only helpers
    script = textwrap.dedent("""
        import numpy as np
        import andoyer.kernels.link_only as L
        L.link_only_options = lambda: {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}
    """) + RUN.format(orbits=ORBITS) + textwrap.dedent(f"""
        from andoyer.kernels import taylor_sections as S
        assert S.poly._compiler.pipeline_class is not L.LinkOnlyCompiler
        np.savez({str(tmp_path / "plain.npz")!r}, z=z, tc=tc, zc=zc)
    """)
    env = {**os.environ, "ANDOYER_CACHE_DIR": str(tmp_path / "cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    subprocess.run([sys.executable, "-c", script], check=True, env=env, timeout=600,
                   capture_output=True)
    plain = np.load(tmp_path / "plain.npz")
    assert np.isfinite(np.asarray(ns["tc"])).sum() >= 40
    for name in ("z", "tc", "zc"):
        assert np.array_equal(plain[name], np.asarray(ns[name]), equal_nan=True), name
