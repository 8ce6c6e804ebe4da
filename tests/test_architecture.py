"""Architecture rules that the import contracts (``lint-imports``) cannot express.

No private name crosses a module boundary: ``from andoyer.x import _y`` is refused outside
``andoyer.x``, and a private module (``andoyer.cli._common``) is imported only from inside
its own package. ``andoyer._version`` is the one private module open to every layer.
"""

import ast
import re
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
    bad = [("andoyer.analysis.chaos.lyapunov",
            "from andoyer.integrate.api import _params, propagate"),
           ("andoyer.explore.ui", "from andoyer.cli._common import floats"),
           ("andoyer.explore.ui", "import andoyer.cli._common")]
    ok = [("andoyer.x", "from andoyer.validation import finite\nfrom andoyer import __version__"),
          ("andoyer.cli.orbit", "from andoyer.cli._common import floats"),
          ("andoyer.cli", "from andoyer.cli._common import floats"),
          ("andoyer.report.paper", "from andoyer._version import __version__")]
    assert private_crossings(bad) == [
        "andoyer.analysis.chaos.lyapunov imports _params from andoyer.integrate.api",
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


# --- tests mirror src/ ---------------------------------------------------------------------
#
# ``src/andoyer/a/b.py`` is tested by ``tests/a/test_b.py`` (a private ``_b.py`` by
# ``test_b.py``, a package's ``__init__.py`` by ``tests/a/test_a.py``); more files of one
# module's tests go beside it (``test_b_<aspect>.py``). A package ``__init__.py`` that only
# re-exports needs no test of its own. Every other module is listed here with where it is
# tested; a module that gets its mirrored test leaves the table (a stale entry fails).

TESTS = Path(__file__).resolve().parent
#: Module (path under src/andoyer) -> the test file that exercises it, or "doctest" (its
#: examples run by ``pytest --doctest-modules src``: the module must have ``>>>`` examples).
COVERED_ELSEWHERE: dict[str, str] = {
    "__init__.py": "test_public_api.py",
    "__main__.py": "test_processes.py",
    "_version.py": "test_public_api.py",
    "errors.py": "cli/test_cli_errors.py",
    "analysis/chaos/tangent_space.py": "analysis/chaos/test_lyapunov.py",
    "analysis/hess/reduced.py": "analysis/hess/test_solution.py",
    "analysis/paper/trajectories.py": "report/test_paper.py",
    "analysis/resonance/torus.py": "analysis/resonance/test_predict.py",
    "analysis/resonance/second_order.py": "analysis/resonance/test_predict.py",
    "analysis/space/lagrange.py": "analysis/space/test_inertial.py",
    "analysis/unperturbed/portraits.py": "analysis/unperturbed/test_separatrix.py",
    "charts/andoyer_deprit.py": "charts/test_charts.py",
    "charts/euler_poisson.py": "charts/test_charts.py",
    "charts/hess.py": "charts/test_charts.py",
    "cli/__init__.py": "cli/test_cli_errors.py",
    "cli/_common.py": "cli/test_output_files.py",
    "cli/atlas.py": "scan/test_scan.py",
    "cli/chaos_map.py": "cli/test_cli_coverage.py",
    "cli/explore.py": "explore/test_explore.py",
    "cli/frequencies.py": "cli/test_cli_coverage.py",
    "cli/indicators.py": "cli/test_cli_coverage.py",
    "cli/manifolds.py": "cli/test_cli_coverage.py",
    "cli/orbit.py": "cli/test_cli_errors.py",
    "cli/paper.py": "report/test_paper.py",
    "cli/paper_check.py": "report/test_paper.py",
    "cli/scan.py": "scan/test_scan.py",
    "cli/section.py": "cli/test_cli_coverage.py",
    "explore/base.py": "explore/test_explore.py",
    "explore/export.py": "explore/test_explore.py",
    "explore/layout.py": "explore/test_explore.py",
    "explore/orbits.py": "explore/test_explore.py",
    "explore/seeds.py": "explore/test_explore.py",
    "explore/server.py": "explore/test_explore_e2e.py",
    "explore/state.py": "explore/test_explore.py",
    "explore/ui.py": "explore/test_explore.py",
    "integrate/budget.py": "test_guards.py",
    "integrate/plane_sampling.py": "integrate/test_fill.py",
    "integrate/variational.py": "integrate/test_tangent.py",
    "io/netcdf.py": "integrate/test_api.py",
    "plot/atlas.py": "scan/test_scan.py",
    "plot/border.py": "plot/test_layout.py",
    "plot/chaos.py": "analysis/chaos/test_lyapunov.py",
    "plot/fig3.py": "report/test_paper.py",
    "plot/solutions.py": "report/test_paper.py",
    "plot/style.py": "plot/test_layout.py",
    "report/__init__.py": "report/test_paper.py",
    "report/base.py": "report/test_paper.py",
    "report/html.py": "report/test_paper.py",
    "report/items/__init__.py": "report/test_schedule.py",
    "report/items/perturbed.py": "report/test_report_e2e.py",
    "report/items/hess.py": "report/test_paper.py",
    "report/items/resonance.py": "cli/test_resonances.py",
    "report/items/unperturbed.py": "report/test_report_e2e.py",
    "scan/config.py": "scan/test_scan.py",
    "scan/cost.py": "test_guards.py",
    "scan/run.py": "scan/test_scan.py",
    "scan/store.py": "scan/test_scan.py",
    "scan/tasks.py": "scan/test_scan.py",
    "symbolic/hamiltonian.py": "analysis/hess/test_solution.py",
    "kernels/simd.py": "kernels/taylor/test_lanes.py",
    "kernels/taylor/lane_sections.py": "kernels/taylor/test_lane_crossings.py",
    "kernels/dop853/attitude.py": "integrate/test_orientation.py",
    "kernels/dop853/coefficients.py": "kernels/dop853/test_flow.py",
    "kernels/dop853/fields.py": "symbolic/test_codegen.py",
    "kernels/dop853/stepper.py": "kernels/dop853/test_flow.py",
    "kernels/generated/equations.py": "symbolic/test_codegen.py",
    "kernels/generated/recurrences.py": "symbolic/test_taylor_codegen.py",
}
#: Folders whose modules are all tested in one test folder. integrate/engines/ is being
#: reorganised (issue 33 item 2): its tests stay in tests/integrate/engines (the engine
#: contract suite runs every engine module) until the move settles and the entry becomes
#: per-module rows of COVERED_ELSEWHERE.
COVERED_BY_FOLDER: dict[str, str] = {
    "integrate/engines/": "integrate/engines/",
}


#: What a package ``__init__.py`` that only re-exports may hold besides imports: the names
#: of its table of lazy re-exports and the module functions that serve it.
REEXPORT_NAMES = {"__all__", "EXPORTS", "_LAZY"}
REEXPORT_FUNCTIONS = {"__getattr__", "__dir__"}


def _only_reexports(path: Path) -> bool:
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Import | ast.ImportFrom):
            continue
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):
            continue  # the docstring
        if isinstance(node, ast.If) and getattr(node.test, "id", "") == "TYPE_CHECKING":
            continue
        if isinstance(node, ast.FunctionDef) and node.name in REEXPORT_FUNCTIONS:
            continue
        targets = (node.targets if isinstance(node, ast.Assign)
                   else [node.target] if isinstance(node, ast.AnnAssign) else [])
        # ``__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)`` serves the table too
        names = [e for t in targets for e in (t.elts if isinstance(t, ast.Tuple) else [t])]
        if names and all(getattr(t, "id", "") in REEXPORT_NAMES | REEXPORT_FUNCTIONS
                         for t in names):
            continue
        return False
    return True


def mirrored_test(module: str) -> str:
    """``"a/b.py"`` -> ``"a/test_b.py"`` (paths under src/andoyer and tests/)."""
    parts = module.removesuffix(".py").split("/")
    if parts[-1] == "__init__":
        name = parts[-2] if len(parts) > 1 else "andoyer"
    else:
        name = parts[-1].lstrip("_")
    return "/".join([*parts[:-1], f"test_{name}.py"])


def untested_modules():
    """Modules with neither a mirrored test file nor a row saying where they are tested."""
    missing = []
    for path in sorted(SRC.rglob("*.py")):
        module = path.relative_to(SRC).as_posix()
        if (TESTS / mirrored_test(module)).exists() or module in COVERED_ELSEWHERE:
            continue
        if path.name == "__init__.py" and _only_reexports(path):
            continue
        folder = next((f for f in COVERED_BY_FOLDER if module.startswith(f)), None)
        if folder is not None and (TESTS / COVERED_BY_FOLDER[folder]).is_dir():
            continue
        missing.append(module)
    return missing


def test_every_module_has_its_mirrored_test_or_a_row_saying_where_it_is_tested():
    assert untested_modules() == [], (
        "add tests/<mirrored path>/test_<module>.py, or a row of COVERED_ELSEWHERE")


def test_the_covered_elsewhere_table_is_true():
    """Each row names a module that exists, has no mirrored test yet, and a test file that
    exists (or doctest examples)."""
    stale = []
    for module, where in COVERED_ELSEWHERE.items():
        path = SRC / module
        if not path.exists():
            stale.append(f"{module}: no such module")
        elif (TESTS / mirrored_test(module)).exists():
            stale.append(f"{module}: has {mirrored_test(module)}, drop the row")
        elif path.name == "__init__.py" and _only_reexports(path):
            stale.append(f"{module}: only re-exports, drop the row")
        elif where == "doctest":
            if ">>> " not in path.read_text(encoding="utf-8"):
                stale.append(f"{module}: no doctest examples")
        elif not (TESTS / where).is_file():
            stale.append(f"{module}: no {where}")
    assert stale == []


def test_the_mirror_rule_catches_an_untested_module(tmp_path, monkeypatch):
    src = tmp_path / "andoyer"
    (src / "pkg").mkdir(parents=True)
    (src / "pkg" / "__init__.py").write_text('"""Doc."""\nfrom .a import f\n__all__ = ["f"]\n')
    (src / "pkg" / "a.py").write_text("def f(): pass\n")
    (src / "pkg" / "_b.py").write_text("def g(): pass\n")
    (tmp_path / "tests" / "pkg").mkdir(parents=True)
    (tmp_path / "tests" / "pkg" / "test_b.py").write_text("")
    monkeypatch.setitem(globals(), "SRC", src)
    monkeypatch.setitem(globals(), "TESTS", tmp_path / "tests")
    monkeypatch.setitem(globals(), "COVERED_ELSEWHERE", {})
    assert untested_modules() == ["pkg/a.py"]
    (tmp_path / "tests" / "pkg" / "test_a.py").write_text("")
    assert untested_modules() == []


def test_a_lazy_reexport_table_is_only_reexports(tmp_path):
    lazy = ('"""Doc."""\nfrom typing import TYPE_CHECKING\n'
            "from andoyer.analysis._exports import lazy_exports\n"
            "if TYPE_CHECKING:\n    from .a import f as f\n"
            'EXPORTS = {"f": "a"}\n__all__ = sorted(EXPORTS)\n'
            "__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)\n")
    (tmp_path / "lazy.py").write_text(lazy)
    (tmp_path / "more.py").write_text(lazy + "x, __dir__ = 1, 2\n")
    assert _only_reexports(tmp_path / "lazy.py")
    assert not _only_reexports(tmp_path / "more.py")


def modules_named_like_their_functions(sources):
    """``"module defines name"`` for every module whose last name part is a public
    function or class it defines or lists in ``__all__``: ``from package import name``
    would then give the module or the function depending on what was imported before."""
    out = []
    for module, text in sources:
        name = module.rsplit(".", 1)[-1]
        if _private(name):
            continue
        tree = ast.parse(text)
        defined = {n.name for n in tree.body
                   if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)}
        for node in tree.body:
            if isinstance(node, ast.Assign) and any(
                    isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets) \
                    and isinstance(node.value, ast.List | ast.Tuple):
                defined |= {e.value for e in node.value.elts if isinstance(e, ast.Constant)}
        if name in defined:
            out.append(f"{module} defines {name}")
    return out


#: Modules named like a function they export: none (``andoyer.scan``'s function is
#: ``run_scan``; ``andoyer scan`` stays the command's name). The list is exact: do not grow it.
NAMED_LIKE_A_FUNCTION: set[str] = set()


def test_no_module_is_named_like_a_function_it_exports():
    assert set(modules_named_like_their_functions(_package_sources())) == NAMED_LIKE_A_FUNCTION


def test_the_name_rule_catches_a_module_named_like_its_function():
    bad = [("andoyer.analysis.chaos.indicators", "def indicators(body):\n    pass\n"),
           ("andoyer.a.b", "__all__ = ['b']\nfrom andoyer.c import b\n")]
    ok = [("andoyer.analysis.chaos.lyapunov", "def indicators(body):\n    pass\n"),
          ("andoyer.a._b", "def _b():\n    pass\n")]
    assert modules_named_like_their_functions(bad) == [
        "andoyer.analysis.chaos.indicators defines indicators", "andoyer.a.b defines b"]
    assert modules_named_like_their_functions(ok) == []


# --- no history in the tree ----------------------------------------------------------------
#
# Nothing is released: no module only redirects an old path, no keyword, flag or key is kept
# under a former name with a DeprecationWarning; dates, commit hashes and "x -> y ms"
# measurement histories go to benchmarks/NOTES.md and commit messages.

#: A date, a commit hash named as such, a timing history ("0.59 -> 0.05 s").
HISTORY = re.compile(r"20[0-9]{2}-[01][0-9]-[0-3][0-9]|\bcommit [0-9a-f]{7}"
                     r"|(->|→) ?[0-9.]+ ?(ms|s|ns|us|µs)\b")
#: Shims: a module replacing itself in sys.modules, a deprecation warning.
SHIM = re.compile(r"sys\.modules\[__name__\] *=|DeprecationWarning|FutureWarning")


def history_lines(texts):
    """``"path:line: text"`` of every history line (dates, hashes, timings) or shim."""
    out = []
    for path, text in texts:
        for k, line in enumerate(text.splitlines(), 1):
            if SHIM.search(line) or HISTORY.search(line):
                out.append(f"{path}:{k}: {line.strip()}")
    return out


def test_no_history_and_no_shims_in_src():
    texts = [(p.relative_to(SRC).as_posix(), p.read_text(encoding="utf-8"))
             for p in sorted(SRC.rglob("*.py"))]
    assert history_lines(texts) == []


def test_the_history_rule_sees_dates_timings_and_shims():
    bad = [("a.py", "# measured 2026-11-27"), ("b.py", "# jet 0.9 -> 0.7 ms"),
           ("c.py", "sys.modules[__name__] = importlib.import_module('x')"),
           ("d.py", "warnings.warn('old', DeprecationWarning)"),
           ("e.py", "# since commit 41dea64"), ("kernels/g.py", "# 1.0 -> 0.8 s")]
    ok = [("f.py", "# mu -> 0 limit"), ("kernels/h.py", "# see benchmarks/NOTES.md#threads")]
    assert len(history_lines(bad)) == 6 and history_lines(ok) == []
