"""Generate the numeric kernels from the symbolic Hamiltonians.

The output, ``andoyer/kernels/generated/equations.py``, is plain Python on scalars or NumPy
arrays (common subexpressions eliminated); the same functions are compiled by Numba
in :mod:`andoyer.kernels.dop853.fields`. It is committed, so importing ``andoyer`` never runs
SymPy; ``tests/symbolic/test_codegen.py`` regenerates it in memory and checks that the
committed file still evaluates to the same numbers.

Regenerate with ``python -m andoyer.symbolic.codegen``.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from pathlib import Path

import sympy as sp
from sympy.printing.numpy import NumPyPrinter

from andoyer.atomic import atomic_path
from andoyer.symbolic import attitude as att
from andoyer.symbolic import hamiltonian as sym
from andoyer.symbolic import sections as sec

__all__ = ["KERNELS", "generate_source", "write_generated", "GENERATED_PATH", "NumbaPrinter"]

GENERATED_PATH = (Path(__file__).resolve().parent.parent / "kernels" / "generated"
                  / "equations.py")

S = sym.S

#: name -> (argument symbols, builder of the expressions, docstring)
KERNELS: dict[str, tuple[tuple[sp.Symbol, ...], Callable[[], Sequence[sp.Expr]], str]] = {
    "ep_hamiltonian": (S.y + S.body, lambda: [sym.H_euler_poisson()],
                       "H of Eq. (1) in Euler-Poisson variables."),
    "ep_field": (S.y + S.body, sym.euler_poisson_field,
                 "Lie-Poisson equations (1): d(G1, G2, G3, gamma1, gamma2, gamma3)/dt."),
    "ep_jacobian": (S.y + S.body, sym.euler_poisson_jacobian,
                    "Jacobian of (1), row-major: J[6 i + j] = d f_i / d y_j (variational "
                    "equations dw/dt = J w)."),
    "attitude_field": (S.y + att.Q + S.body, att.attitude_field,
                       "Field (1) with the attitude quaternion (scalar first, body -> space): "
                       "d(G1, G2, G3, gamma1, gamma2, gamma3, q0, q1, q2, q3)/dt."),
    "andoyer_hamiltonian": (S.andoyer + S.body, lambda: [sym.H_andoyer()],
                            "H of Eq. (7) in Andoyer-Deprit variables."),
    "andoyer_field": (S.andoyer + S.body, sym.andoyer_field,
                      "Canonical equations (4): d(l, g, L, G, M, m)/dt."),
    "hess_hamiltonian": (S.hess + S.hess_body, lambda: [sym.H_hess()],
                         "H in the Hess chart (14)-(15), e = (cos phi0, sin phi0, 0)."),
    "hess_field": (S.hess + S.hess_body, sym.hess_field,
                   "Canonical equations in the Hess chart (general form of (16)): "
                   "d(theta1, theta2, J1, J2, J3, theta3)/dt."),
}


class NumbaPrinter(NumPyPrinter):
    """NumPy printer whose output also compiles in Numba ``nopython`` mode."""

    def __init__(self) -> None:
        super().__init__({"fully_qualified_modules": False, "inline": True,
                          "allow_unknown_functions": False})

    def _print_Zero(self, expr: sp.Expr) -> str:
        return "0.0"  # a float, so that Numba returns a homogeneous tuple


def _function_source(name: str, args: Sequence[sp.Symbol], exprs: Sequence[sp.Expr],
                     doc: str) -> str:
    printer = NumbaPrinter()
    replacements, reduced = sp.cse(list(exprs), symbols=sp.numbered_symbols("x"),
                                   optimizations="basic")
    lines = [f"def {name}({', '.join(str(a) for a in args)}):", f'    """{doc}"""']
    for s, e in replacements:
        lines.append(f"    {s} = {printer.doprint(e)}")
    if len(reduced) == 1:
        lines.append(f"    return {printer.doprint(reduced[0])}")
    else:
        lines.append("    return (")
        lines += [f"        {printer.doprint(e)}," for e in reduced]
        lines.append("    )")
    return "\n".join(lines) + "\n"


def _section_source() -> str:
    """One dispatch function ``section(kind, *SECTION_ARGS) -> (f, w)`` over all kinds."""
    printer = NumbaPrinter()
    public = [*sec.SMOOTH, *sec.ANGLES]
    kinds = [*public, *sec.EXTRA_ANGLES]
    args = ", ".join(str(a) for a in sec.SECTION_ARGS)
    lines = [f"SECTION_KINDS = {tuple(public)!r}",
             "#: Kinds after SECTION_KINDS: section angles that are not chart coordinates.",
             f"EXTRA_SECTION_KINDS = {tuple(sec.EXTRA_ANGLES)!r}", "", "",
             f"def section(kind, {args}):",
             '    """Section function ``(f, w)`` of ``(SECTION_KINDS + EXTRA_SECTION_KINDS)[kind] '
             '= value`` (see andoyer.symbolic.sections)."""']
    for i, kind in enumerate(kinds):
        f, w = sec.section_function(kind)
        kw = "if" if i == 0 else "elif"
        lines.append(f"    {kw} kind == {i}:  # {kind}")
        reps, (fr, wr) = sp.cse([f, w], symbols=sp.numbered_symbols("s"))
        lines += [f"        {s} = {printer.doprint(e)}" for s, e in reps]
        wtxt = printer.doprint(wr) if wr.free_symbols else "1.0"
        lines.append(f"        return {printer.doprint(fr)}, {wtxt}")
    lines.append("    return 0.0, -1.0")
    return "\n".join(lines) + "\n"


def generate_source() -> str:
    """The text of ``generated/equations.py`` (runs SymPy; takes tens of seconds)."""
    head = [
        '"""Numeric kernels generated by andoyer.symbolic.codegen from H written once.',
        "",
        "DO NOT EDIT: regenerate with ``python -m andoyer.symbolic.codegen``.",
        "Every function takes scalars or broadcastable NumPy arrays and compiles in Numba.",
        '"""',
        "",
        "from numpy import cos, sin, sqrt",
        "",
        f"SYMPY_VERSION = {sp.__version__!r}",
        "",
        "",
    ]
    body = [_function_source(name, args, build(), doc)
            for name, (args, build, doc) in KERNELS.items()]
    body.append(_section_source())
    return "\n".join(head) + "\n\n".join(body)


def write_generated(path: Path = GENERATED_PATH) -> Path:
    """Write the generated module atomically (temporary file, then rename).

    Parameters
    ----------
    path : pathlib.Path, default the package's ``kernels/generated/equations.py``
        Where to write.
    """
    src = generate_source()
    with atomic_path(path) as tmp:
        tmp.write_text(src)
    return path


if __name__ == "__main__":  # pragma: no cover
    out = write_generated(Path(sys.argv[1]) if len(sys.argv) > 1 else GENERATED_PATH)
    print(f"wrote {out}")
