"""Every shell command of the documentation runs (README.md and docs/**/*.md).

The commands are read from the ```sh / ```bash blocks (and MyST ``{code-block} sh``)
and from the inline ```andoyer ...``` spans of the text. Every ``andoyer`` command must
parse with the CLI's own parser (a flag the CLI does not have fails here); every fenced
command is run in a temporary folder, as written or with smaller sizes, as the table
``HOW`` says. A command new to the docs fails :func:`test_every_fenced_command_is_run`
until ``HOW`` says how it is run.
"""

from __future__ import annotations

import os
import re
import shlex
import signal
import subprocess
import sys
import tomllib
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from andoyer.cli import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
FENCE = re.compile(r"^(?P<f>`{3,}|~{3,})[ \t]*(?:\{code-block\}[ \t]*)?(?P<lang>sh|bash|shell"
                   r"|console)[ \t]*\n(?P<body>.*?)^(?P=f)[ \t]*$", re.M | re.S)
INLINE = re.compile(r"(?<!`)`(andoyer [^`\n]+)`(?!`)")


def doc_files() -> list[Path]:
    """README.md and the pages of the site (not the build output)."""
    pages = [p for p in sorted((ROOT / "docs").rglob("*.md")) if "_build" not in p.parts]
    return [ROOT / "README.md", *pages]


def fenced_commands() -> dict[str, list[str]]:
    """``command -> pages`` of every line of a shell block, comments stripped."""
    found: dict[str, list[str]] = {}
    for page in doc_files():
        for block in FENCE.finditer(page.read_text(encoding="utf-8")):
            for line in block["body"].splitlines():
                command = line.split("#")[0].strip()
                if command:
                    found.setdefault(command, []).append(str(page.relative_to(ROOT)))
    return found


def inline_commands() -> dict[str, list[str]]:
    """``command -> pages`` of every inline ```andoyer ...``` span."""
    found: dict[str, list[str]] = {}
    for page in doc_files():
        for span in INLINE.finditer(page.read_text(encoding="utf-8")):
            found.setdefault(span[1].strip(), []).append(str(page.relative_to(ROOT)))
    return found


# A scan of 2 x 1 points of 2 orbits x 10 crossings (seconds): what the atlas commands draw.
TINY_SCAN = """
[body]
kind = "hess"
name = "paper"
[parameters]
mu = [0.01, 0.1]
h = 0.25
[task]
kind = "section"
section = "theta2=0"
n_orbits = 2
n_crossings = 10
"""
# A chaos_border scan of 2 x 1 points on a 8 x 4 grid to t = 20 (the kind border.zarr is).
TINY_BORDER = """
[body]
kind = "hess"
name = "rho~1"
[parameters]
A = 2.5
B = 1.0
C = 1.6
mu = [0.02, 0.05]
epsilon = [0.0, 0.1]
h = 0.3125
[task]
kind = "chaos_border"
n = [8, 4]
t_end = 20.0
"""


@dataclass(frozen=True)
class Way:
    """How a documented command is run by this test.

    ``kind``: ``"cli"`` runs ``argv`` through ``andoyer.cli.main`` in this process;
    ``"process"`` runs ``argv`` as a program; ``"serve"`` starts the explorer and fetches
    its page; ``"ci"`` is a ``make`` target that CI runs itself (the script is named in
    ``why``). ``setup`` files are written into the folder first; ``expect`` files must
    exist afterwards.
    """

    kind: str
    argv: tuple[str, ...] = ()
    why: str = ""
    slow: bool = False
    setup: dict[str, str] = field(default_factory=dict)
    expect: tuple[str, ...] = ()


EXAMPLES = str(ROOT / "examples")
SMALL_SECTION = ("--n-orbits", "3", "--n-crossings", "10")
HOW: dict[str, Way] = {
    # The README's two set-up commands and `make docs` are CI's own jobs.
    "make run": Way("ci", why=".ci/newcomer"),
    "make test": Way("ci", why=".ci/run"),
    "make docs": Way("ci", why=".ci/docs"),
    "andoyer paper": Way("cli", ("paper", "--quick", "--only", "fig2"),
                         "the full report takes ~20 s: one item, --quick",
                         expect=("andoyer-paper/index.html",)),
    "andoyer paper --out DIR --only fig2 fig3": Way(
        "cli", ("paper", "--out", "DIR", "--only", "fig2", "fig3", "--quick"), "--quick",
        expect=("DIR/index.html",)),
    "andoyer paper --jobs 1": Way("cli", ("paper", "--jobs", "1", "--quick", "--only", "fig2"),
                                  "one item, --quick", expect=("andoyer-paper/index.html",)),
    "andoyer paper-check": Way("cli", ("paper-check", "--points", "20"), "20 points, not 200"),
    "andoyer prove --epsilon 0.1 --branch theta1=0 --out near-hess.json": Way(
        "cli", ("prove", "--epsilon", "0.1", "--branch", "theta1=0", "--digits", "12",
                "--out", "near-hess.json"), "12 digits, not 30", expect=("near-hess.json",)),
    "andoyer prove --kind transversal --B 1.0 --C 1.6 --epsilon 0.1 --mu 0.05 --out "
    "theorem.json": Way("cli", ("prove", "--kind", "transversal", "--B", "1.0", "--C", "1.6",
                                "--epsilon", "0.1", "--mu", "0.05", "--out", "theorem.json"),
                        "as written (the finite-mu proof, ~30 s)", slow=True,
                        expect=("theorem.json",)),
    "andoyer section": Way("cli", ("section", *SMALL_SECTION), "3 orbits x 10 crossings",
                           expect=("section.nc", "section.png")),
    "andoyer section --energy 0.25 --section g=0 --n-orbits 40 --n-crossings 500 "
    "--engine numba": Way(
        "cli", ("section", "--energy", "0.25", "--section", "g=0", *SMALL_SECTION, "--engine",
                "numba"), "3 orbits x 10 crossings", expect=("section.nc",)),
    "andoyer section --energy 0.25 --n-orbits 40 --n-crossings 500 --epsilon 0.05": Way(
        "cli", ("section", "--energy", "0.25", *SMALL_SECTION, "--epsilon", "0.05"),
        "3 orbits x 10 crossings", expect=("section.nc",)),
    "andoyer frequencies --andoyer 0.3,0,0.3,1,0 --t-end 3000": Way(
        "cli", ("frequencies", "--andoyer", "0.3,0,0.3,1,0", "--t-end", "3000"),
        "as written", expect=("frequencies.nc",)),
    "andoyer frequencies --n-orbits 100 --epsilon 0.1": Way(
        "cli", ("frequencies", "--n-orbits", "4", "--epsilon", "0.1", "--t-end", "500",
                "--n-samples", "1025"), "4 orbits to t = 500",
        expect=("frequencies.nc", "frequencies.png")),
    "andoyer resonances --body hess --A 3 --B 1 --C 2 --mu 0.001 --energy 1 --max-order 5":
        Way("cli", ("resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--mu",
                    "0.001", "--energy", "1", "--max-order", "5"), "as written",
            expect=("resonances.nc", "resonances.png")),
    "andoyer last-torus --body hess --A 3 --B 1 --C 2 --mu 0.001 --energy 1 --n-convergents 4 "
    "--mu-range 0.001 0.1": Way(
        "cli", ("last-torus", "--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--mu",
                "0.001", "--energy", "1", "--n-convergents", "1"),
        "one convergent, no search in mu", expect=("last-torus.nc",)),
    "andoyer last-torus --body hess --A 3 --B 1 --C 2 --mu 0.002 --axis 2 --h-values 1,2,3 "
    "--mu-range 0.01 1 --out mu-c.nc": Way(
        "cli", ("last-torus", "--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--mu",
                "0.002", "--axis", "2", "--h-values", "1,2,3", "--mu-range", "0.01", "1",
                "--n-convergents", "2", "--out", "mu-c.nc"),
        "two convergents", expect=("mu-c.nc",)),
    "andoyer resonances --max-order 10": Way(
        "cli", ("resonances", "--max-order", "10"), "as written",
        expect=("resonances.nc", "resonances.png")),
    "andoyer resonances --max-order 8 --order 8": Way(
        "cli", ("resonances", "--max-order", "8", "--order", "8"), "as written",
        expect=("resonances.nc", "resonances-normal-form.nc", "resonances.png")),
    "andoyer resonances --body general --A 2.5 --B 1 --C 2 --mu 0.001 --r 0.6 0.48 0.64 "
    "--energy 1 --max-order 3 --order 8": Way(
        "cli", ("resonances", "--body", "general", "--A", "2.5", "--B", "1", "--C", "2",
                "--mu", "0.001", "--r", "0.6", "0.48", "0.64", "--energy", "1",
                "--max-order", "3", "--order", "8"), "as written",
        expect=("resonances.nc", "resonances-normal-form.nc", "resonances.png")),
    "andoyer indicators --andoyer 0.3,0,0.3,1,0 --t-end 1000": Way(
        "cli", ("indicators", "--andoyer", "0.3,0,0.3,1,0", "--t-end", "1000"), "as written",
        expect=("indicators.nc", "indicators.png")),
    "andoyer orbit --andoyer 0.3,1.0,0.2,1.0,0.0 --t-end 10000 --out orbit.nc": Way(
        "cli", ("orbit", "--andoyer", "0.3,1.0,0.2,1.0,0.0", "--t-end", "10000", "--out",
                "orbit.nc"), "as written", expect=("orbit.nc",)),
    "andoyer chaos-map": Way("cli", ("chaos-map", "--n", "6", "--t-end", "20"),
                             "6 x 6 to t = 20", expect=("chaos-map.nc", "chaos-map.png")),
    "andoyer chaos-map --body hess --A 3 --B 1 --C 2 --mu 1 --energy 1 --n 64 --t-end 500 "
    "--indicator both": Way(
        "cli", ("chaos-map", "--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--mu", "1",
                "--energy", "1", "--n", "6", "--t-end", "20", "--indicator", "both"),
        "6 x 6 to t = 20", expect=("chaos-map.nc",)),
    "andoyer manifolds --mu-list 0.0025,0.005,0.01 --out manifolds": Way(
        "cli", ("manifolds", "--mu-list", "0.01", "--out", "manifolds"), "one mu",
        slow=True),
    "andoyer explore": Way("serve", ("explore",), "serves, page fetched, Ctrl-C",
                           slow=True),
    "andoyer explore --section g=0 --energy 0.25 --n-crossings 1000 --no-browser "
    "--port 8800": Way(
        "serve", ("explore", "--section", "g=0", "--energy", "0.25", "--n-crossings", "1000"),
        "a free port, not 8800", slow=True),
    "andoyer scan examples/atlas.toml": Way(
        "cli", ("scan", f"{EXAMPLES}/atlas.toml"),
        "as written (12 points of 30 orbits)", slow=True, expect=("atlas.zarr",)),
    "andoyer atlas atlas.zarr --out atlas.png": Way(
        "cli", ("atlas", "atlas.zarr", "--out", "atlas.png"), "on a scan of 2 points",
        setup={"tiny.toml": TINY_SCAN}, expect=("atlas.png",)),
    "andoyer scan examples/atlas.toml --store scan.zarr": Way(
        "cli", ("scan", f"{EXAMPLES}/atlas.toml", "--store", "scan.zarr"), "as written",
        slow=True, expect=("scan.zarr",)),
    "andoyer atlas scan.zarr --out scan.png": Way(
        "cli", ("atlas", "scan.zarr", "--out", "scan.png"), "on a scan of 2 points",
        setup={"tiny.toml": TINY_SCAN}, expect=("scan.png",)),
    "andoyer scan CONFIG.toml --dry-run": Way(
        "cli", ("scan", f"{EXAMPLES}/atlas.toml", "--dry-run"), "CONFIG = examples/atlas.toml"),
    "dask scheduler": Way("process", ("dask", "scheduler", "--help"), "--help: a service"),
    "dask worker tcp://HOST:8786 --nthreads 1": Way(
        "process", ("dask", "worker", "--help"), "--help: a service"),
    "andoyer scan CONFIG.toml --scheduler tcp://HOST:8786": Way(
        "cli", ("scan", "tiny.toml", "--scheduler", "serial", "--store", "s.zarr"),
        "a 2-point scan, serially (the cluster is Dask's)", setup={"tiny.toml": TINY_SCAN},
        expect=("s.zarr",)),
    "pip install -e '.[bench]'": Way("extra", ("bench",), "the extra exists"),
    "python -m benchmarks --quick": Way("process", ("python", "-m", "benchmarks", "--help"),
                                        "--help (the quick run takes ~3 min)"),
    "python -m benchmarks": Way("process", ("python", "-m", "benchmarks", "--help"),
                                "--help (the full run takes ~35 min)"),
    "andoyer scan examples/border_of_chaos.toml --store border.zarr": Way(
        "cli", ("scan", f"{EXAMPLES}/border_of_chaos.toml", "--store", "border.zarr",
                "--dry-run"), "--dry-run (the scan takes ~6 min)"),
    "andoyer atlas border.zarr --out border.png": Way(
        "cli", ("atlas", "border.zarr", "--out", "border.png"),
        "on a chaos_border scan of 2 x 2 points", setup={"border.toml": TINY_BORDER},
        expect=("border.png",)),
}
# Stores the atlas commands draw: made by a tiny scan first (config file -> store).
STORES = {"atlas.zarr": "tiny.toml", "scan.zarr": "tiny.toml", "border.zarr": "border.toml"}


def _parse(command: str) -> None:
    words = shlex.split(command)
    assert words[0] == "andoyer"
    build_parser().parse_args(words[1:])


@pytest.mark.parametrize("command", sorted(fenced_commands()))
def test_every_fenced_command_is_run(command: str) -> None:
    """A command new to the docs needs a line in HOW (and so a run)."""
    assert command in HOW, (f"{command!r} ({', '.join(fenced_commands()[command])}) is not "
                            "run by tests/test_docs_commands.py: add it to HOW")


def test_how_lists_only_documented_commands() -> None:
    stale = sorted(set(HOW) - set(fenced_commands()))
    assert not stale, f"no longer in the docs, remove from HOW: {stale}"


@pytest.mark.parametrize("command", sorted(c for c in fenced_commands()
                                           if c.startswith("andoyer ")))
def test_documented_andoyer_commands_parse(command: str) -> None:
    """Exactly as written in the docs, flags and all (``--out`` on ``scan`` fails here)."""
    _parse(command)


@pytest.mark.parametrize("command", sorted(inline_commands()))
def test_inline_andoyer_commands_parse(command: str, capsys: pytest.CaptureFixture[str]
                                       ) -> None:
    """An inline span names a command (``andoyer scan``), an option (``andoyer --debug
    ...``) or gives a command in full, which must parse."""
    words = [w for w in shlex.split(command)[1:] if w != "..."]
    if len([w for w in words if not w.startswith("-")]) > 1:
        _parse(command)
        return
    parser = build_parser()
    for option in (w for w in words if w.startswith("-")):
        assert f" {option}" in parser.format_help(), f"{command!r}: no option {option}"
    with pytest.raises(SystemExit) as exc:  # the command's own --help: it exists
        parser.parse_args([w for w in words if not w.startswith("-")] + ["--help"])
    assert exc.value.code == 0, capsys.readouterr().err


def test_make_targets_are_run_by_ci() -> None:
    for command, way in HOW.items():
        if way.kind == "ci":
            script = (ROOT / way.why).read_text(encoding="utf-8")
            assert command in script, f"{way.why} does not run {command!r}"


def _run_cli(argv: tuple[str, ...], capsys: pytest.CaptureFixture[str]) -> None:
    try:
        code = main(list(argv))
    except SystemExit as exc:  # pragma: no cover - the failure is the message
        err = capsys.readouterr().err
        raise AssertionError(f"andoyer {' '.join(argv)} exited {exc.code}: {err}") from None
    assert code == 0


def _serve(argv: tuple[str, ...]) -> None:
    proc = subprocess.Popen([str(BIN / "andoyer"), *argv, "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "PYTHONUNBUFFERED": "1"})
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        m = re.fullmatch(r"andoyer explore: serving on (http://127\.0\.0\.1:\d+/)\n", line)
        assert m, line + (proc.stderr.read() if proc.stderr and proc.poll() else "")
        with urllib.request.urlopen(m.group(1), timeout=60) as page:
            assert page.status == 200
        proc.send_signal(signal.SIGINT)
        proc.communicate(timeout=60)
        assert proc.returncode == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()


def _params() -> list[object]:
    out: list[object] = []
    for command, way in sorted(HOW.items()):
        if way.kind == "ci":
            continue
        marks = [pytest.mark.slow] if way.slow else []
        out.append(pytest.param(command, way, marks=marks, id=command[:60]))
    return out


def _has_heyoka() -> bool:
    import importlib.util

    return importlib.util.find_spec("heyoka") is not None


@pytest.mark.timeout(600)
@pytest.mark.parametrize("command, way", _params())
def test_documented_command_runs(command: str, way: Way, tmp_path: Path,
                                 monkeypatch: pytest.MonkeyPatch,
                                 capsys: pytest.CaptureFixture[str]) -> None:
    """The command (or its variant in HOW) succeeds in an empty folder."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    for name, text in way.setup.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    for store, config in STORES.items():
        if store in way.argv and way.argv[0] == "atlas":
            _run_cli(("scan", config, "--scheduler", "serial", "--store", store,
                      "--no-progress"), capsys)
    if way.kind == "cli":
        _run_cli(way.argv, capsys)
    elif way.kind == "serve":
        _serve(way.argv)
    elif way.kind == "process":
        if way.argv[:3] == ("python", "-m", "benchmarks") and not _has_heyoka():
            pytest.skip("the benchmarks compare with heyoka (pip install -e '.[bench]')")
        program = sys.executable if way.argv[0] == "python" else str(BIN / way.argv[0])
        done = subprocess.run([program, *way.argv[1:]], cwd=ROOT, capture_output=True,
                              text=True, timeout=300)
        assert done.returncode == 0, done.stderr
    elif way.kind == "extra":
        extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
            "optional-dependencies"]
        assert way.argv[0] in extras
    else:  # pragma: no cover
        raise AssertionError(f"unknown way {way.kind!r}")
    for name in way.expect:
        assert (tmp_path / name).exists(), f"{command!r} did not write {name}"
