"""The analysis sub-packages re-export the functions and classes of their modules: the
natural ``from andoyer.analysis.splitting import separatrix_splitting`` works, warns
nothing, and gives the very object of the defining module. Nothing was released, so no old
path is kept (``andoyer.analysis.separatrix`` and the like do not import)."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import subprocess
import sys
import warnings

import pytest

import andoyer.analysis

PACKAGES = sorted(m.name for m in pkgutil.iter_modules(andoyer.analysis.__path__) if m.ispkg)


def _defined(package: str) -> dict[str, str]:
    """``name -> module`` of every function and class a module of ``package`` defines and
    lists in its ``__all__``."""
    pkg = importlib.import_module(f"andoyer.analysis.{package}")
    out: dict[str, str] = {}
    for info in pkgutil.iter_modules(pkg.__path__):
        full = f"{pkg.__name__}.{info.name}"
        module = importlib.import_module(full)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if (inspect.isfunction(obj) or inspect.isclass(obj)) and obj.__module__ == full:
                out[name] = full
    return out


def test_the_sub_packages_are_the_seven_concepts():
    assert PACKAGES == ["chaos", "hess", "paper", "resonance", "space", "splitting",
                        "unperturbed"]


@pytest.mark.parametrize("package", PACKAGES)
def test_a_package_re_exports_what_its_modules_define(package):
    pkg = importlib.import_module(f"andoyer.analysis.{package}")
    modules = {info.name for info in pkgutil.iter_modules(pkg.__path__)}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name, module in _defined(package).items():
            if name in modules:
                # a module named like its function: the package's attribute is the module
                # (issue 33 item 4 renames these modules)
                assert name not in pkg.__all__, name
                continue
            assert name in pkg.__all__, f"andoyer.analysis.{package} does not export {name}"
            assert getattr(pkg, name) is getattr(importlib.import_module(module), name)
    assert sorted(pkg.__all__) == sorted(set(pkg.__all__)), "a name listed twice"


def test_the_natural_imports_warn_nothing_in_a_fresh_interpreter():
    code = ("from andoyer.analysis.splitting import separatrix_splitting\n"
            "from andoyer.analysis.chaos import chaos_map, sali, naff\n"
            "from andoyer.analysis.hess import floquet_multipliers\n"
            "from andoyer.analysis.unperturbed import separatrix_energy\n"
            "from andoyer.analysis.paper import fig3_trajectories\n"
            "from andoyer.analysis.space import axis_trace\n"
            "from andoyer.analysis.resonance import resonance_widths\n"
            "print(separatrix_splitting.__module__)\n")
    out = subprocess.run([sys.executable, "-W", "error", "-c", code], capture_output=True,
                         text=True, timeout=300, check=True)
    assert out.stdout.strip() == "andoyer.analysis.splitting.measure" and out.stderr == ""


@pytest.mark.parametrize("old", ["separatrix", "melnikov", "chaos_border", "hess_solution",
                                 "paper_check", "frequency", "alignment"])
def test_no_old_flat_path_is_kept(old):
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(f"andoyer.analysis.{old}")
