"""The analysis sub-packages' lazy re-exports: the two lists of each ``__init__`` agree,
a name is kept after its first use, and nothing heavy loads before it is asked for."""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
from pathlib import Path

import pytest

from andoyer.analysis._exports import lazy_exports

ANALYSIS = Path(__file__).resolve().parents[2] / "src" / "andoyer" / "analysis"
PACKAGES = sorted(p.parent.name for p in ANALYSIS.glob("*/__init__.py"))


def static_imports(path: Path) -> dict[str, str]:
    """Name -> module of the imports under ``if TYPE_CHECKING:`` (what mypy sees)."""
    out = {}
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.If) and getattr(node.test, "id", "") == "TYPE_CHECKING":
            for imp in node.body:
                assert isinstance(imp, ast.ImportFrom), ast.dump(imp)
                for alias in imp.names:
                    assert alias.asname == alias.name, "an explicit re-export: 'x as x'"
                    out[alias.name] = imp.module or ""
    return out


@pytest.mark.parametrize("name", PACKAGES)
def test_what_mypy_sees_is_what_runs(name):
    """The ``TYPE_CHECKING`` imports and ``EXPORTS`` name the same objects; that each is
    what its module defines is ``tests/analysis/test_analysis.py``'s."""
    pkg = importlib.import_module(f"andoyer.analysis.{name}")
    static = static_imports(ANALYSIS / name / "__init__.py")
    assert static == {k: f"andoyer.analysis.{name}.{m}" for k, m in pkg.EXPORTS.items()}
    assert pkg.__all__ == sorted(pkg.EXPORTS)
    assert set(pkg.EXPORTS) <= set(dir(pkg))
    with pytest.raises(AttributeError, match=f"andoyer.analysis.{name}' has no attribute"):
        _ = pkg.no_such_name


def test_the_check_catches_a_name_missing_from_the_static_imports(tmp_path):
    init = tmp_path / "__init__.py"
    init.write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                    "    from andoyer.x.a import f as f\nEXPORTS = {'f': 'a', 'g': 'a'}\n")
    assert static_imports(init) == {"f": "andoyer.x.a"}  # != the EXPORTS: g is missing


def test_a_name_is_kept_after_its_first_use():
    ns = sys.modules["andoyer.analysis.space"].__dict__
    get, _ = lazy_exports("andoyer.analysis.space", {"lagrange_top": "lagrange"})
    ns.pop("lagrange_top", None)
    value = get("lagrange_top")
    assert ns["lagrange_top"] is value


def test_a_light_module_does_not_load_its_siblings():
    """The CLI's argument parser reads analysis.chaos.registry: not lyapunov, xarray."""
    code = ("import sys, andoyer.analysis.chaos.registry\n"
            "print('andoyer.analysis.chaos.lyapunov' in sys.modules, 'xarray' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "False"]
