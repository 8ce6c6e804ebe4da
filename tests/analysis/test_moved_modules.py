"""The analysis modules moved into sub-packages by concept (unperturbed/, hess/,
splitting/, chaos/, paper/); their old paths work for one release, with a
DeprecationWarning, and give the very same objects."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

MOVED = {
    "euler_poinsot": "unperturbed.euler_poinsot", "equilibria": "unperturbed.equilibria",
    "fixed_points": "unperturbed.fixed_points", "separatrix": "unperturbed.separatrix",
    "portraits": "unperturbed.portraits", "hess_solution": "hess.hess_solution",
    "hess_periods": "hess.hess_periods", "pendulum": "hess.pendulum", "floquet": "hess.floquet",
    "section_map": "splitting.section_map", "periodic": "splitting.periodic",
    "manifolds": "splitting.manifolds", "melnikov": "splitting.melnikov",
    "alignment": "chaos.alignment", "chaos_border": "chaos.chaos_border",
    "frequency": "chaos.frequency", "paper_check": "paper.paper_check",
    "trajectories": "paper.trajectories",
}


@pytest.mark.parametrize(("old", "new"), sorted(MOVED.items()))
def test_an_old_module_path_warns_and_is_the_new_module(old: str, new: str) -> None:
    code = (f"import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            f"try:\n    import andoyer.analysis.{old}\n"
            f"except DeprecationWarning as w:\n    print('warned:', w)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, check=True).stdout
    assert f"andoyer.analysis.{new}" in out and "warned" in out
    with pytest.warns(DeprecationWarning):
        sys.modules.pop(f"andoyer.analysis.{old}", None)
        module = importlib.import_module(f"andoyer.analysis.{old}")
    assert module is importlib.import_module(f"andoyer.analysis.{new}")


@pytest.mark.parametrize(("old", "new", "name"), [
    ("splitting", "splitting.measure", "separatrix_splitting")])
def test_names_of_a_module_that_became_a_package_warn(old: str, new: str, name: str) -> None:
    package = importlib.import_module(f"andoyer.analysis.{old}")
    with pytest.warns(DeprecationWarning, match=f"andoyer.analysis.{new}"):
        value = getattr(package, name)
    assert value is getattr(importlib.import_module(f"andoyer.analysis.{new}"), name)
