"""Helpers compiled into their callers only (:mod:`andoyer.kernels.link_only`).

* a ``kernel_jit`` helper has a link-only library: the caller that uses it runs, the
  helper's own functions are not in the process's machine code, the caller's are; the
  DOP853 and Taylor helpers are link-only and refuse a Python call;
* the pipeline is used on the tested Numba releases only (the installed one is on the
  list), and ``ANDOYER_LINK_ONLY=0`` turns it off; off, or on another Numba, the helpers
  are plain Numba functions, silently;
* the fallback: the Taylor and the DOP853 kernels compiled in a fresh process with an
  empty cache and ``ANDOYER_LINK_ONLY=0`` (Numba's own pipeline) give the same floats,
  bit for bit, as this process's link-only kernels.
"""

from __future__ import annotations

import json
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

needs_link_only = pytest.mark.skipif(not link_only.enabled(),
                                     reason="link-only pipeline off in this process")


def test_the_installed_numba_is_a_tested_release() -> None:
    """A new Numba is tested (this file) before it joins TESTED_NUMBA; until then the
    helpers fall back to plain Numba functions."""
    assert link_only.numba_release() in link_only.TESTED_NUMBA, (
        f"Numba {numba.__version__} is not in link_only.TESTED_NUMBA: run "
        "tests/kernels/test_link_only.py with it and add it")
    assert link_only.supported()


@needs_link_only
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


@needs_link_only
@pytest.mark.parametrize("helper", [flow.ep_rhs, tangent.tangent_rhs, attitude.attitude_rhs,
                                    stepper._section, jets.horner])
def test_the_kernels_helpers_are_link_only(helper: object) -> None:
    # The DOP853 stepper's helpers and fields, and the Taylor helpers: compiled into the
    # entry points only, no Python entry.
    assert helper._compiler.pipeline_class is link_only.LinkOnlyCompiler  # type: ignore[attr-defined]
    with pytest.raises(TypeError, match="compiled kernels only"):
        helper(0.0, np.zeros(6), np.zeros(8), np.zeros(6))  # type: ignore[operator]


@needs_link_only
def test_options_name_the_pipeline() -> None:
    options = link_only.link_only_options()
    assert options["pipeline_class"] is link_only.LinkOnlyCompiler
    assert options["no_cpython_wrapper"] and options["no_cfunc_wrapper"]


PROBE = """
import json, warnings
warnings.simplefilter("error")
{before}
from andoyer.kernels import link_only as L
from andoyer.kernels.common import kernel_jit
import numba

@kernel_jit
def helper(x):
    return 2.0 * x + 1.0

@numba.njit
def caller(x):
    return helper(x) * 3.0

print(json.dumps({{"enabled": L.enabled(), "supported": L.supported(),
                   "compiler": L.LinkOnlyCompiler is not None,
                   "options": sorted(L.link_only_options()), "value": caller(1.5),
                   "pipeline": helper._compiler.pipeline_class.__name__}}))
"""


def probe(tmp_path: Path, before: str = "", **env: str) -> tuple[dict[str, object], str]:
    """A fresh process's view of the switch and a helper's compilation; and its stderr."""
    environ = {**os.environ, "ANDOYER_CACHE_DIR": str(tmp_path / "cache"), **env}
    run = subprocess.run([sys.executable, "-c", PROBE.format(before=before)],
                         capture_output=True, text=True, env=environ, timeout=300)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1]), run.stderr


@pytest.mark.parametrize("value", ["0", "off", "False", "no"])
def test_the_switch_turns_the_pipeline_off(tmp_path: Path, value: str) -> None:
    out, err = probe(tmp_path, ANDOYER_LINK_ONLY=value)
    assert out["supported"] and not out["enabled"] and not out["compiler"]
    assert out["options"] == ["no_cfunc_wrapper", "no_cpython_wrapper"]
    assert out["pipeline"] != "LinkOnlyCompiler" and out["value"] == 12.0
    assert err == ""


def test_the_switch_left_on_keeps_the_pipeline(tmp_path: Path) -> None:
    out, _ = probe(tmp_path, ANDOYER_LINK_ONLY="1")
    assert out["enabled"] and out["pipeline"] == "LinkOnlyCompiler" and out["value"] == 12.0


def test_an_untested_numba_falls_back_silently(tmp_path: Path) -> None:
    """Another Numba release: Numba's private methods are not touched (no subclass is
    built), the helpers compile through Numba's own pipeline, and nothing is printed
    or warned (warnings are errors in the probe)."""
    out, err = probe(tmp_path, before="import numba\nnumba.__version__ = '0.99.0'")
    assert not out["supported"] and not out["enabled"] and not out["compiler"]
    assert out["pipeline"] != "LinkOnlyCompiler" and out["value"] == 12.0
    assert err == ""


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
    tcd, ycd, _, _ = D.EP_FLOW.locate_crossings(y0, p, 2, 0.0, 1, 20, 1e4, 1e-12, 1e-12,
                                                10**7)
    out = dict(zd=zd, tcd=tcd, ycd=ycd)
"""


def plain_pipeline_arrays(tmp_path: Path, taylor: bool) -> tuple[dict[str, object], object]:
    """This process's arrays (link-only helpers where enabled), and the same computed in
    a fresh process with an empty cache and the switch off (Numba's own pipeline)."""
    ns: dict[str, object] = {"np": np}
    run = RUN.format(orbits=ORBITS, taylor=taylor)
    exec(run, ns)  # this process: the link-only helpers
    script = "import numpy as np\n" + run + textwrap.dedent(f"""
        import andoyer.kernels.link_only as L
        from andoyer.kernels.dop853 import stepper
        from andoyer.kernels.taylor import sections as S
        assert not L.enabled() and L.LinkOnlyCompiler is None
        assert S.poly._compiler.pipeline_class.__name__ != "LinkOnlyCompiler"
        assert stepper._section._compiler.pipeline_class.__name__ != "LinkOnlyCompiler"
        np.savez({str(tmp_path / "plain.npz")!r}, **out)
    """)
    env = {**os.environ, "ANDOYER_CACHE_DIR": str(tmp_path / "cache"),
           link_only.SWITCH_ENV: "0"}
    env.pop("NUMBA_CACHE_DIR", None)
    subprocess.run([sys.executable, "-c", script], check=True, env=env, timeout=600,
                   capture_output=True)
    return ns["out"], np.load(tmp_path / "plain.npz")  # type: ignore[return-value]


def same_bits(a: object, b: object) -> bool:
    """The same floats bit for bit (NaN payloads and signed zeros included)."""
    x, y = np.asarray(a), np.asarray(b)
    return x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes()


def test_the_fallback_compiles_the_same_taylor_kernels(tmp_path: Path) -> None:
    mine, plain = plain_pipeline_arrays(tmp_path, taylor=True)
    assert np.isfinite(np.asarray(mine["tc"])).sum() >= 40
    for name in ("z", "tc", "zc"):
        assert same_bits(plain[name], mine[name]), name


def test_the_fallback_compiles_the_same_dop853_kernels(tmp_path: Path) -> None:
    mine, plain = plain_pipeline_arrays(tmp_path, taylor=False)
    assert np.all(np.isfinite(np.asarray(mine["zd"])))
    assert np.isfinite(np.asarray(mine["tcd"])).sum() >= 40
    for name in ("zd", "tcd", "ycd"):
        assert same_bits(plain[name], mine[name]), name
