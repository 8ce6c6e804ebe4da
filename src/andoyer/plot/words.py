"""Labels in words and symbols: the names code uses (``"theta1=4phi0"``, a body's
preset name, ``1e-3``) as a figure's reader reads them (mathtext).

Examples
--------
>>> branch_words("theta1=4phi0")
'$\\\\theta_1 = 4\\\\varphi_0$'
>>> number_words(1e-3)
'$10^{-3}$'
"""

from __future__ import annotations

import math
import re

__all__ = ["branch_words", "symbol_words", "number_words", "body_words"]

#: ASCII names of the paper's symbols -> mathtext.
_SYMBOLS = {"theta1": r"\theta_1", "theta2": r"\theta_2", "phi0": r"\varphi_0",
            "mu": r"\mu", "kappa": r"\kappa", "sigma": r"\sigma", "gamma": r"\gamma",
            "epsilon": r"\varepsilon", "J1": "J_1", "J2": "J_2", "G3": "G_3", "psi": r"\psi",
            "pi": r"\pi"}


def symbol_words(text: str) -> str:
    """``text`` written with the paper's symbols (``"theta1=4phi0"`` -> ``θ1 = 4φ0``), as
    mathtext.

    Parameters
    ----------
    text : str
        An equation or a name as the code spells it.
    """
    def one(m: re.Match[str]) -> str:
        return _SYMBOLS.get(m.group(0), m.group(0))

    body = re.sub(r"[A-Za-z]+\d?", one, text.replace(" ", ""))
    body = body.replace("=", " = ")
    return f"${body}$"


def branch_words(name: str) -> str:
    """A separatrix branch (``"theta1=0"``, ``"theta1=4phi0"``) in symbols.

    Parameters
    ----------
    name : str
        The branch as :data:`andoyer.analysis.unperturbed.separatrix.BRANCHES` names it.
    """
    return symbol_words(name)


def number_words(x: float) -> str:
    """A number as a paper prints it: ``0.01``, ``$10^{-3}$``, ``$2 \\times 10^{-4}$``.

    Parameters
    ----------
    x : float
        The number.
    """
    if x == 0 or 1e-2 <= abs(x) < 1e4:
        return f"{x:g}"
    e = math.floor(math.log10(abs(x)))
    m = x / 10.0**e
    if abs(m - round(m)) < 1e-9 and round(m) == 1:
        return f"$10^{{{e}}}$"
    return f"${m:g} \\times 10^{{{e}}}$"


def body_words(A: float, B: float, C: float, mu: float, hess: bool = True) -> str:
    """A body in words: ``Hess body (A, B, C) = (3, 1, 2), μ = 10⁻³``.

    Parameters
    ----------
    A, B, C : float
        Principal moments of inertia.
    mu : float
        Weight times the distance of the centre of mass.
    hess : bool, default True
        Name it a Hess body.

    Examples
    --------
    >>> body_words(3.0, 1.0, 2.0, 1e-3)
    'Hess body $(A, B, C) = (3, 1, 2)$, $\\\\mu$ = $10^{-3}$'
    """
    kind = "Hess body" if hess else "body"
    return f"{kind} $(A, B, C) = ({A:g}, {B:g}, {C:g})$, $\\mu$ = {number_words(mu)}"
