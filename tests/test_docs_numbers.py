"""Numbers in the docs come from a run, and the default engine from the library.

The timings and the table "Which engine for what" of the README and the user guide are
``benchmarks/SUMMARY.md`` (written by ``python -m benchmarks`` from ``results.json``; the
README holds a copy between its markers, the guide includes the file); the default engine
of each workload is ``andoyer.integrate.engines.MEASURED_DEFAULTS``, and every page that
says what ``engine=None`` runs says so with its exceptions."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from andoyer.integrate import engines

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "benchmarks"
START, END = "<!-- benchmarks:start -->", "<!-- benchmarks:end -->"
#: The workloads of the benchmark rows (W1, W2 by section, W3) as ``WORKLOADS`` names them.
KEYS = {"W1": "orbit", "G3": "component_section", "theta2": "angle_section", "W3": "fli_map"}
#: The workloads a row's case names before its workload's tag (W3's MEGNO map).
CASES = {"MEGNO map": "megno_map"}
#: How the docs name a workload (what a paragraph naming an exception must say).
WORDS = {"orbit": "orbit", "component_section": "G3", "angle_section": "θ2",
         "fli_map": "FLI map", "megno_map": "MEGNO map"}
#: The pages a reader meets that state defaults or timings.
PAGES = ["README.md", "ARCHITECTURE.md", "docs/index.md", "docs/guide.md",
         *sorted(str(p.relative_to(ROOT)) for p in (ROOT / "docs").glob("*/*.md"))]


def advice_rows(text: str) -> dict[str, tuple[str, str]]:
    """The "Which engine for what" table of ``text``: workload -> (default with heyoka,
    default without heyoka)."""
    out = {}
    lines = text.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("| workload | default"))
    for line in lines[head + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        wl = cells[0]
        case = wl.split(": ", 1)[-1]
        key = next((k for tag, k in CASES.items() if case.startswith(tag)), None) or next(
            k for tag, k in KEYS.items() if tag in wl.split(":")[0] or f"of {tag} " in wl)
        out[key] = (cells[1], cells[3])
    return out


def expected_default(key: str) -> tuple[str, str]:
    need = {"orbit": engines.Capability.PROPAGATE, "fli_map": engines.Capability.TANGENT,
            "megno_map": engines.Capability.TANGENT}.get(key, engines.Capability.CROSSINGS)
    without = next(n for n in engines.FALLBACK_DEFAULTS
                   if need in engines.engine_class(n).capabilities)
    return engines.MEASURED_DEFAULTS.get(key, "heyoka"), without


def test_readme_block_is_the_generated_summary() -> None:
    readme = (ROOT / "README.md").read_text()
    block = readme[readme.index(START) + len(START):readme.index(END)].strip()
    assert block == (BENCH / "SUMMARY.md").read_text().strip(), \
        "README's benchmark block differs from benchmarks/SUMMARY.md: python -m benchmarks --tables"
    assert "```{include} ../benchmarks/SUMMARY.md" in (ROOT / "docs/guide.md").read_text()


@pytest.mark.parametrize("page", ["README.md", "benchmarks/SUMMARY.md"])
def test_which_engine_for_what_states_the_measured_defaults(page: str) -> None:
    rows = advice_rows((ROOT / page).read_text())
    # every table has the four workloads; a run that measured the MEGNO map has its row too
    assert set(KEYS.values()) <= set(rows) <= set(KEYS.values()) | set(CASES.values())
    for key, stated in rows.items():
        assert stated == expected_default(key), (page, key, stated)


def test_a_changed_default_is_caught(monkeypatch) -> None:
    """The check above is not vacuous: move the G3 sections to numba and it fails."""
    monkeypatch.setattr(engines, "MEASURED_DEFAULTS",
                        {**engines.MEASURED_DEFAULTS, "component_section": "numba"})
    rows = advice_rows((BENCH / "SUMMARY.md").read_text())
    assert rows["component_section"] != expected_default("component_section")


def paragraphs(text: str) -> list[str]:
    """The paragraphs of a page, the generated benchmark block left out (checked above)."""
    if START in text and END in text:
        text = text[:text.index(START)] + text[text.index(END):]
    return [" ".join(p.split()) for p in re.split(r"\n\s*\n", text) if p.strip()]


#: A paragraph that says which engine runs by default.
STATES_DEFAULT = re.compile(r"engine=None|default where (heyoka is )?installed|"
                            r"(stays|is) the default where|default with heyoka")


@pytest.mark.parametrize("page", PAGES)
def test_every_statement_of_the_default_names_its_exceptions(page: str) -> None:
    """``engine=None`` means heyoka where installed *except* the workloads of
    MEASURED_DEFAULTS: a paragraph saying what the default is names them (the engine and
    the workload) or points to ``MEASURED_DEFAULTS``."""
    bad = []
    for para in paragraphs((ROOT / page).read_text()):
        if not STATES_DEFAULT.search(para) or "heyoka" not in para:
            continue
        if "MEASURED_DEFAULTS" not in para:
            bad.append(para[:160])
            continue
        for key, engine in engines.MEASURED_DEFAULTS.items():
            if engine not in para or WORDS[key].lower() not in para.lower():
                bad.append(para[:160])
    assert not bad, f"{page}: the default stated without MEASURED_DEFAULTS' exceptions: {bad}"


def test_paper_timings_are_the_benchmarks() -> None:
    """A time of ``andoyer paper`` in the README or the guide is W5 of the last run."""
    result = json.loads((BENCH / "results.json").read_text())
    w5 = next(r["wall_s"] for r in result["rows"] if r["workload"] == "W5")
    allowed = {f"{w5:.2f}", f"{w5:.1f}"}
    for page in ("README.md", "docs/guide.md"):
        for para in paragraphs((ROOT / page).read_text()):
            if "andoyer paper" not in para or para.startswith("|"):
                continue
            # the first time within a few words of the command's name (a target "<= 20 s"
            # is no time)
            for at in re.finditer(r"andoyer paper\b(?!-)", para):
                near = re.sub(r"(≤|<=) \d+(\.\d+)? s\b", "", para[at.end():at.end() + 40])
                value = next(iter(re.findall(r"(\d+(?:\.\d+)?) s\b", near)), None)
                if value is None:
                    continue
                assert value in allowed, (page, para[at.start():at.start() + 120], w5)
