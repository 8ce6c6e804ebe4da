"""The docs' one way of showing figures: the IPython start-up file of every notebook
kernel the site runs (``conf.py`` installs it; a test of the built site checks it).

andoyer's plot functions build :class:`matplotlib.figure.Figure` objects without pyplot,
which no notebook backend shows by itself, and a cell that ends in ``;`` or assigns its
figure shows nothing: here every figure a cell creates is shown once, as a PNG, when the
cell ends (a figure that is the cell's value is shown in its place instead). The kernel
runs on Agg (``MPLBACKEND``), so pyplot's figures are shown the same way and closed.
"""

import weakref

from IPython import get_ipython
from IPython.display import display
from matplotlib.figure import Figure

_created: "list[weakref.ref[Figure]]" = []  # in the order the cell made them
_shown: "weakref.WeakSet[Figure]" = weakref.WeakSet()
_init = Figure.__init__


def _tracked_init(self, *args, **kwargs):
    _init(self, *args, **kwargs)
    _created.append(weakref.ref(self))


def _png(fig):
    from io import BytesIO

    _shown.add(fig)
    buf = BytesIO()
    fig.savefig(buf, format="png", dpi=fig.dpi, bbox_inches="tight")
    return buf.getvalue()


def _show_new_figures(result=None):
    import matplotlib.pyplot as plt

    for ref in _created:
        fig = ref()
        if fig is not None and fig not in _shown:
            display(fig)
    _created.clear()
    plt.close("all")


Figure.__init__ = _tracked_init
_ip = get_ipython()
if _ip is not None:
    _ip.display_formatter.formatters["image/png"].for_type(Figure, _png)
    # a Figure's text repr ("<Figure size 360x360 with 1 Axes>") never reaches the page
    _ip.display_formatter.formatters["text/plain"].for_type(Figure, lambda fig, p, cycle: None)
    _ip.events.register("post_run_cell", _show_new_figures)
