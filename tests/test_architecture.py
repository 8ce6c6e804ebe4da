"""Architecture rules that the import contracts (``lint-imports``) cannot express."""

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "andoyer"
#: Package-private modules: importable anywhere in andoyer (their names are public).
PRIVATE_MODULES = {"andoyer._validate", "andoyer._atomic", "andoyer._version"}


def private_crossings(sources):
    """``"mod imports _name from src"`` for every private name imported across modules."""
    out = []
    for module, text in sources:
        for node in ast.walk(ast.parse(text)):
            if not (isinstance(node, ast.ImportFrom)
                    and (node.module or "").startswith("andoyer")):
                continue
            for alias in node.names:
                name = alias.name
                if (name.startswith("_") and not name.startswith("__")
                        and node.module != module
                        and f"{node.module}.{name}" not in PRIVATE_MODULES):
                    out.append(f"{module} imports {name} from {node.module}")
    return out


def _package_sources():
    for path in sorted(SRC.rglob("*.py")):
        yield ".".join(path.relative_to(SRC.parent).with_suffix("").parts), path.read_text()


def test_no_private_name_crosses_a_module_boundary():
    assert private_crossings(_package_sources()) == []


def test_the_rule_catches_a_crossing():
    bad = [("andoyer.analysis.chaos", "from andoyer.integrate.api import _params, propagate")]
    ok = [("andoyer.x", "from andoyer._validate import finite\nfrom andoyer import __version__")]
    assert private_crossings(bad) == [
        "andoyer.analysis.chaos imports _params from andoyer.integrate.api"]
    assert private_crossings(ok) == []
