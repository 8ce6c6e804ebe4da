r"""The Cauchy product of lane jets as explicit SIMD code (one vector per lane row).

The lane jets (``ep_taylor_jet_lanes`` and ``ep_taylor_tangent_jet_lanes`` of
:mod:`andoyer.kernels.generated.recurrences`) hold :data:`LANES` orbits in the last,
contiguous axis of ``x[k, i, lane]``. Their work is the Cauchy products of the
recurrences of the field (1),

.. math:: m_{\text{lane}} = \sum_{j=0}^{k} u^{[j]}_{a,\text{lane}}\, v^{[k-j]}_{b,\text{lane}},

the same sum in every lane. Numba leaves such a loop scalar: its lane loop of
constant trip count is unrolled before LLVM's loop vectoriser sees it, and Numba
disables the SLP vectoriser by default (plain lane loops ran slower per orbit than the
scalar jets, whatever the layout, and enabling SLP globally slows the scalar kernels;
measured: benchmarks/NOTES.md#taylor-lanes). :func:`cauchy` is therefore an intrinsic
that writes the
vector code itself: one ``<LANES x double>`` accumulator, two vector loads and one
fused multiply-add per ``j`` (the scalar jets' ``contract`` flag fuses the same
multiply-add, in the same order of ``j``).

Plain Python when Numba is disabled (:func:`cauchy` is an ordinary function whose
compiled version is the intrinsic, through :func:`numba.extending.overload`).
"""

from __future__ import annotations

import functools
from typing import Any

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic, overload

__all__ = ["LANES", "cauchy", "combine", "advance"]

#: Orbits per vector (one AVX-512 register of doubles; two AVX2 ones).
LANES = 8


def cauchy(m: Any, u: Any, v: Any, k: int, products: tuple[int, ...]) -> None:
    """The Cauchy products ``m[r, :] = sum_j u[j, a, :] * v[k - j, b, :]`` over
    ``0 <= j <= k`` (lane vectors), for each triple ``(r, a, b)`` of ``products``.

    Parameters
    ----------
    m : ndarray, shape (rows, LANES)
        The products (C-contiguous).
    u, v : ndarray, shape (order + 1, 6, LANES)
        Lane jets (C-contiguous; may be the same array).
    k : int
        The order of the products.
    products : tuple of int
        ``(r0, a0, b0, r1, a1, b1, ...)``: row of ``m``, component of ``u``, component
        of ``v`` of each product.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.ones((3, 6, LANES))
    >>> m = np.zeros((2, LANES))
    >>> cauchy(m, x, x, 2, (0, 1, 2, 1, 0, 0))
    >>> float(m[0, 0]), float(m[1, 7])
    (3.0, 3.0)
    """
    for i in range(0, len(products), 3):
        r, a, b = products[i:i + 3]
        s = u[0, a] * v[k, b]
        for j in range(1, k + 1):
            s = s + u[j, a] * v[k - j, b]
        m[r] = s


def _cauchy_typer(typingctx: Any, m: Any, u: Any, v: Any, k: Any, products: Any) -> Any:
    """The vector code of :func:`cauchy` (arguments as there): one loop over ``j``, one
    vector accumulator per product (independent chains of fused multiply-adds: a single
    chain waits out the multiply-add's latency at every ``j``; measured:
    benchmarks/NOTES.md#taylor-lanes)."""
    sig = types.void(m, u, v, k, products)
    n = len(products) // 3

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        mt, ut, vt, kt, pt = signature.args
        m_, u_, v_, k_, p_ = args
        intp = context.get_value_type(types.intp)
        triple = [context.cast(builder, e, t, types.intp)
                  for e, t in zip(cgutils.unpack_tuple(builder, p_, len(pt)), pt, strict=True)]

        def pointer(aryty: Any, ary: Any, inds: list[Any]) -> Any:
            arr = context.make_array(aryty)(context, builder, ary)
            return cgutils.get_item_pointer2(
                context, builder, data=arr.data, shape=cgutils.unpack_tuple(builder, arr.shape),
                strides=cgutils.unpack_tuple(builder, arr.strides), layout=aryty.layout,
                inds=inds)

        vec = ir.VectorType(ir.DoubleType(), LANES)
        fma = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(vec, [vec, vec, vec]), f"llvm.fma.v{LANES}f64")
        zero = ir.Constant(intp, 0)
        k_i = context.cast(builder, k_, kt, types.intp)

        def load(p: Any) -> Any:
            return builder.load(builder.bitcast(p, vec.as_pointer()), align=8)

        accs = [cgutils.alloca_once_value(builder, ir.Constant(vec, [0.0] * LANES))
                for _ in range(n)]
        count = builder.add(k_i, ir.Constant(intp, 1))
        with cgutils.for_range(builder, count, intp=intp) as loop:
            j = loop.index
            kj = builder.sub(k_i, j)
            for p in range(n):
                pu = pointer(ut, u_, [j, triple[3 * p + 1], zero])
                pv = pointer(vt, v_, [kj, triple[3 * p + 2], zero])
                builder.store(builder.call(fma, [load(pu), load(pv), builder.load(accs[p])]),
                              accs[p])
        for p in range(n):
            pm = pointer(mt, m_, [triple[3 * p], zero])
            builder.store(builder.load(accs[p]), builder.bitcast(pm, vec.as_pointer()), align=8)
        return context.get_dummy_value()

    return sig, codegen


_cauchy: Any = intrinsic(_cauchy_typer)


def combine(y: Any, m: Any, k: int, c: tuple[float, ...], terms: tuple[int, ...]) -> None:
    """``y[k + 1, i, :] = sum c[ci] * s / (k + 1)`` over the terms ``(i, kind, idx, ci)``
    of output component ``i``, ``s`` = ``m[idx]`` (``kind`` 0) or ``y[k, idx]`` (1).

    Parameters
    ----------
    y : ndarray, shape (order + 1, 6, LANES)
        Lane jets; row ``k + 1`` is written.
    m : ndarray, shape (rows, LANES)
        Cauchy products (:func:`cauchy`).
    k : int
        The order of the sources.
    c : tuple of float
        Coefficients.
    terms : tuple of int
        ``(i, kind, idx, ci, ...)``, grouped by ``i`` (each ``i`` once at least).

    Examples
    --------
    >>> import numpy as np
    >>> y = np.ones((2, 6, LANES))
    >>> m = np.full((1, LANES), 3.0)
    >>> combine(y, m, 0, (2.0,), (0, 0, 0, 0, 0, 1, 5, 0) + tuple(
    ...     v for i in range(1, 6) for v in (i, 1, i, 0)))
    >>> float(y[1, 0, 0]), float(y[1, 5, 3])
    (8.0, 2.0)
    """
    rows: dict[int, Any] = {}
    for t in range(0, len(terms), 4):
        i, kind, idx, ci = terms[t:t + 4]
        s = c[ci] * (m[idx] if kind == 0 else y[k, idx])
        rows[i] = s if i not in rows else rows[i] + s
    for i, s in rows.items():
        y[k + 1, i] = s / (k + 1)


@functools.cache
def _combine(ints: tuple[int, ...]) -> Any:
    """The vector code of :func:`combine` for the terms ``ints`` (one intrinsic per
    tuple of terms, which decide the code: a compile-time constant)."""
    return intrinsic(functools.partial(_combine_typer, ints))


def _combine_typer(ints: tuple[int, ...], typingctx: Any, y: Any, m: Any, k: Any,
                   c: Any) -> Any:
    sig = types.void(y, m, k, c)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        yt, mt, kt, ct = signature.args
        y_, m_, k_, c_ = args
        intp = context.get_value_type(types.intp)
        coefs = [context.cast(builder, e, t, types.float64)
                 for e, t in zip(cgutils.unpack_tuple(builder, c_, len(ct)), ct, strict=True)]
        vec = ir.VectorType(ir.DoubleType(), LANES)
        fma = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(vec, [vec, vec, vec]), f"llvm.fma.v{LANES}f64")
        zero = ir.Constant(intp, 0)
        k_i = context.cast(builder, k_, kt, types.intp)
        k1 = builder.add(k_i, ir.Constant(intp, 1))

        def pointer(aryty: Any, ary: Any, inds: list[Any]) -> Any:
            arr = context.make_array(aryty)(context, builder, ary)
            p = cgutils.get_item_pointer2(
                context, builder, data=arr.data, shape=cgutils.unpack_tuple(builder, arr.shape),
                strides=cgutils.unpack_tuple(builder, arr.strides), layout=aryty.layout,
                inds=inds)
            return builder.bitcast(p, vec.as_pointer())

        def splat(x: Any) -> Any:
            v = ir.Constant(vec, ir.Undefined)
            for lane in range(LANES):
                v = builder.insert_element(v, x, ir.Constant(ir.IntType(32), lane))
            return v

        rows: dict[int, Any] = {}
        for t in range(0, len(ints), 4):
            i, kind, idx, ci = ints[t:t + 4]
            src = (pointer(mt, m_, [ir.Constant(intp, idx), zero]) if kind == 0
                   else pointer(yt, y_, [k_i, ir.Constant(intp, idx), zero]))
            value = builder.load(src, align=8)
            coef = splat(coefs[ci])
            rows[i] = (builder.fmul(coef, value) if i not in rows
                       else builder.call(fma, [coef, value, rows[i]]))
        div = splat(builder.sitofp(k1, ir.DoubleType()))
        for i, acc in rows.items():
            dst = pointer(yt, y_, [k1, ir.Constant(intp, i), zero])
            builder.store(builder.fdiv(acc, div), dst, align=8)
        return context.get_dummy_value()

    return sig, codegen


def _literal_ints(ty: Any) -> list[int]:
    """The values of a tuple type of integer literals (``TypingError`` otherwise)."""
    from numba.core.errors import TypingError

    values = [getattr(e, "literal_value", None) for e in ty]
    if any(not isinstance(v, int) for v in values):
        raise TypingError(f"combine's terms must be integer literals, got {ty}")
    return values  # type: ignore[return-value]


@overload(combine, jit_options={"nogil": True}, prefer_literal=True)
def _combine_overload(y: Any, m: Any, k: Any, c: Any, terms: Any) -> Any:
    """Compiled :func:`combine`: the intrinsic."""
    for ary in (y, m):
        if not (isinstance(ary, types.Array) and ary.dtype == types.float64
                and ary.layout == "C"):
            return None

    code = _combine(tuple(_literal_ints(terms)))

    def impl(y: Any, m: Any, k: Any, c: Any, terms: Any) -> None:
        code(y, m, k, c)

    return impl


@overload(cauchy, jit_options={"nogil": True})
def _cauchy_overload(m: Any, u: Any, v: Any, k: Any, products: Any) -> Any:
    """Compiled :func:`cauchy`: the intrinsic (C-contiguous float64 arrays only)."""
    for ary in (m, u, v):
        if not (isinstance(ary, types.Array) and ary.dtype == types.float64
                and ary.layout == "C"):
            return None

    def impl(m: Any, u: Any, v: Any, k: Any, products: Any) -> None:
        _cauchy(m, u, v, k, products)

    return impl


def advance(X: Any, order: int, h: Any) -> None:
    """Rows 0 of the lane jets ``X[b, k, i, lane]`` = their polynomials at ``h[lane]``
    (Horner: ``v = v h + X[b, k]`` from ``k = order``).

    Parameters
    ----------
    X : ndarray, shape (blocks, order + 1, 6, LANES)
        Lane jets (C-contiguous).
    order : int
        Their order.
    h : ndarray, shape (LANES,)
        The step of each lane.

    Examples
    --------
    >>> import numpy as np
    >>> X = np.ones((1, 3, 6, LANES))
    >>> advance(X, 2, np.full(LANES, 2.0))
    >>> float(X[0, 0, 5, 7])
    7.0
    """
    for b in range(X.shape[0]):
        v = X[b, order].copy()
        for k in range(order - 1, -1, -1):
            v = v * h + X[b, k]
        X[b, 0] = v


def _advance_typer(typingctx: Any, X: Any, order: Any, h: Any) -> Any:
    """The vector code of :func:`advance`: the six components of a block as six
    independent chains of fused multiply-adds."""
    sig = types.void(X, order, h)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        xt, ot, ht = signature.args
        x_, o_, h_ = args
        intp = context.get_value_type(types.intp)
        vec = ir.VectorType(ir.DoubleType(), LANES)
        fma = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(vec, [vec, vec, vec]), f"llvm.fma.v{LANES}f64")
        arr = context.make_array(xt)(context, builder, x_)
        shape = cgutils.unpack_tuple(builder, arr.shape)
        strides = cgutils.unpack_tuple(builder, arr.strides)
        harr = context.make_array(ht)(context, builder, h_)
        order_i = context.cast(builder, o_, ot, types.intp)
        zero = ir.Constant(intp, 0)

        def pointer(b: Any, k: Any, i: int) -> Any:
            p = cgutils.get_item_pointer2(context, builder, data=arr.data, shape=shape,
                                          strides=strides, layout=xt.layout,
                                          inds=[b, k, ir.Constant(intp, i), zero])
            return builder.bitcast(p, vec.as_pointer())

        hv = builder.load(builder.bitcast(harr.data, vec.as_pointer()), align=8)
        accs = [cgutils.alloca_once(builder, vec) for _ in range(6)]
        with cgutils.for_range(builder, shape[0], intp=intp) as block:
            b = block.index
            for i in range(6):
                builder.store(builder.load(pointer(b, order_i, i), align=8), accs[i])
            with cgutils.for_range(builder, order_i, intp=intp) as loop:
                k = builder.sub(builder.sub(order_i, loop.index), ir.Constant(intp, 1))
                for i in range(6):
                    term = builder.load(pointer(b, k, i), align=8)
                    builder.store(builder.call(fma, [builder.load(accs[i]), hv, term]), accs[i])
            for i in range(6):
                builder.store(builder.load(accs[i]), pointer(b, zero, i), align=8)
        return context.get_dummy_value()

    return sig, codegen


_advance: Any = intrinsic(_advance_typer)


@overload(advance, jit_options={"nogil": True})
def _advance_overload(X: Any, order: Any, h: Any) -> Any:
    """Compiled :func:`advance`: the intrinsic (C-contiguous float64 arrays only)."""
    for ary in (X, h):
        if not (isinstance(ary, types.Array) and ary.dtype == types.float64
                and ary.layout == "C"):
            return None

    def impl(X: Any, order: Any, h: Any) -> None:
        _advance(X, order, h)

    return impl
