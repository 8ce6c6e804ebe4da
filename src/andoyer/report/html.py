"""``index.html`` from the Jinja2 templates of this package (``templates/``).

``index.html.j2`` is the page (its style is ``report.css``); ``item.html.j2`` lays out
one item (figures, what the paper says, what was corrected or added, files, table) and
``items/<key>.html.j2``, which extends it, holds that item's prose. Values are escaped
by Jinja2 (autoescape); numbers are formatted in the templates with the ``fmt`` filter
(a :func:`format` spec; a zero is never printed with a sign, in table cells either).

Examples
--------
>>> env = environment()
>>> env.from_string("{{ x|fmt('.2e') }} {{ s }}").render(x=12345.0, s="a < b")
'1.23e+04 a &lt; b'
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path
from typing import Any

from andoyer.atomic import atomic_path
from andoyer.body import RigidBody
from andoyer.report.base import Item, Result

__all__ = ["environment", "render_item", "write_index", "DISPLAY_DPI", "MATHJAX"]

#: Figures are written at 200 dpi and shown at most this many CSS pixels per inch (so a
#: 6.4 in figure is at most 960 px wide; narrower windows scale it down).
DISPLAY_DPI = 150.0
_WRITTEN_DPI = 200.0


@cache
def environment() -> Any:
    """The Jinja2 environment of the report's templates (package data)."""
    import jinja2

    env = jinja2.Environment(loader=jinja2.PackageLoader("andoyer.report", "templates"),
                             autoescape=True, undefined=jinja2.StrictUndefined,
                             keep_trailing_newline=True)
    env.filters["fmt"] = lambda value, spec="": _no_negative_zero(format(value, spec))
    env.filters["cell"] = lambda value: _symbols(_no_negative_zero(str(value)))
    return env


#: A number that prints as zero with a sign (``-0``, ``-0.000``, ``+0.00e+00``).
_SIGNED_ZERO = re.compile(r"[-+−]0(\.0*)?([eE][-+]?0+)?")


#: The paper's symbols as the code spells them -> as a reader reads them (table cells).
_SYMBOLS = {"theta1": "θ₁", "theta2": "θ₂", "phi0": "φ₀", "mu": "μ", "epsilon": "ε",
            "Delta": "Δ", "sigma": "σ", "kappa": "κ", "gamma": "γ", "rho": "ρ", "lambda": "λ",
            "omega": "ω", "psi": "ψ", "J1": "J₁", "J2": "J₂", "G0": "G₀", "H0": "H₀"}
_SYMBOL = re.compile(r"(?<![A-Za-z_])(" + "|".join(sorted(_SYMBOLS, key=len, reverse=True))
                     + r")(?![A-Za-z0-9_])")


def _symbols(text: str) -> str:
    """A table cell with the paper's symbols in place of their ASCII names
    (``theta1=4phi0`` -> ``θ₁ = 4φ₀``).

    Examples
    --------
    >>> _symbols("theta1=4phi0"), _symbols("max |Delta G| at mu = 0.01"), _symbols("must")
    ('θ₁ = 4φ₀', 'max |Δ G| at μ = 0.01', 'must')
    """
    out = _SYMBOL.sub(lambda m: _SYMBOLS[m.group(1)], text)
    return re.sub(r"(?<=[₀-₉])=(?=\S)", " = ", out)


def _no_negative_zero(text: str) -> str:
    """``text`` with a zero printed without its sign (``-0.00e+00`` -> ``0.00e+00``).

    Examples
    --------
    >>> _no_negative_zero("-0.00e+00"), _no_negative_zero("-0.5"), _no_negative_zero("+0.000")
    ('0.00e+00', '-0.5', '0.000')
    """
    return text[1:] if _SIGNED_ZERO.fullmatch(text.strip()) else text


def _images(result: Result) -> list[dict[str, Any]]:
    """The item's PNGs with the size they are shown at (scaled down by the page's CSS)."""
    from PIL import Image

    out = []
    for f in result.files:
        if f.suffix == ".png":
            with Image.open(f) as im:
                w, h = im.size
            scale = DISPLAY_DPI / _WRITTEN_DPI
            out.append({"name": f.name, "width": round(w * scale), "height": round(h * scale)})
    return out


def render_item(item: Item, result: Result, seconds: float, body: RigidBody) -> str:
    """One item's section of ``index.html``: its figures, prose, files and table.

    Parameters
    ----------
    item : Item
        The item.
    result : Result
        What it built.
    seconds : float
        How long it took.
    body : RigidBody
        The paper's body (its prose reads it).
    """
    template = environment().get_template(f"items/{item.key}.html.j2")
    return str(template.render(item=item, result=result, v=result.values, seconds=seconds,
                               body=body, images=_images(result)))


def write_index(out: Path, body: RigidBody, engine: str,
                done: list[tuple[Item, Result, float]]) -> Path:
    """Write ``out/index.html`` (atomically) for the items ``done``, in their order.

    Parameters
    ----------
    out : pathlib.Path
        The report's folder.
    body : RigidBody
        The paper's body.
    engine : str
        The engine the items ran on.
    done : list of (Item, Result, float)
        The items built, their results and seconds.
    """
    from markupsafe import Markup

    from andoyer._version import __version__

    sections = [Markup(render_item(item, res, seconds, body)) for item, res, seconds in done]
    page = environment().get_template("index.html.j2").render(
        version=__version__, body=body, engine=engine, items=[i for i, _, _ in done],
        sections=sections, mathjax=MATHJAX)
    index = out / "index.html"
    _copy_mathjax(out)
    with atomic_path(index) as tmp:
        tmp.write_text(page, encoding="utf-8")
    return index


#: The report's MathJax (package data), copied beside ``index.html``: formulas render
#: from the folder alone, offline.
MATHJAX = "mathjax-tex-svg.js"


def _copy_mathjax(out: Path) -> Path:
    """``out/mathjax-tex-svg.js`` (left alone when it is already the same file)."""
    from importlib.resources import files

    source = files("andoyer.report").joinpath("mathjax", "tex-svg.js").read_bytes()
    target = out / MATHJAX
    if not (target.exists() and target.read_bytes() == source):
        with atomic_path(target) as tmp:
            tmp.write_bytes(source)
    return target
