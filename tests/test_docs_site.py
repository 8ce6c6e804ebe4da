"""Docs that cannot lose a figure, and a README that lists every tutorial.

The README's list of tutorials is the site's table of contents (``docs/tutorials/index.md``,
same pages, same order): checked always. The built site (``make docs``; ``.ci/docs`` runs
this file after the build) is checked where it exists: every tutorial page shows at least
as many images in its cells' outputs as its cells create figures (a call of a plot
function without ``ax=``, ``new_figure``, ``plt.subplots``/``plt.figure``), and never a
figure's text repr ``<Figure size ...>`` (a figure that was made and not shown)."""

from __future__ import annotations

import ast
import html
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TUTORIALS = ROOT / "docs" / "tutorials"
SITE = ROOT / "docs" / "_build" / "html"


def toctree(index: Path) -> list[str]:
    """The pages of the ``{toctree}`` of ``index``, in order."""
    block = re.search(r"```\{toctree\}\n(.*?)```", index.read_text(), re.S)
    assert block, f"{index}: no toctree"
    return [line.strip() for line in block.group(1).splitlines()
            if line.strip() and not line.strip().startswith(":")]


def test_readme_lists_every_tutorial_in_the_sites_order() -> None:
    readme = (ROOT / "README.md").read_text()
    linked = re.findall(r"\(docs/tutorials/([\w-]+)\.md\)", readme)
    assert linked == toctree(TUTORIALS / "index.md"), \
        "README's tutorial list differs from docs/tutorials/index.md's toctree"


def code_cells(page: Path) -> list[str]:
    """The code of the page's ``{code-cell}`` blocks (IPython magics left out)."""
    cells = re.findall(r"```\{code-cell\}[^\n]*\n(.*?)```", page.read_text(), re.S)
    return ["\n".join(line for line in cell.splitlines()
                      if not line.lstrip().startswith(("%", "!", ":")))
            for cell in cells]


#: Calls that make a new figure (andoyer's plot functions make one unless given ``ax=``).
NEW_FIGURE = {"new_figure", "subplots", "figure", "Figure"}


def figures_created(page: Path) -> int:
    """How many figures the page's cells create (read from their code)."""
    n = 0
    for cell in code_cells(page):
        for node in ast.walk(ast.parse(cell)):
            if not isinstance(node, ast.Call):
                continue
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            if name in NEW_FIGURE or (name.startswith("plot_")
                                      and "ax" not in {k.arg for k in node.keywords}):
                n += 1
    return n


def output_images(page_html: str) -> int:
    """The images inside the cells' outputs of a built page."""
    parts = page_html.split('class="cell_output')[1:]
    return sum(part.split('class="cell docutils')[0].count("<img") for part in parts)


def test_figure_counting_reads_the_code() -> None:
    page = ROOT / "docs" / "tutorials" / "first-orbit.md"
    assert figures_created(page) >= 1
    html_text = ('<div class="cell docutils"><div class="cell_output docutils"><img src=a>'
                 '</div></div><div class="cell docutils"><img src=b></div>')
    assert output_images(html_text) == 1


NOTEBOOKS = sorted(p for p in TUTORIALS.glob("*.md") if "code-cell" in p.read_text())


@pytest.mark.skipif(not (SITE / "tutorials").is_dir(),
                    reason="no built site (make docs; .ci/docs runs this after the build)")
@pytest.mark.parametrize("page", NOTEBOOKS, ids=lambda p: p.stem)
def test_every_tutorial_shows_its_figures(page: Path) -> None:
    built = SITE / "tutorials" / f"{page.stem}.html"
    assert built.exists(), f"{built} not built"
    text = built.read_text()
    lost = re.findall(r"&lt;Figure size [^&]*&gt;|<Figure size [^<]*>", text)
    assert not lost, f"{page.name}: figures printed as text, not shown: " \
                     f"{[html.unescape(x) for x in lost]}"
    created, shown = figures_created(page), output_images(text)
    assert shown >= created, f"{page.name}: {created} figures made, {shown} shown"


def _recipe(target: str) -> str:
    """The commands of a Makefile target."""
    text = (ROOT / "Makefile").read_text()
    m = re.search(rf"^{re.escape(target)}:[^\n]*\n((?:\t[^\n]*\n)*)", text, re.M)
    assert m, target
    return m.group(1)


def test_make_run_installs_the_main_job_only_and_make_docs_is_incremental() -> None:
    """``make run`` installs andoyer without the test tools; ``make docs`` keeps its
    doctrees and output (an unchanged site rebuilds in seconds), warnings still errors."""
    assert "[test" not in _recipe("$(VENV)/.installed")
    assert "[test" not in _recipe("$(VENV)/.docs")
    docs = _recipe("docs")
    assert "rm " not in docs and docs.count(" -W ") == 2 and docs.count(" -q ") == 2
    assert "$(VENV)/.test" in (ROOT / "Makefile").read_text().split("\ntest:")[1].split("\n")[0]
