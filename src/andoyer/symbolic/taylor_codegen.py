r"""Generate the Taylor-series jets of the field (1) and of the section functions.

The output, ``andoyer/kernels/generated/recurrences.py``, holds plain Python loops that
Numba compiles (:mod:`andoyer.kernels.taylor.flow`); it is committed, so importing andoyer
never runs SymPy, and ``tests/symbolic/test_taylor_codegen.py`` regenerates it and
compares. Nothing in it is typed by hand: every recurrence is read off the SymPy
expressions of :mod:`andoyer.symbolic.hamiltonian` and :mod:`andoyer.symbolic.sections`.

Jets. A jet is the array of normalised Taylor coefficients
:math:`x^{[k]} = x^{(k)}(t_0)/k!`, ``k = 0 .. order``, of a function of time.

* The field (1) is a polynomial of degree <= 2 in the state with coefficients that
  depend on the body only. Written as :math:`f_i = \sum_m q_{im} x^{m}` over monomials
  (``sympy.Poly``), the jet of the solution follows from

  .. math:: x_i^{[k+1]} = \frac{1}{k+1} \sum_m q_{im} (x^m)^{[k]}, \qquad
            (x_a x_b)^{[k]} = \sum_{j=0}^{k} x_a^{[j]} x_b^{[k-j]}

  (a Cauchy product per quadratic monomial, computed once for all components):
  :func:`ep_taylor_jet` in the generated module.
* The variational equations :math:`\dot w = J(x) w` are bilinear in ``(x, w)``
  (``J = df/dx`` differentiated by SymPy); with the jet of ``x`` known to the full
  order, the jet of each tangent vector follows from the same kind of Cauchy
  products: ``ep_taylor_tangent_jet``.
* A section function ``f(x)`` (:func:`andoyer.symbolic.sections.section_function`)
  is decomposed into sums with state-free coefficients, products and square roots
  (the norm ``|G|`` of the ``g`` and ``theta2`` angles); each gets the jet rule of its
  operation (for :math:`s = \sqrt{v}`:
  :math:`s^{[k]} = (v^{[k]} - \sum_{j=1}^{k-1} s^{[j]} s^{[k-j]}) / (2 s^{[0]})`), equal
  subexpressions share one jet: ``section_jet``. The area ``M = G . gamma``
  (:data:`andoyer.symbolic.sections.AREA`) is a first integral of (1): along the jet of
  a step its jet is its value (:math:`M^{[k]} = 0`, ``k >= 1``: the truncated series
  keep the polynomial identity :math:`\dot M = 0`), so it is one dot product at order 0
  (``DOT``) and a product with it a scaling (``SCALE``), not a Cauchy product.

The coefficients ``q`` that depend on the body are computed once per call by
``ep_taylor_constants`` (constants folded out of the step loop).

Regenerate with ``python -m andoyer.symbolic.taylor_codegen``.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

import sympy as sp

from andoyer.atomic import atomic_path
from andoyer.symbolic import attitude as att
from andoyer.symbolic import hamiltonian as sym
from andoyer.symbolic import sections as sec
from andoyer.symbolic.codegen import NumbaPrinter

__all__ = ["TAYLOR_PATH", "generate_taylor_source", "write_taylor", "field_terms",
           "tangent_terms", "attitude_terms"]

TAYLOR_PATH = (Path(__file__).resolve().parent.parent / "kernels" / "generated"
               / "recurrences.py")

S = sym.S
_W = sp.symbols("w1:7", real=True)  # a tangent vector, components in the order of S.y


def field_terms() -> list[list[tuple[tuple[int, ...], sp.Expr]]]:
    """For each component of (1): ``[(monomial exponents in S.y, coefficient), ...]``."""
    return [sorted(sp.Poly(f, *S.y).terms()) for f in sym.euler_poisson_field()]


def tangent_terms() -> list[list[tuple[tuple[int, ...], sp.Expr]]]:
    """For each component of ``J(y) w``: terms as :func:`field_terms`, exponents over
    ``(*S.y, *w)``."""
    J = sym.euler_poisson_jacobian()
    n = len(S.y)
    rows = [sp.expand(sum(J[n * i + j] * _W[j] for j in range(n))) for i in range(n)]
    return [sorted(sp.Poly(r, *S.y, *_W).terms()) for r in rows]


def attitude_terms() -> list[list[tuple[tuple[int, ...], sp.Expr]]]:
    """For each component of ``dq/dt = q (x) (0, I^-1 G) / 2``
    (:func:`andoyer.symbolic.attitude.attitude_field`): terms as :func:`field_terms`,
    exponents over ``(*S.y, *Q)`` (bilinear in ``(G, q)``)."""
    rows = att.attitude_field()[len(S.y):]
    return [sorted(sp.Poly(r, *S.y, *att.Q).terms()) for r in rows]


class _Constants:
    """State-free coefficients, numbered ``q0, q1, ...`` (up to sign, deduplicated)."""

    def __init__(self) -> None:
        self.exprs: list[sp.Expr] = []

    def ref(self, c: sp.Expr) -> str:
        """Code for the coefficient ``c``: ``q<i>`` or ``-q<i>`` or a number."""
        c = sp.factor(c)
        if c.is_number:
            return repr(float(c))
        for sign, e in ((1, c), (-1, -c)):
            e = sp.factor(e)
            if e in self.exprs:
                return f"{'-' if sign < 0 else ''}q{self.exprs.index(e)}"
        self.exprs.append(c)
        return f"q{len(self.exprs) - 1}"


def _monomial(exps: tuple[int, ...]) -> tuple[int, ...]:
    """The variable indices of a monomial, with repetition (``x0^2 x3 -> (0, 0, 3)``)."""
    return tuple(i for i, e in enumerate(exps) for _ in range(e))


def _poly_jet_body(rows: list[list[tuple[tuple[int, ...], sp.Expr]]], access: Sequence[str],
                   out: str, q: _Constants) -> list[str]:
    """Loop computing ``out`` jets of a polynomial field of degree <= 2 (see module notes).

    ``access[i]`` formats the jet of variable ``i`` at order ``{j}``.
    """
    products: list[tuple[int, int]] = []
    for row in rows:
        for exps, _ in row:
            mono = _monomial(exps)
            if len(mono) > 2:
                raise ValueError("the field is not of degree <= 2")
            if len(mono) == 2 and mono not in products:
                products.append((mono[0], mono[1]))
    lines = ["    for k in range(order):"]
    lines += [f"        m{i} = 0.0" for i in range(len(products))]
    lines.append("        for j in range(k + 1):")
    for i, (a, b) in enumerate(products):
        lines.append(f"            m{i} += {access[a].format(j='j')} * "
                     f"{access[b].format(j='k - j')}")
    for i, row in enumerate(rows):
        terms = []
        for exps, coeff in row:
            mono = _monomial(exps)
            if len(mono) == 0:
                raise ValueError("a constant term in a field without constant jets")
            v = (f"m{products.index((mono[0], mono[1]))}" if len(mono) == 2
                 else access[mono[0]].format(j="k"))
            terms.append((q.ref(coeff), v))
        rhs = _sum(terms)
        lines.append(f"        {out.format(i=i)} = ({rhs}) / (k + 1)")
    return lines


def _lane_jet_body(rows: list[list[tuple[tuple[int, ...], sp.Expr]]], arrays: Sequence[str],
                   out: str, q: _Constants) -> tuple[list[str], int]:
    """:func:`_poly_jet_body` over ``LANES`` orbits (``x[k, i, lane]``): each Cauchy
    product is a row ``m[product]`` of one call of :func:`andoyer.kernels.simd.cauchy`
    per order, the new coefficients one call of :func:`andoyer.kernels.simd.combine`
    (both vector code). ``arrays[i]`` names the array of variable ``i`` (its component
    ``i % 6``); ``out`` the array written."""
    products: list[tuple[int, int]] = []
    for row in rows:
        for exps, _ in row:
            mono = _monomial(exps)
            if len(mono) == 2 and mono not in products:
                products.append((mono[0], mono[1]))
    n = len(S.y)
    if len({(arrays[a], arrays[b]) for a, b in products}) != 1:
        raise ValueError("the products of a lane jet multiply one pair of arrays")
    u, v = arrays[products[0][0]], arrays[products[0][1]]
    triples = ", ".join(f"{i}, {a % n}, {b % n}" for i, (a, b) in enumerate(products))
    lines = ["    for k in range(order):", f"        cauchy(m, {u}, {v}, k, ({triples}))"]
    coefs: list[str] = []
    terms: list[int] = []
    for i, row in enumerate(rows):
        for exps, coeff in row:
            mono = _monomial(exps)
            c = q.ref(coeff)
            if c not in coefs:
                coefs.append(c)
            source = ((0, products.index((mono[0], mono[1]))) if len(mono) == 2
                      else (1, mono[0] % n))
            terms += [i, *source, coefs.index(c)]
    lines.insert(0, f"    c = ({', '.join(coefs)},)")
    lines.append(f"        combine({out}, m, k, c, ({', '.join(map(str, terms))}))")
    return lines, len(products)


def _sum(terms: Sequence[tuple[str, str]]) -> str:
    """Code of ``sum(c * v)`` for ``(c, v)`` code pairs, without ``1.0 *`` or ``+ -``."""
    out = ""
    for c, v in terms:
        neg = c.startswith("-")
        c = c[1:] if neg else c
        term = v if c == "1.0" else f"{c} * {v}"
        out += (" - " if neg else " + ") + term if out else ("-" if neg else "") + term
    return out or "0.0"


def _constants_source(q: _Constants) -> str:
    printer = NumbaPrinter()
    reps, reduced = sp.cse(q.exprs, symbols=sp.numbered_symbols("c"))
    args = ", ".join(str(s) for s in S.body)
    lines = [f"def ep_taylor_constants({args}):",
             '    """The body-dependent coefficients ``q`` of the jets (folded constants)."""']
    lines += [f"    {s} = {printer.doprint(e)}" for s, e in reps]
    lines.append("    return (" + "".join(f"{printer.doprint(e)}, " for e in reduced) + ")")
    return "\n".join(lines) + "\n"


def _unpack(q: _Constants) -> list[str]:
    return [f"    q{i} = q[{i}]" for i in range(len(q.exprs))]


def _dot_triples(e: sp.Expr) -> tuple[int, int]:
    """``(a, b)`` with ``e = sum_i y_{a+i} y_{b+i}`` (``i < 3``), a ``DOT`` row's operands."""
    for a in range(len(S.y) - 2):
        for b in range(a + 3, len(S.y) - 2):
            if sp.expand(e - sum(S.y[a + i] * S.y[b + i] for i in range(3))) == 0:
                return a, b
    raise ValueError(f"{e!r} is no dot product of two state triples")


#: Operations of a section tape (see :class:`_SectionTape`).
VAR, LIN, MUL, SQRT, DOT, SCALE = 0, 1, 2, 3, 4, 5


class _SectionTape:
    """A section function as a tape of jet operations (see the module notes).

    Row ``n`` of the tape is ``(op, a, b, ca, cb, cc)``; the jet of node ``n`` at order
    ``k`` is, by ``op``: ``VAR``: state component ``a``; ``LIN``:
    ``C[ca] u_a + C[cb] u_b`` (``b = -1``: no second term) plus ``C[cc]`` at ``k = 0``
    (``cc = -1``: none); ``MUL``: the Cauchy product of ``u_a`` and ``u_b``; ``SQRT``:
    the square root of ``u_a``; ``DOT``: a first integral, the dot product of the state
    triples from components ``a`` and ``b`` at ``k = 0``, zero above (the area
    :data:`~andoyer.symbolic.sections.AREA`); ``SCALE``: ``u_a^{[0]} u_b`` (``a`` a
    ``DOT`` node: the product with a first integral). ``C`` are state-free constants
    (slot 0 is 1); the last
    node is ``f``. One compiled interpreter runs every tape, so a new section kind costs
    no compilation.
    """

    def __init__(self) -> None:
        self.consts: list[sp.Expr] = [sp.Integer(1)]
        self.rows: list[tuple[int, int, int, int, int, int]] = []
        self.memo: dict[sp.Expr, int] = {}

    def const(self, e: sp.Expr) -> int:
        e = sp.sympify(e)
        if e in self.consts:
            return self.consts.index(e)
        self.consts.append(e)
        return len(self.consts) - 1

    def _row(self, *row: int) -> int:
        self.rows.append((row + (-1,) * 6)[:6])  # type: ignore[arg-type]
        return len(self.rows) - 1

    def node(self, e: sp.Expr) -> int:
        """Index of the node holding the jet of the state-dependent expression ``e``."""
        if e in self.memo:
            return self.memo[e]
        if e in S.y:
            n = self._row(VAR, S.y.index(e))
        elif e == sec.AREA:
            n = self._row(DOT, *_dot_triples(e))
        elif isinstance(e, sp.Add) or (isinstance(e, sp.Mul)
                                       and e.as_independent(*S.y, as_Add=False)[0] != 1):
            n = self._lin(e)
        elif isinstance(e, sp.Mul):
            nodes = [self.node(f) for f in e.as_ordered_factors()]
            integrals = [m for m in nodes if self.rows[m][0] == DOT]
            others = [m for m in nodes if self.rows[m][0] != DOT] or integrals[:1]
            n = others[0]
            for m in others[1:]:
                n = self._row(MUL, n, m)
            for m in integrals[1:] if others[0] in integrals else integrals:
                n = self._row(SCALE, m, n)
        elif isinstance(e, sp.Pow) and e.exp == sp.Rational(1, 2):
            n = self._row(SQRT, self.node(e.base))
        elif isinstance(e, sp.Pow) and e.exp.is_Integer and e.exp >= 2:
            base = self.node(e.base)
            n = base
            for _ in range(int(e.exp) - 1):
                n = self._row(MUL, n, base)
        else:
            raise ValueError(f"no jet rule for {e!r}")
        self.memo[e] = n
        return n

    def _lin(self, e: sp.Expr) -> int:
        const, dep = e.as_independent(*S.y, as_Add=True)
        terms = []
        for t in sp.Add.make_args(dep):
            c, d = t.as_independent(*S.y, as_Add=False)
            terms.append((self.const(c), self.node(d)))
        cc = self.const(const) if const != 0 else -1
        (ca, a), rest = terms[0], terms[1:]
        if not rest:
            return self._row(LIN, a, -1, ca, -1, cc)
        n = -1
        for i, (cb, b) in enumerate(rest):
            last = i == len(rest) - 1
            n = self._row(LIN, a, b, ca, cb, cc if last else -1)
            a, ca = n, 0
        return n

    def build(self, f: sp.Expr) -> None:
        f = sp.sympify(f)
        if not f.free_symbols & set(S.y):  # a constant: 0 * G1 + f
            self._row(LIN, self.node(S.y[0]), -1, self.const(0), -1, self.const(f))
            return
        n = self.node(f)
        if n != len(self.rows) - 1:  # the last row must be f
            self._row(LIN, n, -1, 0, -1, -1)


def _tapes_source(name: str, doc: str, which: int) -> tuple[str, int, int]:
    """``<NAME>_TAPES`` and ``<name>_constants`` for the section functions (``which = 0``),
    their margins (``which = 1``) or the reduced section functions where ``sin(value)``
    (``which = 2``) or ``cos(value)`` (``which = 3``) vanishes
    (:func:`andoyer.symbolic.sections.section_function_reduced`; an empty tape where there
    is none)."""
    kinds = [*sec.SMOOTH, *sec.ANGLES, *sec.EXTRA_ANGLES]
    printer = NumbaPrinter()
    args = ", ".join(str(a) for a in sec.SECTION_ARGS[len(S.y):])
    tapes = [f"#: {doc}, one tape per section kind: rows (op, a, b, ca, cb, cc), ops",
             "#: VAR, LIN, MUL, SQRT, DOT, SCALE = 0 .. 5 (see andoyer.symbolic.taylor_codegen).",
             f"{name.upper()}_TAPES = ("]
    consts = [f"def {name}_constants(kind, {args}):",
              f'    """The constants ``C`` of the tape of {name.upper()}_TAPES[kind]."""']
    nodes = n_consts = 0
    for i, kind in enumerate(kinds):
        expr = (sec.section_function(kind)[which] if which < 2
                else sec.section_function_reduced(kind, sec.VANISHING[which - 2]))
        if expr is None:  # no tape of its own: the kind's section function
            tapes.append(f"    (),  # {kind}")
            consts.append(f"    {'if' if i == 0 else 'elif'} kind == {i}:  # {kind}")
            consts.append("        return ()")
            continue
        tape = _SectionTape()
        tape.build(expr)
        nodes = max(nodes, len(tape.rows))
        n_consts = max(n_consts, len(tape.consts))
        tapes.append(f"    (  # {kind}")
        tapes += [f"        {row!r}," for row in tape.rows]
        tapes.append("    ),")
        values = "".join(f"{printer.doprint(c) if not c.is_number else repr(float(c))}, "
                         for c in tape.consts)
        consts.append(f"    {'if' if i == 0 else 'elif'} kind == {i}:  # {kind}")
        consts.append(f"        return ({values})")
    consts.append("    raise ValueError(f'no section kind {kind}')")
    tapes.append(")")
    return "\n".join(tapes) + "\n\n\n" + "\n".join(consts) + "\n", nodes, n_consts


def generate_taylor_source() -> str:
    """The text of ``generated/recurrences.py`` (runs SymPy; a few seconds)."""
    q = _Constants()
    y_access = [f"x[{{j}}, {i}]" for i in range(len(S.y))]
    field = ["def ep_taylor_jet(x, order, q):",
             '    """Jet of the solution of (1): ``x[1 .. order]`` from ``x[0]`` (the state); '
             '``q`` = ep_taylor_constants(*body)."""']
    field_loop = _poly_jet_body(field_terms(), y_access, "x[k + 1, {i}]", q)
    w_access = [*y_access, *(f"w[{{j}}, {i}]" for i in range(len(S.y)))]
    tangent = ["def ep_taylor_tangent_jet(x, w, order, q):",
               '    """Jet of a tangent vector ``w`` (dw/dt = J(x) w, J of (1)): '
               '``w[1 .. order]`` from ``w[0]``, along the full jet ``x``."""']
    tangent_loop = _poly_jet_body(tangent_terms(), w_access, "w[k + 1, {i}]", q)
    q_access = [*y_access, *(f"w[{{j}}, {i}]" for i in range(len(att.Q)))]
    attitude = ["def ep_taylor_attitude_jet(x, w, order, q):",
                '    """Jet of the attitude quaternion ``w[:, 0:4]`` (dq/dt = q (x) (0, I^-1 G)/2, '
                'scalar first): ``w[1 .. order, 0:4]`` from ``w[0]``, along the full jet '
                '``x``."""']
    attitude_loop = _poly_jet_body(attitude_terms(), q_access, "w[k + 1, {i}]", q)
    lane_field, n_field = _lane_jet_body(field_terms(), ["x"] * len(S.y), "x", q)
    lane_tangent, n_tangent = _lane_jet_body(tangent_terms(),
                                             ["x"] * len(S.y) + ["w"] * len(S.y), "w", q)
    lanes = ["def ep_taylor_jet_lanes(x, order, q, m):",
             '    """ep_taylor_jet of LANES orbits: ``x[k, i, lane]``; ``m`` scratch '
             '(LANE_PRODUCTS, LANES)."""', *_unpack(q), *lane_field]
    lanes_w = ["def ep_taylor_tangent_jet_lanes(x, w, order, q, m):",
               '    """ep_taylor_tangent_jet of LANES orbits: ``w[k, i, lane]`` along '
               '``x[k, i, lane]``; ``m`` as ep_taylor_jet_lanes."""', *_unpack(q),
               *lane_tangent]
    field += _unpack(q) + field_loop
    tangent += _unpack(q) + tangent_loop
    attitude += _unpack(q) + attitude_loop
    section, nodes, n_consts = _tapes_source("section", "Section functions f", 0)
    margin, m_nodes, m_consts = _tapes_source("margin", "Margins w of the sections", 1)
    sin_zero, _, _ = _tapes_source("sin_zero", "Section functions f where sin(value) = 0, "
                                   "over their factor ``|G|`` (empty: the kind's f)", 2)
    cos_zero, _, _ = _tapes_source("cos_zero", "Section functions f where cos(value) = 0 "
                                   "(empty: the kind's f)", 3)
    head = [
        '"""Taylor jets generated by andoyer.symbolic.taylor_codegen from the field (1)',
        "and the section functions.",
        "",
        "DO NOT EDIT: regenerate with ``python -m andoyer.symbolic.taylor_codegen``.",
        "Plain loops on float arrays, compiled by Numba in andoyer.kernels.taylor.flow.",
        '"""',
        "",
        "{imports}",
        "",
        f"SYMPY_VERSION = {sp.__version__!r}",
        "#: Number of body-dependent coefficients returned by ep_taylor_constants.",
        f"N_CONSTANTS = {len(q.exprs)}",
        "#: Most nodes and constants of a section tape.",
        f"TAPE_NODES = {max(nodes, m_nodes)}",
        f"TAPE_CONSTANTS = {max(n_consts, m_consts)}",
        "#: Scratch rows of the lane jets (one per Cauchy product).",
        f"LANE_PRODUCTS = {max(n_field, n_tangent)}",
        "",
        "",
    ]
    body = [_constants_source(q), "\n".join(field) + "\n", "\n".join(tangent) + "\n",
            "\n".join(attitude) + "\n", "\n".join(lanes) + "\n", "\n".join(lanes_w) + "\n",
            section, margin, sin_zero, cos_zero]
    text = "\n\n".join(body)
    used = [f for f in ("cos", "sin", "sqrt") if f"{f}(" in text]
    imports = f"from math import {', '.join(used)}\n\n" if used else ""
    imports += "from andoyer.kernels.simd import cauchy, combine"
    return "\n".join(head).replace("{imports}", imports) + text


def write_taylor(path: Path = TAYLOR_PATH) -> Path:
    """Write the generated module atomically.

    Parameters
    ----------
    path : pathlib.Path, default the package's ``kernels/generated/recurrences.py``
        Where to write.
    """
    src = generate_taylor_source()
    with atomic_path(path) as tmp:
        tmp.write_text(src)
    return path


if __name__ == "__main__":  # pragma: no cover
    out = write_taylor(Path(sys.argv[1]) if len(sys.argv) > 1 else TAYLOR_PATH)
    print(f"wrote {out}")
