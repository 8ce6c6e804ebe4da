"""One vocabulary (andoyer.notation.TERMS): every CLI flag is derived from the API name of
what it sets, every scan key is the API name; nothing was released, so a former spelling
is simply an unknown flag, keyword or key."""

import argparse
import inspect
import re

import pytest

from andoyer import RigidBody
from andoyer.cli import build_parser
from andoyer.notation import TERMS, VOCABULARY

#: Flags that set nothing of the API, with why.
CLI_ONLY = {
    "--out": "output file or folder", "--store": "a scan's Zarr store",
    "--body": "which preset body", "--y0": "initial Euler-Poisson state (API y0)",
    "--andoyer": "initial state in the Andoyer-Deprit chart (API y0, chart)",
    "--hess": "initial state in the Hess chart (API y0, chart)",
    "--n-out": "output times (API t)", "--mu-list": "the list of mu (API mu of "
    "separatrix_splitting; --mu is the body's)", "--no-hess-check": "skip a second run",
    "--port": "server port", "--no-browser": "server option", "--pdf": "also a PDF",
    "--max-sessions": "server option (API serve(max_sessions=))",
    "--rows": "atlas layout", "--cols": "atlas layout", "--select": "atlas slice",
    "--maps": "atlas layout", "--width": "figure size", "--scheduler": "Dask",
    "--workers": "Dask", "--overwrite": "store", "--retries": "Dask", "--dry-run": "scan",
    "--max-core-hours": "cost guard", "--max-store-gb": "cost guard",
    "--progress": "progress line", "--no-progress": "progress line",
    "--points": "paper-check sampling", "--format": "output format", "--jobs": "report",
    "--quick": "report", "--only": "report", "--engines": "report", "--version": "",
    "--no-limits": "cost guards", "--frames": "animation frames (API t)",
    "--fps": "animation frame rate", "--size": "animation frame side (px)",
    "--debug": "traceback", "--help": "",
    "--last-torus": "a mu_c(h) curve file (API critical_mu of plot_border)",
}

#: The API functions each command calls: its flags must be their parameters.
COMMAND_API = {
    "section": ("andoyer.integrate.fill:fill_section", "andoyer.integrate.api:poincare"),
    "orbit": ("andoyer.integrate.api:propagate",),
    "animate": ("andoyer.integrate.orientation:attitude",),
    "explore": ("andoyer.explore.state:make_settings",),
    "chaos-map": ("andoyer.analysis.chaos.lyapunov:chaos_map",),
    "manifolds": ("andoyer.analysis.splitting.measure:separatrix_splitting",),
    "frequencies": ("andoyer.analysis.chaos.frequency:orbit_frequencies",
                    "andoyer.analysis.chaos.frequency:frequency_map"),
    "indicators": ("andoyer.analysis.chaos.lyapunov:indicators",),
    "resonances": ("andoyer.analysis.resonance.predict:resonance_widths",
                   "andoyer.integrate.fill:fill_section", "andoyer.integrate.api:poincare",
                   "andoyer.analysis.resonance.near_centre:resonant_normal_form",
                   "andoyer.analysis.resonance.second_order:island_prediction",
                   "andoyer.analysis.resonance.normal_form:periodic_orbit_normal_form"),
    "last-torus": ("andoyer.analysis.resonance.residues:last_torus",
                   "andoyer.analysis.resonance.residues:critical_mu_curve"),
}
BODY = {"A", "B", "C", "mu", "epsilon", "r"}
#: Flags of a command that the command turns into an API argument of another name.
COMPOSED = {("orbit", "t_end"): "t = linspace(0, t_end, n_out)",
            ("animate", "t_end"): "t = linspace(0, t_end, frames)"}


def _function(path):
    import importlib

    module, name = path.split(":")
    return getattr(importlib.import_module(module), name)


def _parameters(func):
    """Name -> default of what ``func`` takes: its parameters, and the fields of those whose
    default is a frozen specification (``chaos_map(grid=MapGrid(), run=IndicatorRun())``:
    ``n``, ``t_end``, ... are terms of the table, grouped)."""
    import dataclasses

    out = {}
    for name, p in inspect.signature(func).parameters.items():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        out[name] = p.default
        if dataclasses.is_dataclass(p.default) and not isinstance(p.default, type):
            out.update({f.name: getattr(p.default, f.name)
                        for f in dataclasses.fields(p.default)})
    return out


def _commands():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return parser, sub.choices


def _visible(p):
    for a in p._actions:
        if a.help == argparse.SUPPRESS or not a.option_strings:
            continue
        yield a


def test_every_flag_is_the_api_name_or_cli_only():
    _, commands = _commands()
    for name, p in commands.items():
        for a in _visible(p):
            flag = max(a.option_strings, key=len)
            assert len(a.option_strings) == 1 or "-h" in a.option_strings, (name, a)
            if flag in CLI_ONLY:
                continue
            assert a.dest in VOCABULARY, f"andoyer {name} {flag}: not in notation.TERMS"
            assert flag == VOCABULARY[a.dest].flag, (name, flag, VOCABULARY[a.dest].flag)


@pytest.mark.parametrize("command", sorted(COMMAND_API))
def test_command_flags_are_parameters_of_the_api_it_calls(command):
    _, commands = _commands()
    if command not in commands:
        pytest.skip(f"no command {command}")
    params = set()
    for path in COMMAND_API[command]:
        params |= set(_parameters(_function(path)))
    for a in _visible(commands[command]):
        flag = max(a.option_strings, key=len)
        if flag in CLI_ONLY or a.dest in BODY or (command, a.dest) in COMPOSED:
            continue
        assert a.dest in params, f"andoyer {command} {flag} sets {a.dest!r}, not a " \
                                 f"parameter of {COMMAND_API[command]}"


def test_scan_keys_are_api_names():
    from andoyer.scan.config import PARAMETERS
    from andoyer.scan.tasks import TASKS

    keys = {t.config: t for t in TERMS if t.config}
    for p in PARAMETERS:
        assert p in keys and keys[p].api == p
    for kind in TASKS.values():
        for key in kind.options:
            assert key in keys and keys[key].api == key, (kind.name, key)
    assert {"engine", "rtol", "atol", "tol"} <= set(keys)   # [integrator]
    # the section task's keys are fill_section's and poincare's parameters
    from andoyer.integrate.api import poincare
    from andoyer.integrate.fill import fill_section

    api = set(inspect.signature(fill_section).parameters) | set(
        inspect.signature(poincare).parameters)
    assert set(TASKS["section"].options) <= api


def test_scan_dims_are_described_in_the_words_of_the_table():
    from andoyer.scan.config import PARAMETER_ATTRS

    for name, (_symbol, long_name, _eq, _units) in PARAMETER_ATTRS.items():
        assert long_name == VOCABULARY[name].meaning, name


def test_energy_flag_is_not_next_to_help():
    """--h (energy) sat beside -h (help): the flag is --energy."""
    parser, commands = _commands()
    for name in ("section", "chaos-map", "explore"):
        flags = {s for a in _visible(commands[name]) for s in a.option_strings}
        assert "--energy" in flags and "--h" not in flags


@pytest.mark.parametrize("argv, dest, value, old, new", [
    (["section", "--h", "0.25"], "h", 0.25, "--h", "--energy"),
    (["section", "--area", "0.1"], "M", 0.1, "--area", "--M"),
    (["section", "--orbits", "7"], "n_orbits", 7, "--orbits", "--n-orbits"),
    (["section", "--crossings", "9"], "n_crossings", 9, "--crossings", "--n-crossings"),
    (["explore", "--crossings", "9"], "n_crossings", 9, "--crossings", "--n-crossings"),
    (["chaos-map", "--h", "0.3"], "h", 0.3, "--h", "--energy"),
])
def test_former_flags_are_refused_and_the_flags_work(capsys, argv, dest, value, old, new):
    parser = build_parser()
    with pytest.raises(SystemExit) as exc:  # refused; --h abbreviates --help: the usage
        parser.parse_args(argv)
    out = capsys.readouterr()
    assert (exc.value.code == 2 and old in out.err) or (
        old == "--h" and exc.value.code == 0 and out.out.startswith("usage:"))
    new_args = parser.parse_args([argv[0], new, argv[2]])
    assert getattr(new_args, dest) == value
    assert capsys.readouterr().err == ""
    text = parser._subparsers._group_actions[0].choices[argv[0]].format_help()
    assert not re.search(rf"{old}(?![\w-])", text)


def test_former_api_keywords_are_refused():
    from andoyer.integrate.fill import fill_section

    body = RigidBody.paper()
    new = fill_section(body, 0.2466, 0.0, ("g", 0.0), n_orbits=6, sampling="sobol",
                       boundary_grid=40)
    assert new.sizes["orbit"] > 0
    with pytest.raises(TypeError, match="unexpected keyword argument 'method'"):
        fill_section(body, 0.2466, 0.0, ("g", 0.0), n_orbits=6, method="sobol")


def test_former_scan_keys_are_unknown_keys():
    from andoyer.scan.config import parse_config

    base = {"parameters": {"mu": [0.01, 0.02], "h": 0.25},
            "integrator": {"engine": "numba"}}
    new = parse_config({**base, "task": {"kind": "section", "n_orbits": 3,
                                         "n_crossings": 5}})
    assert new == parse_config({**base, "task": {"kind": "section", "n_orbits": 3,
                                                 "n_crossings": 5}})
    with pytest.raises(ValueError, match="unknown key 'orbits'.*n_orbits"):
        parse_config({**base, "task": {"kind": "section", "orbits": 3, "crossings": 5}})


def test_scan_tol_is_both_tolerances():
    from andoyer.scan.config import parse_config

    base = {"parameters": {"mu": [0.01, 0.02], "h": 0.25},
            "task": {"kind": "section", "n_orbits": 3, "n_crossings": 5}}
    cfg = parse_config({**base, "integrator": {"engine": "numba", "tol": 1e-10}})
    assert (cfg.integrator.rtol, cfg.integrator.atol) == (1e-10, 1e-10)
    with pytest.raises(ValueError, match="not tol and rtol"):
        parse_config({**base, "integrator": {"engine": "numba", "tol": 1e-10, "rtol": 1e-9}})


def test_guide_shows_the_vocabulary():
    from pathlib import Path

    guide = Path(__file__).resolve().parents[1] / "docs" / "guide.md"
    rows = [r for r in guide.read_text().splitlines() if r.startswith("| `")]
    for t in TERMS:
        assert "|" not in t.meaning, t  # a table cell
        assert any(r.startswith(f"| `{t.api}` | `{t.flag}` |") for r in rows), t


#: Defaults that differ on purpose between a command or a scan task and the API function it
#: calls, with why; any other difference fails (a default measures what the API measures).
DEFAULTS_ON_PURPOSE = {
    ("chaos-map", "n"): "the shell's map is a picture, 128 x 128; the API's 64 suits scripts",
    ("explore", "body"): "the same body: the CLI names the paper's preset",
    ("resonances", "order_mu"): "0: no normal form in mu unless asked (seconds per chain); "
                                "the API's default is 2 (3 adds the stencil of (S1'), "
                                "some 3x the time)",
    ("resonances", "n_orbits"): "0: no section drawn under the chains unless asked (the "
                                "prediction itself integrates nothing)",
    ("resonances", "degree"): "0: no normal form of the section map unless asked (it "
                              "integrates; the API's 5 is the degree when it is)",
    ("resonances", "order"): "0: no normal form unless asked (the API's 8 is the degree "
                             "when it is)",
    ("scan:section", "n_orbits"): "a grid of points: fewer orbits per point (cost)",
    ("scan:section", "sampling"): "sobol: a prefix of the sequence is spread over the plane",
    ("scan:section", "boundary_grid"): "a grid of points: a coarser boundary search (cost)",
    ("scan:chaos_map", "n"): "the same 64 x 64, written as a pair",
    ("scan:chaos_border", "section"): "the same section, written as text",
    ("scan:chaos_border", "n"): "32 x 32 per point of an (epsilon, mu) grid",
}


def test_defaults_agree_with_the_api_or_say_why():
    from andoyer.scan.tasks import TASKS

    _, commands = _commands()
    found = set()
    pairs = [(cmd, COMMAND_API[cmd], {a.dest: a.default for a in _visible(p)})
             for cmd, p in commands.items() if cmd in COMMAND_API]
    scan_api = {"section": ("andoyer.integrate.fill:fill_section",),
                "chaos_map": ("andoyer.analysis.chaos.lyapunov:chaos_map",),
                "splitting": ("andoyer.analysis.splitting.measure:separatrix_splitting",),
                "chaos_border": ("andoyer.analysis.chaos.border:chaos_border",)}
    pairs += [(f"scan:{k}", paths, {n: o.default for n, o in TASKS[k].options.items()})
              for k, paths in scan_api.items()]
    for where, paths, defaults in pairs:
        for path in paths:
            for name, default in _parameters(_function(path)).items():
                if name in defaults and default is not inspect.Parameter.empty \
                        and default != defaults[name]:
                    found.add((where, name))
    assert found == set(DEFAULTS_ON_PURPOSE), found ^ set(DEFAULTS_ON_PURPOSE)
