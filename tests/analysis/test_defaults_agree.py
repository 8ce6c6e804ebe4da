"""Functions that measure the same thing have the same defaults, and the names of what they
return say what it is (issue 29: the first hour of a new user)."""

import importlib
import inspect
import math
import pkgutil

import numpy as np
import pytest

import andoyer.analysis
from andoyer import RigidBody
from andoyer.analysis.splitting.measure import separatrix_splitting, splitting_vs_epsilon
from andoyer.analysis.splitting.melnikov import melnikov_off_hess, melnikov_rho
from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_frequencies
from andoyer.analysis.unperturbed.separatrix import DEFAULT_BRANCH


def _functions_with_a_branch():
    """Every analysis module of the sub-packages, as ``module.function``."""
    for info in pkgutil.walk_packages(andoyer.analysis.__path__, "andoyer.analysis."):
        mod = importlib.import_module(info.name)
        if info.ispkg:
            continue
        for name in getattr(mod, "__all__", ()):
            f = getattr(mod, name)
            if callable(f) and not inspect.isclass(f):
                p = inspect.signature(f).parameters.get("branch")
                if p is not None and isinstance(p.default, str):
                    yield f"{info.name.rsplit('.', 1)[1]}.{name}", p.default


def test_every_branch_default_is_the_hess_separatrix():
    found = dict(_functions_with_a_branch())
    # (splitting.py is splitting/measure.py since the analysis sub-packages)
    assert {"measure.separatrix_splitting", "measure.splitting_vs_epsilon",
            "melnikov.melnikov_off_hess", "melnikov.melnikov_function"} <= set(found)
    assert set(found.values()) == {DEFAULT_BRANCH} == {"theta1=0"}, found
    from andoyer.scan.tasks import TASKS

    assert TASKS["splitting"].options["branch"].default == DEFAULT_BRANCH


def test_splitting_of_a_turned_body_measures_the_hess_separatrix_at_its_own_mu():
    """The issue's example: a body turned off the Hess direction, no branch, no mu list:
    the Hess separatrix theta1 = 0 at the body's own mu = 0.01, as splitting_vs_epsilon
    and melnikov_off_hess measure it (their first-order amplitude, independently)."""
    eps, mu = 0.1, 0.01
    body = RigidBody.near_hess(2.5, 2, 2.2, mu=mu, epsilon=eps)
    sp = separatrix_splitting(body, n_phase=8, progress=False)["splitting"]
    assert sp.attrs["branch"] == "theta1=0" and list(sp.mu.values) == [mu]
    hess = RigidBody.paper(mu)
    rho = melnikov_rho(hess, 1.0)
    # theta1 = 0 splits by mu 2 (pi rho / sinh pi rho) |sin eps| / (c G); theta1 = 4 phi0
    # would give |sin(2 phi0 + eps)| in place of |sin eps| (about 9 times more here).
    want = mu * 2 * math.pi * rho / math.sinh(math.pi * rho) * abs(math.sin(eps)) / hess.c
    assert float(sp.amplitude_melnikov[0]) == pytest.approx(want, rel=1e-6)
    assert abs(math.sin(2 * hess.phi0 + eps)) > 5 * abs(math.sin(eps))
    assert float(sp.relative_error[0]) < 0.1                     # measured, to first order
    off = np.max(np.abs(melnikov_off_hess(hess, eps, np.linspace(0, 2 * math.pi, 65))))
    assert float(sp.melnikov_function_max) == pytest.approx(off, rel=1e-3)
    sig = inspect.signature(splitting_vs_epsilon).parameters
    assert sig["mu"].default is None and sig["branch"].default == "theta1=0"


def test_mu_list_defaults_to_the_body_and_zero_is_refused_naming_it():
    with pytest.raises(ValueError, match=r"the body's mu = 0.0"):
        separatrix_splitting(RigidBody.paper(0.0))


def test_splitting_names_say_what_they_are():
    """``amplitude_melnikov`` is a predicted splitting (mu max|M| / (c G));
    ``melnikov_function_max`` is max|M| of the Melnikov function itself."""
    body = RigidBody.hess(2.5, 1.0, 1.6, mu=0.01)
    sp = separatrix_splitting(body, branch="theta1=4phi0", n_phase=8, delta=1e-4,
                              progress=False)["splitting"]
    assert "melnikov_amplitude" not in sp.variables
    np.testing.assert_allclose(sp.amplitude_melnikov.values,
                               sp.mu.values * float(sp.melnikov_function_max) / body.c,
                               rtol=1e-6)
    assert "prediction of the splitting amplitude" in sp.amplitude_melnikov.long_name
    assert "Melnikov function itself" in sp.melnikov_function_max.long_name


def test_frequency_ratio_and_the_section_rotation_number():
    """omega_g / omega_l is not the section map's rotation number: both, named."""
    f = euler_poinsot_frequencies(RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0)), 0.21, 1.0)
    assert f.frequency_ratio * f.rotation_number_g_section == pytest.approx(1.0, rel=1e-15)
    assert not hasattr(f, "rotation_number")  # one name each, no ambiguous third
