"""``import andoyer`` and ``andoyer --version`` / ``--help`` stay light: no heavy module.

What makes them slow is a heavy import: SymPy (kernels are generated only on demand,
``andoyer.kernels.generated.equations`` is committed), xarray (and pandas under it), heyoka, and
Numba (importing it, and a fortiori compiling a kernel). So each case runs in a fresh
interpreter and lists the modules it loaded; no clock is read (a time bound fails on a
loaded machine and passes a heavy import on a fast one).
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

#: Top-level packages none of the light entries may load.
HEAVY = ("sympy", "xarray", "pandas", "heyoka", "numba", "llvmlite")

#: (what is run, Python code run for it). The command-line cases call the console
#: script's own entry point (``[project.scripts] andoyer = "andoyer.cli:main"``).
CASES = {
    "import andoyer": "import andoyer",
    # the bottom layers: kernels on plain floats, H in the charts (ARCHITECTURE rule 2)
    "import andoyer.dynamics, andoyer.kernels, andoyer.charts, andoyer.body":
        "import andoyer.dynamics, andoyer.kernels, andoyer.charts, andoyer.body",
    "andoyer --version": "from andoyer.cli import main\n"
                         "try:\n    main(['--version'])\nexcept SystemExit as e:\n"
                         "    assert e.code in (0, None), e.code\n",
    "andoyer --help": "from andoyer.cli import main\n"
                      "try:\n    main(['--help'])\nexcept SystemExit as e:\n"
                      "    assert e.code in (0, None), e.code\n",
}

_REPORT = ("\nimport json, sys\n"
           "print('@@' + json.dumps(sorted({m.split('.')[0] for m in sys.modules})))\n")


def loaded_packages(code: str) -> tuple[set[str], str]:
    """Top-level packages in ``sys.modules`` after ``code`` ran in a fresh interpreter,
    and what it printed before."""
    out = subprocess.run([sys.executable, "-c", code + _REPORT], capture_output=True,
                         text=True, check=True, timeout=120)
    text, _, mods = out.stdout.rpartition("@@")
    return set(json.loads(mods)), text


@pytest.mark.parametrize("what", sorted(CASES))
def test_light_entries_load_no_heavy_module(what):
    loaded, text = loaded_packages(CASES[what])
    assert "andoyer" in loaded
    assert sorted(loaded & set(HEAVY)) == [], f"{what} loads {sorted(loaded & set(HEAVY))}"
    if what == "andoyer --help":
        assert text.startswith("usage: andoyer") and "frequencies" in text
    if what == "andoyer --version":
        import andoyer

        assert andoyer.__version__ in text


def test_the_check_sees_a_heavy_import():
    """The report is not blind: the same subprocess sees xarray when it is imported."""
    loaded, _ = loaded_packages("import andoyer\nimport xarray")
    assert {"xarray", "pandas"} <= loaded
