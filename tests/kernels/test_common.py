"""What the integration methods share (:mod:`andoyer.kernels.common`), defined once.

* ``MEGNO_DELTA`` is assigned in one module of the package, and every engine's tangent
  code reads that one value: the numba, taylor and scipy engines (and heyoka where it
  is installed) give the same MEGNO quadrature over a flight so short that the shift
  dominates it (a second definition that drifted would change it at O(1));
* the tangent layout and the status codes;
* importing the module loads no Numba.
"""

from __future__ import annotations

import ast
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import andoyer
from andoyer import RigidBody
from andoyer.integrate.engines import get_engine
from andoyer.integrate.engines.base import Tolerance
from andoyer.kernels import common

SRC = Path(andoyer.__file__).parent


def _assignments(name: str) -> list[str]:
    """The modules of the package that assign ``name`` at module level."""
    found = []
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in tree.body:
            targets = (node.targets if isinstance(node, ast.Assign)
                       else [node.target] if isinstance(node, ast.AnnAssign) else [])
            if any(isinstance(t, ast.Name) and t.id == name for t in targets):
                found.append(path.relative_to(SRC).as_posix())
    return found


def test_megno_delta_is_defined_once() -> None:
    assert _assignments("MEGNO_DELTA") == ["kernels/common.py"]
    from andoyer.integrate import variational
    from andoyer.integrate.engines import scipy_engine
    from andoyer.kernels.dop853 import tangent
    from andoyer.kernels.taylor import tangent as taylor_tangent

    for module in (variational, scipy_engine, tangent, taylor_tangent):
        assert module.MEGNO_DELTA is common.MEGNO_DELTA, module.__name__


ENGINES = ["numba", "taylor", "scipy"] + (["heyoka"] if importlib.util.find_spec("heyoka")
                                           else [])


def test_every_engine_uses_the_one_megno_delta() -> None:
    """``megno_num = int_0^t (s + delta) f ds ~ f (delta t + t^2 / 2)`` over ``t =
    delta``: two thirds of it are the shift's, so an engine with another delta (2e-6:
    +67 %, 0: -67 %) fails; the engines agree to 1e-9 (measured)."""
    body = RigidBody.paper(0.3)
    y0 = np.array([0.1, 0.7, 0.2, 0.3, 0.4, np.sqrt(0.75)])
    w0 = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    t = np.array([0.0, common.MEGNO_DELTA])
    num = {}
    for name in ENGINES:
        flow = get_engine(name).tangent(y0, w0, body.engine_params, Tolerance(),
                                        t=t, renormalise=True, scale=1.0)
        num[name] = float(flow.megno[0, -1, 0])
    reference = num["numba"]
    assert reference != 0.0
    for name, value in num.items():
        assert value == pytest.approx(reference, rel=1e-6, abs=0.0), (name, num)


def test_the_tangent_layout_fits_the_dimension() -> None:
    for k in range(1, common.MAX_VECTORS + 1):
        L = common.layout(k)
        assert common.n_vectors(common.dimension(k)) == k
        assert L["megno_int"] == common.dimension(k) - 1
        assert L["rho"].stop == L["megno_num"]
    with pytest.raises(ValueError, match="not a tangent state"):
        common.n_vectors(common.dimension(common.MAX_VECTORS + 1))


def test_every_status_has_a_message() -> None:
    codes = (common.SUCCESS, common.STEP_TOO_SMALL, common.MAX_STEPS)
    assert len(set(codes)) == 3 and set(common.STATUS_MESSAGES) == set(codes)
    assert common.INFO[0] == "status"


def test_the_module_loads_no_numba() -> None:
    code = ("import sys, json\nimport andoyer.kernels.common\n"
            "print(json.dumps(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('numba', 'llvmlite'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert json.loads(out.stdout.strip().splitlines()[-1]) == []
