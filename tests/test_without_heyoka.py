"""Where heyoka is missing (no wheel), every module imports, orbits, sections, the chaos
indicators, periodic orbits and Floquet multipliers run: orbits, sections and tangent flows
on the taylor engine (the default without heyoka), and what needs heyoka says so clearly."""

import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent("""
    import sys
    sys.modules["heyoka"] = None  # as if it were not installed
    import importlib, pkgutil, warnings
    import numpy as np
    import andoyer
    for m in pkgutil.walk_packages(andoyer.__path__, "andoyer."):
        if not m.name.endswith("__main__"):
            importlib.import_module(m.name)
    from andoyer import RigidBody
    from andoyer.integrate import poincare, propagate
    from andoyer.integrate.engines import default_engine_name
    from andoyer.integrate.engines.base import Capability
    assert default_engine_name() == "taylor"
    assert default_engine_name(Capability.TANGENT) == "taylor"
    body = RigidBody.paper()
    ds = propagate(body, [0.3, 0, 0.3, 1, 0], [0, 1, 2], chart="andoyer")
    assert ds.attrs["engine"] == "taylor" and abs(ds.H_drift).max() < 1e-12
    ds = poincare(body, [0.3, 0, 0.3, 1, 0], "theta2=0", 3, chart="andoyer")
    assert int(ds.crossings_found[0]) == 3
    from andoyer.analysis.chaos.lyapunov import indicators
    ds = indicators(body, [0.3, 0, 0.3, 1, 0], 5.0, chart="andoyer")
    assert ds.attrs["engine"] == "taylor" and sys.modules["heyoka"] is None
    from andoyer.analysis.chaos.alignment import alignment_indices
    ds = alignment_indices(body, [0.3, 0, 0.3, 1, 0], 5.0, chart="andoyer", k=3)
    assert float(ds.gali.isel(orbit=0, time=-1)) > 0
    import math
    from andoyer.analysis.splitting.periodic import RotationSection, rotation_energy, rotation_orbit
    orb = rotation_orbit(body, rotation_energy(body), 0.0, RotationSection(0.0, 1))
    assert abs(orb.multipliers[0] / math.exp(2 * math.pi * body.sigma / body.c) - 1) < 1e-9
    from andoyer.analysis.hess.floquet import floquet_multipliers
    assert floquet_multipliers(body, 5 * body.mu).stability == "hyperbolic"
    print("ok")
""")


def test_andoyer_without_heyoka():
    proc = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.strip().endswith("ok")
