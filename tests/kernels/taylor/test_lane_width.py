"""The lane count (:func:`andoyer.kernels.simd.lane_width`): chosen from the CPU, set by
``ANDOYER_LANES``, part of the lane kernels' cache key, and without effect on the
results beyond round-off; so the lanes' tuning (:func:`andoyer.kernels.simd.lane_tuning`:
an Intel model's scheduling on AMD Zen, ``ANDOYER_LANE_TUNE``).

* the choice: AVX-512 8, AVX/AVX2 4, else 2; the variable overrides it; a bad value is
  refused naming the variable;
* the tuning: ``haswell`` on ``znver*``, else the CPU's own; the variable overrides it;
* the cache keys of the lane entry points name the width and the tuning;
* (slow) a process with another width (4 here where the CPU has 8, else 8) gives the
  same steps (``info``) and, to round-off, the same states, tangent vectors and
  crossings (G3 = 0 and theta2 = 0) as this process: each lane's arithmetic does not
  depend on how many lanes run beside it.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from andoyer.kernels import simd
from andoyer.kernels.taylor import lane_crossings, lanes


def test_the_width_follows_the_cpu_unless_set() -> None:
    assert simd.lane_width({}, {"avx512f": True, "avx2": True, "avx": True}) == 8
    assert simd.lane_width({}, {"avx512f": False, "avx2": True, "avx": True}) == 4
    assert simd.lane_width({}, {"avx": True}) == 4
    assert simd.lane_width({}, {"sse2": True}) == 2
    assert simd.lane_width({"ANDOYER_LANES": " 16 "}, {"avx2": True}) == 16
    assert simd.lane_width({"ANDOYER_LANES": ""}, {"avx512f": True}) == 8
    for bad in ("3", "eight", "-4"):
        with pytest.raises(ValueError, match="ANDOYER_LANES"):
            simd.lane_width({"ANDOYER_LANES": bad}, {})
    assert simd.LANES in simd.WIDTHS
    if not os.environ.get(simd.LANES_ENV):
        assert simd.LANES == simd.lane_width()


def test_the_tuning_follows_the_cpu_unless_set() -> None:
    assert simd.lane_tuning({}, "znver4") == simd.lane_tuning({}, "znver2") == "haswell"
    assert simd.lane_tuning({}, "skylake-avx512") == simd.lane_tuning({}, "haswell") == ""
    assert simd.lane_tuning({"ANDOYER_LANE_TUNE": "host"}, "znver4") == ""
    assert simd.lane_tuning({"ANDOYER_LANE_TUNE": " x86-64 "}, "znver4") == "x86-64"
    assert simd.lane_tuning({"NUMBA_CPU_NAME": "znver3"}) == "haswell"
    if not os.environ.get(simd.TUNE_ENV):
        assert simd.TUNE == simd.lane_tuning()


def test_the_width_and_tuning_key_the_lane_caches() -> None:
    for stamp in (lanes.LANES_STAMP, lane_crossings.LANE_CROSSINGS_STAMP):
        assert stamp.endswith(f"-lanes{simd.LANES}-tune{simd.TUNE}")


_RUN = textwrap.dedent("""
    import sys
    import numpy as np
    from andoyer import RigidBody
    from andoyer.kernels import simd
    from andoyer.kernels.taylor import lane_crossings, lanes
    rng = np.random.default_rng(3)
    n = 21
    gamma = rng.normal(size=(n, 3))
    gamma /= np.linalg.norm(gamma, axis=1, keepdims=True)
    y0 = np.ascontiguousarray(np.hstack([rng.normal(size=(n, 3)), gamma]))
    z0 = np.ascontiguousarray(np.hstack([y0, rng.normal(size=(n, 6))]))
    p = np.asarray(RigidBody.paper().engine_params, dtype=float)
    t = np.linspace(0.0, 50.0, 6)
    z, zi = lanes.propagate(z0, t, p, 15, 10**7, threads=1)
    a = lane_crossings.locate_crossings(y0, p, 2, 0.0, 0, 10, 300.0, 1e-12, 10**7, threads=1)
    b = lane_crossings.locate_crossings(y0, p, 13, 0.0, 1, 10, 300.0, 1e-12, 10**7, threads=1)
    np.savez(sys.argv[1], lanes=simd.LANES, z=z, zi=zi, at=a[0], ay=a[1], ac=a[2], ai=a[3],
             bt=b[0], by=b[1], bc=b[2], bi=b[3])
""")


def _run(out: Path, width: int) -> dict[str, np.ndarray]:
    env = {**os.environ, simd.LANES_ENV: str(width)}
    subprocess.run([sys.executable, "-c", _RUN, str(out)], env=env, check=True,
                   timeout=900, capture_output=True)
    with np.load(out) as f:
        return dict(f)


@pytest.mark.slow
def test_results_agree_across_lane_widths(tmp_path: Path) -> None:
    other = 4 if simd.LANES != 4 else 8
    here = _run(tmp_path / "here.npz", simd.LANES)
    there = _run(tmp_path / "there.npz", other)
    assert int(here["lanes"]) == simd.LANES and int(there["lanes"]) == other
    for key in ("zi", "ac", "ai", "bc", "bi"):  # steps, statuses, crossing counts
        np.testing.assert_array_equal(here[key], there[key], err_msg=key)
    assert here["ac"].sum() > 100 and here["bc"].sum() > 100
    for key in ("z", "at", "ay", "bt", "by"):
        np.testing.assert_array_equal(np.isnan(here[key]), np.isnan(there[key]))
        scale = 1.0 + np.abs(here[key])
        assert np.nanmax(np.abs(here[key] - there[key]) / scale) < 1e-11, key
