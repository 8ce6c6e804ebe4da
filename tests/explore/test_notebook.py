"""The explorer in Jupyter: a notebook that displays ``andoyer.explore()``, executed by a
real IPython kernel (nbclient), shows the Panel/Bokeh page with andoyer's models."""

from __future__ import annotations

import pytest

nbformat = pytest.importorskip("nbformat", reason="nbclient/nbformat are test extras")
nbclient = pytest.importorskip("nbclient", reason="nbclient/nbformat are test extras")
pytest.importorskip("ipykernel", reason="ipykernel is a test extra")

CELLS = [
    "import panel as pn\npn.extension()",
    "import andoyer\npage = andoyer.explore(n_crossings=50, boundary_grid=40)\npage",
]


def test_the_explorer_displays_in_a_notebook() -> None:
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in CELLS])
    nbclient.NotebookClient(nb, kernel_name="python3", timeout=300).execute()
    errors = [o for c in nb.cells for o in c.outputs if o.output_type == "error"]
    assert not errors, errors
    shown = [o for o in nb.cells[1].outputs if o.output_type == "execute_result"]
    assert len(shown) == 1
    data = shown[0].data
    # Panel's view in Jupyter: its exec bundle, and the HTML with the Bokeh root.
    assert "application/vnd.holoviews_exec.v0+json" in data
    html = data["text/html"]
    assert "data-root-id" in html and "docs_json" in html
    # The Bokeh document carries the explorer's named models (the test hook).
    for name in ("andoyer-plane", "andoyer-points", "andoyer-orbit-table", "andoyer-state"):
        assert name in html, name
