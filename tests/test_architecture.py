"""Architecture rules that the import contracts (``lint-imports``) cannot express.

No private name crosses a module boundary: ``from andoyer.x import _y`` is refused outside
``andoyer.x``, and a private module (``andoyer.cli._common``) is imported only from inside
its own package. ``andoyer._version`` is the one private module open to every layer.
"""

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "andoyer"
#: Private modules that every andoyer module may import.
OPEN_PRIVATE_MODULES = {"andoyer._version"}
#: Today's offenders, ``"importer imports name from module"``; empty this list, do not grow it.
ALLOWED: set[str] = set()


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _private_module_crossing(importer: str, target: str) -> bool:
    """``target`` has a private part and ``importer`` lies outside the package holding it."""
    if target in OPEN_PRIVATE_MODULES:
        return False
    parts = target.split(".")
    for k, part in enumerate(parts):
        if _private(part):
            package = ".".join(parts[:k])
            return not (importer + ".").startswith(package + ".")
    return False


def private_crossings(sources):
    """``"mod imports name from src"`` for every private name or module used across modules."""
    out = []
    for module, text in sources:
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Import):
                out += [f"{module} imports {a.name}" for a in node.names
                        if a.name.startswith("andoyer")
                        and _private_module_crossing(module, a.name)]
            if not (isinstance(node, ast.ImportFrom)
                    and (node.module or "").startswith("andoyer")):
                continue
            src = node.module or ""
            for alias in node.names:
                name = alias.name
                if ((_private(name) and src != module
                     and f"{src}.{name}" not in OPEN_PRIVATE_MODULES)
                        or _private_module_crossing(module, src)):
                    out.append(f"{module} imports {name} from {src}")
    return out


def _package_sources():
    for path in sorted(SRC.rglob("*.py")):
        parts = path.relative_to(SRC.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        yield ".".join(parts), path.read_text()


def test_no_private_name_crosses_a_module_boundary():
    assert set(private_crossings(_package_sources())) <= ALLOWED


def test_the_rule_catches_a_crossing():
    bad = [("andoyer.analysis.chaos.indicators",
            "from andoyer.integrate.api import _params, propagate"),
           ("andoyer.explore.ui", "from andoyer.cli._common import floats"),
           ("andoyer.explore.ui", "import andoyer.cli._common")]
    ok = [("andoyer.x", "from andoyer.validation import finite\nfrom andoyer import __version__"),
          ("andoyer.cli.orbit", "from andoyer.cli._common import floats"),
          ("andoyer.cli", "from andoyer.cli._common import floats"),
          ("andoyer.report.paper", "from andoyer._version import __version__")]
    assert private_crossings(bad) == [
        "andoyer.analysis.chaos.indicators imports _params from andoyer.integrate.api",
        "andoyer.explore.ui imports floats from andoyer.cli._common",
        "andoyer.explore.ui imports andoyer.cli._common"]
    assert private_crossings(ok) == []


def test_the_engine_contract_covers_every_module_outside_the_engines():
    """The import contract "outside integrate.engines nothing imports heyoka or an engine
    module" lists its sources by name: every package and integrate module must be there."""
    import tomllib

    root = Path(__file__).resolve().parents[1]
    config = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))
    contract = next(c for c in config["tool"]["importlinter"]["contracts"]
                    if c["name"].startswith("Outside integrate.engines"))
    sources = set(contract["source_modules"])
    src = root / "src" / "andoyer"
    expected = {f"andoyer.{p.name}" for p in src.iterdir()
                if p.is_dir() and (p / "__init__.py").exists() and p.name != "integrate"}
    expected |= {f"andoyer.integrate.{p.stem}" for p in (src / "integrate").glob("*.py")
                 if p.stem != "__init__"}
    expected |= {f"andoyer.{p.stem}" for p in src.glob("*.py")
                 if p.stem in {"body", "dynamics"}}
    assert expected <= sources, sorted(expected - sources)
