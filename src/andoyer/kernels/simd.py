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

The lane count :data:`LANES` is one vector register of doubles of the CPU the code is
compiled for, chosen once, when this module is imported (:func:`lane_width`): 8 where
the CPU has AVX-512, 4 with AVX or AVX2, 2 otherwise; the environment variable
:data:`LANES_ENV` (``ANDOYER_LANES``: 2, 4, 8 or 16) overrides it, e.g. to measure one
width on a CPU that has another, or where ``NUMBA_CPU_NAME`` compiles for another CPU.
The width enters the cache key of every entry point compiled with it
(:mod:`andoyer.kernels.taylor.lanes`), and the results agree across widths to
round-off: each lane's arithmetic does not depend on how many lanes run beside it.
So does the CPU model the vector code is tuned for (:func:`lane_tuning`, :func:`tune`:
on AMD Zen an Intel model's scheduling, 2-4x faster lane jets).
"""

from __future__ import annotations

import functools
import math
import os
from collections.abc import Mapping
from typing import Any

import numpy as np
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic, overload

from andoyer.kernels.common import kernel_jit

__all__ = ["LANES", "LANES_ENV", "WIDTHS", "lane_width", "TUNE", "TUNE_ENV", "lane_tuning",
           "tune", "cauchy", "combine", "advance", "series_product", "series_linear",
           "ROOT_SHORTFALL", "root", "roots", "series_dot", "megno_orders"]

#: Environment variable that sets the lane count (one of :data:`WIDTHS`).
LANES_ENV = "ANDOYER_LANES"
#: Lane counts the vector code may be compiled for.
WIDTHS = (2, 4, 8, 16)


def lane_width(environ: Mapping[str, str] | None = None,
               features: Mapping[str, bool] | None = None) -> int:
    """Orbits per vector: :data:`LANES_ENV` if set, else one vector register of doubles
    of the CPU (8 with AVX-512, 4 with AVX or AVX2, else 2).

    Parameters
    ----------
    environ : mapping, optional
        The environment (default ``os.environ``).
    features : mapping, optional
        CPU features by LLVM's names (default the host's,
        :func:`llvmlite.binding.get_host_cpu_features`).

    Returns
    -------
    int
        One of :data:`WIDTHS`.

    Raises
    ------
    ValueError
        If :data:`LANES_ENV` is set to something else than one of :data:`WIDTHS`.

    Examples
    --------
    >>> lane_width({}, {"avx512f": True, "avx2": True})
    8
    >>> lane_width({}, {"avx512f": False, "avx2": True}), lane_width({}, {})
    (4, 2)
    >>> lane_width({"ANDOYER_LANES": "4"}, {"avx512f": True})
    4
    """
    value = (os.environ if environ is None else environ).get(LANES_ENV, "").strip()
    if value:
        if value not in {str(w) for w in WIDTHS}:
            raise ValueError(f"{LANES_ENV}={value!r}: the lane count must be one of "
                             f"{', '.join(map(str, WIDTHS))}")
        return int(value)
    if features is None:
        import llvmlite.binding as ll

        features = dict(ll.get_host_cpu_features())
    if features.get("avx512f"):
        return 8
    if features.get("avx2") or features.get("avx"):
        return 4
    return 2


#: Orbits per vector: one vector register of doubles of this CPU (:func:`lane_width`).
LANES = lane_width()

#: Environment variable that sets the CPU model the lanes' code is tuned for
#: (:func:`lane_tuning`).
TUNE_ENV = "ANDOYER_LANE_TUNE"


def lane_tuning(environ: Mapping[str, str] | None = None, cpu: str | None = None) -> str:
    """The CPU model whose instruction scheduling the lane kernels are compiled with
    (LLVM's per-function ``tune-cpu``; the instructions themselves stay those of the
    CPU), or ``""`` for the target CPU's own.

    On AMD Zen (LLVM's ``znver*``), whose scheduling models made LLVM spill the lane
    jets' addresses and run their Cauchy products 2-4x slower than under an Intel
    model (measured: benchmarks/NOTES.md#lane-width), ``"haswell"``; elsewhere ``""``.
    :data:`TUNE_ENV` (``ANDOYER_LANE_TUNE``) overrides it: a CPU name LLVM knows, or
    ``host`` for the CPU's own.

    Parameters
    ----------
    environ : mapping, optional
        The environment (default ``os.environ``).
    cpu : str, optional
        The CPU Numba compiles for (default ``NUMBA_CPU_NAME``, else the host's,
        :func:`llvmlite.binding.get_host_cpu_name`).

    Returns
    -------
    str
        A CPU name, or ``""``.

    Examples
    --------
    >>> lane_tuning({}, "znver4"), lane_tuning({}, "skylake-avx512")
    ('haswell', '')
    >>> lane_tuning({"ANDOYER_LANE_TUNE": "host"}, "znver4")
    ''
    >>> lane_tuning({"ANDOYER_LANE_TUNE": "icelake-server"}, "znver4")
    'icelake-server'
    """
    value = (os.environ if environ is None else environ).get(TUNE_ENV, "").strip()
    if value:
        return "" if value == "host" else value
    if cpu is None:
        cpu = (os.environ if environ is None else environ).get("NUMBA_CPU_NAME", "").strip()
        if not cpu or cpu == "host":
            import llvmlite.binding as ll

            cpu = str(ll.get_host_cpu_name())
    return "haswell" if cpu.startswith("znver") else ""


#: The CPU model the lanes' code is tuned for (:func:`lane_tuning`; ``""``: the CPU's own).
TUNE = lane_tuning()
if any(c in TUNE for c in '"\\ '):
    raise ValueError(f"{TUNE_ENV}={TUNE!r} is not a CPU name")


def _c_float64(*arrays: Any, ndim: int | None = None) -> bool:
    """Whether every Numba type of ``arrays`` is a C-contiguous float64 array (of ``ndim``
    dimensions where given): what an intrinsic's overload takes, else it declines."""
    return all(isinstance(a, types.Array) and a.dtype == types.float64 and a.layout == "C"
               and (ndim is None or a.ndim == ndim) for a in arrays)


def _vector_fma(builder: Any) -> tuple[Any, Any]:
    """The lane vector type and LLVM's fused multiply-add on it, declared in the module of
    ``builder``."""
    vec = ir.VectorType(ir.DoubleType(), LANES)
    fma = cgutils.get_or_insert_function(
        builder.module, ir.FunctionType(vec, [vec, vec, vec]), f"llvm.fma.v{LANES}f64")
    return vec, fma


def _tune(builder: Any) -> None:
    """Mark the function being lowered with the tuning :data:`TUNE`."""
    attributes = builder.function.attributes
    # llvmlite lists the attribute names it knows; a set is what it builds on (checked,
    # so that another llvmlite only loses the tuning, a hint, never the kernel).
    if TUNE and isinstance(attributes, set):
        set.add(attributes, f'"tune-cpu"="{TUNE}"')


def tune() -> None:
    """Compile the calling function with the lanes' tuning :data:`TUNE` (LLVM's
    ``tune-cpu`` attribute; nothing in Python): every lane kernel calls it, so the
    tuning holds wherever LLVM inlines them.

    Examples
    --------
    >>> tune()
    """


def _tune_typer(typingctx: Any) -> Any:
    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        _tune(builder)
        return context.get_dummy_value()

    return types.void(), codegen


_tune_intrinsic: Any = intrinsic(_tune_typer)


@overload(tune, jit_options={"nogil": True})
def _tune_overload() -> Any:
    def impl() -> None:
        _tune_intrinsic()

    return impl


def cauchy(m: Any, u: Any, v: Any, k: int, products: tuple[int, ...]) -> None:
    """The Cauchy products ``m[r, :] = sum_j u[j, a, :] * v[k - j, b, :]`` over
    ``0 <= j <= k`` (lane vectors), for each triple ``(r, a, b)`` of ``products``.

    Parameters
    ----------
    m : ndarray, shape (rows, LANES)
        The products (C-contiguous): ``m[r]``.
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
    >>> float(m[0, 0]), float(m[1, LANES - 1])
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
        _tune(builder)
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

        vec, fma = _vector_fma(builder)
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
    >>> float(y[1, 0, 0]), float(y[1, 5, LANES - 1])
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
        _tune(builder)
        yt, mt, kt, ct = signature.args
        y_, m_, k_, c_ = args
        intp = context.get_value_type(types.intp)
        coefs = [context.cast(builder, e, t, types.float64)
                 for e, t in zip(cgutils.unpack_tuple(builder, c_, len(ct)), ct, strict=True)]
        vec, fma = _vector_fma(builder)
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
    if not _c_float64(y, m):
        return None

    code = _combine(tuple(_literal_ints(terms)))

    def impl(y: Any, m: Any, k: Any, c: Any, terms: Any) -> None:
        code(y, m, k, c)

    return impl


@overload(cauchy, jit_options={"nogil": True})
def _cauchy_overload(m: Any, u: Any, v: Any, k: Any, products: Any) -> Any:
    """Compiled :func:`cauchy`: the intrinsic (C-contiguous float64 arrays only)."""
    if not _c_float64(m, u, v):
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
    >>> float(X[0, 0, 5, LANES - 1])
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
        _tune(builder)
        xt, ot, ht = signature.args
        x_, o_, h_ = args
        intp = context.get_value_type(types.intp)
        vec, fma = _vector_fma(builder)
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
    if not _c_float64(X, h):
        return None

    def impl(X: Any, order: Any, h: Any) -> None:
        _advance(X, order, h)

    return impl


def series_product(U: Any, n: int, a: int, b: int, order: int) -> None:
    """``U[k, n, :] = sum_{j <= k} U[j, a, :] * U[k - j, b, :]`` for ``k = 0 .. order``:
    the product node of a section tape on lane jets (the lane counterpart of
    :func:`andoyer.kernels.taylor.sections.cauchy`).

    Parameters
    ----------
    U : ndarray, shape (order + 1, nodes, LANES)
        The tape's lane jets (C-contiguous); row ``n`` is written, rows ``a, b < n``
        read.
    n, a, b : int
        The product's node and its two factors.
    order : int
        The highest order.

    Examples
    --------
    >>> import numpy as np
    >>> U = np.zeros((3, 3, LANES))
    >>> U[:, 0] = 1.0
    >>> U[:, 1] = 2.0
    >>> series_product(U, 2, 0, 1, 2)
    >>> U[:, 2, 0].tolist()
    [2.0, 4.0, 6.0]
    """
    for k in range(order + 1):
        s = U[0, a] * U[k, b]
        for j in range(1, k + 1):
            s = s + U[j, a] * U[k - j, b]
        U[k, n] = s


def _series_product_typer(typingctx: Any, U: Any, n: Any, a: Any, b: Any, order: Any) -> Any:
    """The vector code of :func:`series_product`: four orders ``k0 .. k0 + 3`` at a time
    (four independent chains of fused multiply-adds, as the scalar tape's products),
    each order's sum over ``j`` in ascending order. The four factors ``U[k0 + i - j, b]``
    of one ``j`` are three of the previous ``j``'s, shifted: kept in registers, so a
    step of ``j`` loads two vectors for four multiply-adds (the loads, not the
    multiply-adds, bound the lane jets)."""
    sig = types.void(U, n, a, b, order)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        _tune(builder)
        ut, nt, at, bt, ot = signature.args
        u_, n_, a_, b_, o_ = args
        intp = context.get_value_type(types.intp)
        vec, fma = _vector_fma(builder)
        arr = context.make_array(ut)(context, builder, u_)
        shape = cgutils.unpack_tuple(builder, arr.shape)
        strides = cgutils.unpack_tuple(builder, arr.strides)
        n_i = context.cast(builder, n_, nt, types.intp)
        a_i = context.cast(builder, a_, at, types.intp)
        b_i = context.cast(builder, b_, bt, types.intp)
        order_i = context.cast(builder, o_, ot, types.intp)
        zero = ir.Constant(intp, 0)

        def const(v: int) -> Any:
            return ir.Constant(intp, v)

        def pointer(k: Any, node: Any) -> Any:
            p = cgutils.get_item_pointer2(context, builder, data=arr.data, shape=shape,
                                          strides=strides, layout=ut.layout,
                                          inds=[k, node, zero])
            return builder.bitcast(p, vec.as_pointer())

        def load(k: Any, node: Any) -> Any:
            return builder.load(pointer(k, node), align=8)

        accs = [cgutils.alloca_once(builder, vec) for _ in range(4)]
        ys = [cgutils.alloca_once(builder, vec) for _ in range(4)]
        zvec = ir.Constant(vec, [0.0] * LANES)
        count = builder.add(order_i, const(1))
        groups = builder.sdiv(count, const(4))
        with cgutils.for_range(builder, groups, intp=intp) as group:
            k0 = builder.mul(group.index, const(4))
            for i in range(4):
                builder.store(zvec, accs[i])
                builder.store(load(builder.add(k0, const(i)), b_i), ys[i])
            with cgutils.for_range(builder, builder.add(k0, const(1)), intp=intp) as loop:
                j = loop.index
                x = load(j, a_i)
                y = [builder.load(p) for p in ys]
                for i in range(4):
                    builder.store(builder.call(fma, [x, y[i], builder.load(accs[i])]), accs[i])
                # the next j's factors: U[k0 - j - 1, b] (row 0 again after the last j,
                # unused), then this j's first three
                nxt = builder.sub(builder.sub(k0, j), const(1))
                nxt = builder.select(builder.icmp_signed("<", nxt, zero), zero, nxt)
                builder.store(load(nxt, b_i), ys[0])
                for i in range(1, 4):
                    builder.store(y[i - 1], ys[i])
            for r in range(1, 4):  # the triangle of orders k0 + 1 .. k0 + 3 past j = k0
                x = load(builder.add(k0, const(r)), a_i)
                for i in range(r, 4):
                    y0 = load(const(i - r), b_i)
                    builder.store(builder.call(fma, [x, y0, builder.load(accs[i])]), accs[i])
            for i, acc in enumerate(accs):
                builder.store(builder.load(acc), pointer(builder.add(k0, const(i)), n_i),
                              align=8)
        start = builder.mul(groups, const(4))
        with cgutils.for_range_slice(builder, start, count, const(1), intp=intp) as (k, _):
            builder.store(zvec, accs[0])
            with cgutils.for_range(builder, builder.add(k, const(1)), intp=intp) as loop:
                j = loop.index
                x = load(j, a_i)
                y0 = load(builder.sub(k, j), b_i)
                builder.store(builder.call(fma, [x, y0, builder.load(accs[0])]), accs[0])
            builder.store(builder.load(accs[0]), pointer(k, n_i), align=8)
        return context.get_dummy_value()

    return sig, codegen


_series_product: Any = intrinsic(_series_product_typer)


@overload(series_product, jit_options={"nogil": True})
def _series_product_overload(U: Any, n: Any, a: Any, b: Any, order: Any) -> Any:
    """Compiled :func:`series_product`: the intrinsic (a C-contiguous float64 array)."""
    if not (isinstance(U, types.Array) and U.dtype == types.float64 and U.layout == "C"
            and U.ndim == 3):
        return None

    def impl(U: Any, n: Any, a: Any, b: Any, order: Any) -> None:
        _series_product(U, n, a, b, order)

    return impl

def series_linear(U: Any, n: int, S: Any, a: int, ca: float, b: int, cb: float,
                  k: int) -> None:
    """``U[k, n, :] = ca * S[k, a, :] + cb * S[k, b, :]`` (without the second term when
    ``b < 0``): order ``k`` of the linear node of a section tape on lane jets (``S`` is
    ``U``), or of a variable node (``S`` the state's lane jets, ``ca = 1``).

    Parameters
    ----------
    U : ndarray, shape (order + 1, nodes, LANES)
        The tape's lane jets (C-contiguous); ``U[k, n]`` is written.
    n : int
        The node written.
    S : ndarray, shape (order + 1, rows, LANES)
        The rows read (C-contiguous).
    a, b : int
        The rows of ``S`` combined (``b < 0``: one term).
    ca, cb : float
        Their coefficients.
    k : int
        The order.

    Examples
    --------
    >>> import numpy as np
    >>> U = np.ones((2, 3, LANES))
    >>> series_linear(U, 2, U, 0, 2.0, 1, 3.0, 1)
    >>> series_linear(U, 1, U, 0, 4.0, -1, 0.0, 0)
    >>> float(U[1, 2, 0]), float(U[0, 1, LANES - 1]), float(U[1, 1, LANES - 1])
    (5.0, 4.0, 1.0)
    """
    U[k, n] = ca * S[k, a] + cb * S[k, b] if b >= 0 else ca * S[k, a]


def _series_linear_typer(typingctx: Any, U: Any, n: Any, S: Any, a: Any, ca: Any, b: Any,
                         cb: Any, k: Any) -> Any:
    """The vector code of :func:`series_linear` (``ca * S_a + cb * S_b`` as one product
    and one fused multiply-add, as the scalar tape's contraction)."""
    sig = types.void(U, n, S, a, ca, b, cb, k)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        _tune(builder)
        ut, nt, st, at, cat, bt, cbt, ot = signature.args
        u_, n_, s_, a_, ca_, b_, cb_, o_ = args
        intp = context.get_value_type(types.intp)
        vec, fma = _vector_fma(builder)
        zero = ir.Constant(intp, 0)

        def pointer(aryty: Any, ary: Any, k: Any, row: Any) -> Any:
            arr = context.make_array(aryty)(context, builder, ary)
            p = cgutils.get_item_pointer2(
                context, builder, data=arr.data, shape=cgutils.unpack_tuple(builder, arr.shape),
                strides=cgutils.unpack_tuple(builder, arr.strides), layout=aryty.layout,
                inds=[k, row, zero])
            return builder.bitcast(p, vec.as_pointer())

        def splat(x: Any) -> Any:
            v = ir.Constant(vec, ir.Undefined)
            for lane in range(LANES):
                v = builder.insert_element(v, x, ir.Constant(ir.IntType(32), lane))
            return v

        n_i = context.cast(builder, n_, nt, types.intp)
        a_i = context.cast(builder, a_, at, types.intp)
        b_i = context.cast(builder, b_, bt, types.intp)
        k = context.cast(builder, o_, ot, types.intp)
        va = splat(context.cast(builder, ca_, cat, types.float64))
        vb = splat(context.cast(builder, cb_, cbt, types.float64))
        two = builder.icmp_signed(">=", b_i, zero)
        x = builder.load(pointer(st, s_, k, a_i), align=8)
        with builder.if_else(two) as (then, otherwise):
            with then:
                y = builder.load(pointer(st, s_, k, b_i), align=8)
                v = builder.call(fma, [va, x, builder.fmul(vb, y)])
                builder.store(v, pointer(ut, u_, k, n_i), align=8)
            with otherwise:
                builder.store(builder.fmul(va, x), pointer(ut, u_, k, n_i), align=8)
        return context.get_dummy_value()

    return sig, codegen


_series_linear: Any = intrinsic(_series_linear_typer)


@overload(series_linear, jit_options={"nogil": True})
def _series_linear_overload(U: Any, n: Any, S: Any, a: Any, ca: Any, b: Any, cb: Any,
                            k: Any) -> Any:
    """Compiled :func:`series_linear`: the intrinsic (C-contiguous float64 arrays)."""
    if not _c_float64(U, S, ndim=3):
        return None

    def impl(U: Any, n: Any, S: Any, a: Any, ca: Any, b: Any, cb: Any, k: Any) -> None:
        _series_linear(U, n, S, a, ca, b, cb, k)

    return impl


#: Relative shortfall of :func:`root` below the exact power: its approximation error (at
#: most 1.6e-8 below the power, never above it: ``tests/kernels/taylor/test_jets.py``
#: over 5e-324 .. 1e308 and exponents 1/2 .. 1/30) plus this margin.
ROOT_SHORTFALL = 2.0**-26
_LN2 = math.log(2.0)
_INV_LN2 = 1.0 / _LN2
_SQRT2 = math.sqrt(2.0)
_MANTISSA = (1 << 52) - 1
_ONE = 1023 << 52  # the bits of 1.0 (exponent 0)
_TINY = 2.0**-1000  # below: scaled by 2^200 first (a subnormal's bits hold no exponent)
_LOG_TERMS = (1.0 / 9.0, 1.0 / 7.0, 0.2, 1.0 / 3.0, 1.0)  # 2 artanh(s) / (2 s) in s^2
_EXP_TERMS = (1.0 / 40320.0, 1.0 / 5040.0, 1.0 / 720.0, 1.0 / 120.0, 1.0 / 24.0,
              1.0 / 6.0, 0.5, 1.0, 1.0)  # e^t to t^8


@kernel_jit
def root(x, inv_p):
    r"""``x ** inv_p`` for ``x > 0`` without ``pow``, a little below it: the radii of the
    Taylor step size (:func:`andoyer.kernels.taylor.jets.radius`), so that a step is
    never longer than the exact formula's (at most 1.6e-8 + :data:`ROOT_SHORTFALL`,
    3e-8, shorter).

    ``x = 2^e f`` from the float's bits (``f`` in :math:`[1/\sqrt 2, \sqrt 2)`),
    :math:`\ln f = 2\,\mathrm{artanh}\,s`, :math:`s = (f - 1)/(f + 1)`, to the
    :math:`s^9` term (:math:`|s| \le 0.172`); then :math:`z = \ln x / p = k \ln 2 + t`
    with :math:`|t| \le \ln 2 / 2`, :math:`e^t` to the :math:`t^8` term and :math:`2^k`
    from its bits. For exponents ``inv_p <= 1/2`` (the step sizes' ``1/(p-1)``, ``1/p``);
    ``x = inf`` gives a finite :math:`2^{1024/p}`; NaN is no input (the step sizes test
    finiteness first). :func:`roots` is the same on lane vectors.
    """
    small = x < _TINY
    xs = x * 2.0**200 if small else x
    i = np.float64(xs).view(np.int64)
    e = (i >> 52) - (1223 if small else 1023)
    f = np.int64((i & _MANTISSA) | _ONE).view(np.float64)
    if f > _SQRT2:
        f *= 0.5
        e += 1
    s = (f - 1.0) / (f + 1.0)
    s2 = s * s
    p = _LOG_TERMS[0]
    for c in _LOG_TERMS[1:]:
        p = p * s2 + c
    z = (e * _LN2 + (2.0 * s) * p) * inv_p
    k = math.floor(z * _INV_LN2 + 0.5)
    t = z - k * _LN2
    q = _EXP_TERMS[0]
    for c in _EXP_TERMS[1:]:
        q = q * t + c
    two_k = np.int64((np.int64(k) + 1023) << 52).view(np.float64)
    return q * two_k * (1.0 - ROOT_SHORTFALL)


def roots(x: Any, inv_p: float, out: Any) -> None:
    """``out[lane] = root(x[lane], inv_p)`` (:func:`root`) for every lane, as vector
    code: one ``<LANES x double>`` of each operation (a scalar loop over the lanes runs
    one lane at a time, see the module notes).

    Parameters
    ----------
    x : ndarray, shape (LANES,)
        Positive floats (C-contiguous).
    inv_p : float
        The exponent.
    out : ndarray, shape (LANES,)
        The roots (C-contiguous; may be ``x``).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.full(LANES, 2.0**15)
    >>> roots(x, 1.0 / 15.0, x)
    >>> bool(abs(x[0] - 2.0) < 1e-7 and x[0] < 2.0)
    True
    """
    scalar = getattr(root, "py_func", root)
    for lane in range(LANES):
        out[lane] = scalar(float(x[lane]), inv_p)


def _roots_typer(typingctx: Any, x: Any, inv_p: Any, out: Any) -> Any:
    """The vector code of :func:`roots`: :func:`root`'s operations on lane vectors, its
    branches as selects."""
    sig = types.void(x, inv_p, out)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        _tune(builder)
        xt, pt, ot = signature.args
        x_, p_, o_ = args
        vec, fma = _vector_fma(builder)
        ivec = ir.VectorType(ir.IntType(64), LANES)
        floor = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(vec, [vec]), f"llvm.floor.v{LANES}f64")

        def splat(v: float) -> Any:
            return ir.Constant(vec, [v] * LANES)

        def isplat(v: int) -> Any:
            return ir.Constant(ivec, [v] * LANES)

        def data(aryty: Any, ary: Any) -> Any:
            arr = context.make_array(aryty)(context, builder, ary)
            return builder.bitcast(arr.data, vec.as_pointer())

        inv = context.cast(builder, p_, pt, types.float64)
        vinv = builder.insert_element(ir.Constant(vec, ir.Undefined), inv,
                                      ir.Constant(ir.IntType(32), 0))
        vinv = builder.shuffle_vector(vinv, ir.Constant(vec, ir.Undefined),
                                      ir.Constant(ir.VectorType(ir.IntType(32), LANES),
                                                  [0] * LANES))
        x = builder.load(data(xt, x_), align=8)
        small = builder.fcmp_ordered("<", x, splat(_TINY))
        xs = builder.select(small, builder.fmul(x, splat(2.0**200)), x)
        i = builder.bitcast(xs, ivec)
        e = builder.sub(builder.ashr(i, isplat(52)),
                        builder.select(small, isplat(1223), isplat(1023)))
        f = builder.bitcast(builder.or_(builder.and_(i, isplat(_MANTISSA)), isplat(_ONE)), vec)
        big = builder.fcmp_ordered(">", f, splat(_SQRT2))
        f = builder.select(big, builder.fmul(f, splat(0.5)), f)
        e = builder.add(e, builder.zext(big, ivec))
        s = builder.fdiv(builder.fsub(f, splat(1.0)), builder.fadd(f, splat(1.0)))
        s2 = builder.fmul(s, s)
        p = splat(_LOG_TERMS[0])
        for c in _LOG_TERMS[1:]:
            p = builder.call(fma, [p, s2, splat(c)])
        lnx = builder.call(fma, [builder.sitofp(e, vec), splat(_LN2),
                                 builder.fmul(builder.fmul(splat(2.0), s), p)])
        z = builder.fmul(lnx, vinv)
        k = builder.call(floor, [builder.call(fma, [z, splat(_INV_LN2), splat(0.5)])])
        t = builder.call(fma, [builder.fneg(k), splat(_LN2), z])
        q = splat(_EXP_TERMS[0])
        for c in _EXP_TERMS[1:]:
            q = builder.call(fma, [q, t, splat(c)])
        two_k = builder.bitcast(
            builder.shl(builder.add(builder.fptosi(k, ivec), isplat(1023)), isplat(52)), vec)
        r = builder.fmul(builder.fmul(q, two_k), splat(1.0 - ROOT_SHORTFALL))
        builder.store(r, data(ot, o_), align=8)
        return context.get_dummy_value()

    return sig, codegen


_roots: Any = intrinsic(_roots_typer)


@overload(roots, jit_options={"nogil": True})
def _roots_overload(x: Any, inv_p: Any, out: Any) -> Any:
    """Compiled :func:`roots`: the intrinsic (C-contiguous float64 arrays)."""
    if not _c_float64(x, out, ndim=1):
        return None

    def impl(x: Any, inv_p: Any, out: Any) -> None:
        _roots(x, inv_p, out)

    return impl


def series_dot(P: Any, row: int, w: Any, order: int) -> None:
    """``P[k, row, :] = sum_{j <= k} w[j, :, :] . w[k - j, :, :]`` for ``k = 0 .. order``:
    the Cauchy product of a lane vector's jets with themselves, summed over its six
    components (the MEGNO jets' ``w . w``, :mod:`andoyer.kernels.taylor.lane_tangent`).

    Parameters
    ----------
    P : ndarray, shape (order + 1, rows, LANES)
        Lane jets (C-contiguous); row ``row`` is written.
    row : int
        The row written.
    w : ndarray, shape (order + 1, 6, LANES)
        A vector's lane jets (C-contiguous).
    order : int
        The highest order.

    Examples
    --------
    >>> import numpy as np
    >>> w = np.ones((3, 6, LANES))
    >>> P = np.zeros((3, 1, LANES))
    >>> series_dot(P, 0, w, 2)
    >>> P[:, 0, 0].tolist()
    [6.0, 12.0, 18.0]
    """
    for k in range(order + 1):
        s = w[0, 0] * w[k, 0]
        for j in range(k + 1):
            for i in range(6):
                if j or i:
                    s = s + w[j, i] * w[k - j, i]
        P[k, row] = s


def _series_dot_typer(typingctx: Any, P: Any, row: Any, w: Any, order: Any) -> Any:
    """The vector code of :func:`series_dot`: each pair ``(j, k - j)`` once (the sum is
    symmetric), one accumulator per component (six independent chains of fused
    multiply-adds), their sum doubled, and the middle term ``w[k/2] . w[k/2]`` of even
    orders added."""
    sig = types.void(P, row, w, order)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        _tune(builder)
        pt, rt, wt, ot = signature.args
        p_, r_, w_, o_ = args
        intp = context.get_value_type(types.intp)
        vec, fma = _vector_fma(builder)
        zero = ir.Constant(intp, 0)

        def const(v: int) -> Any:
            return ir.Constant(intp, v)

        def pointer(aryty: Any, ary: Any, inds: list[Any]) -> Any:
            arr = context.make_array(aryty)(context, builder, ary)
            p = cgutils.get_item_pointer2(
                context, builder, data=arr.data, shape=cgutils.unpack_tuple(builder, arr.shape),
                strides=cgutils.unpack_tuple(builder, arr.strides), layout=aryty.layout,
                inds=inds)
            return builder.bitcast(p, vec.as_pointer())

        def load(k: Any, i: int) -> Any:
            return builder.load(pointer(wt, w_, [k, const(i), zero]), align=8)

        def splat(x: Any) -> Any:
            v = ir.Constant(vec, ir.Undefined)
            for lane in range(LANES):
                v = builder.insert_element(v, x, ir.Constant(ir.IntType(32), lane))
            return v

        row_i = context.cast(builder, r_, rt, types.intp)
        order_i = context.cast(builder, o_, ot, types.intp)
        zvec = ir.Constant(vec, [0.0] * LANES)
        two = ir.Constant(vec, [2.0] * LANES)
        accs = [cgutils.alloca_once(builder, vec) for _ in range(6)]
        with cgutils.for_range(builder, builder.add(order_i, const(1)), intp=intp) as korder:
            k = korder.index
            for acc in accs:
                builder.store(zvec, acc)
            half = builder.sdiv(builder.add(k, const(1)), const(2))
            with cgutils.for_range(builder, half, intp=intp) as loop:
                j = loop.index
                kj = builder.sub(k, j)
                for i in range(6):
                    builder.store(builder.call(fma, [load(j, i), load(kj, i),
                                                     builder.load(accs[i])]), accs[i])
            s = builder.fadd(builder.load(accs[0]), builder.load(accs[1]))
            s2 = builder.fadd(builder.load(accs[2]), builder.load(accs[3]))
            s4 = builder.fadd(builder.load(accs[4]), builder.load(accs[5]))
            s = builder.fmul(two, builder.fadd(builder.fadd(s, s2), s4))
            mid = builder.sdiv(k, const(2))
            even = builder.icmp_signed("==", builder.mul(mid, const(2)), k)
            weight = splat(builder.select(even, ir.Constant(ir.DoubleType(), 1.0),
                                          ir.Constant(ir.DoubleType(), 0.0)))
            m0 = load(mid, 0)
            dot = builder.fmul(m0, m0)
            for i in range(1, 6):
                mi = load(mid, i)
                dot = builder.call(fma, [mi, mi, dot])
            s = builder.call(fma, [weight, dot, s])
            builder.store(s, pointer(pt, p_, [k, row_i, zero]), align=8)
        return context.get_dummy_value()

    return sig, codegen


_series_dot: Any = intrinsic(_series_dot_typer)


@overload(series_dot, jit_options={"nogil": True})
def _series_dot_overload(P: Any, row: Any, w: Any, order: Any) -> Any:
    """Compiled :func:`series_dot`: the intrinsic (C-contiguous float64 arrays)."""
    if not _c_float64(P, w, ndim=3):
        return None

    def impl(P: Any, row: Any, w: Any, order: Any) -> None:
        _series_dot(P, row, w, order)

    return impl


def megno_orders(W: Any, order: int, s0: Any, inv: Any) -> None:
    r"""Orders ``1 .. order`` of the MEGNO quadratures' lane jets from ``w . w``: the
    recurrences of :mod:`andoyer.kernels.taylor.tangent`'s notes on lane vectors
    (:func:`andoyer.kernels.taylor.lane_tangent.lane_megno_jets`).

    ``W[k, row, lane]``, rows ``0 .. 5``: ``L``, ``N``, ``I``, ``P = w . w`` (every order
    given), ``g`` and the weights ``j L_j``; row 0 of each given (order 0). For each
    ``k``: :math:`\ell_k = (P_k - \frac2k \sum_{j=1}^{k-1} j L_j P_{k-j}) / P_0`,
    :math:`L_k = \ell_k / 2`, :math:`N_k = s_0 L_k + \frac{k-1}{k} L_{k-1}`,
    :math:`I_k = 2 g_{k-1} / k`, :math:`g_k = (N_k - g_{k-1}) / s_0`.

    Parameters
    ----------
    W : ndarray, shape (order + 1, 6, LANES)
        The quadratures' lane jets (C-contiguous); orders ``1 .. order`` written.
    order : int
        The highest order.
    s0 : ndarray, shape (LANES,)
        ``t0 + delta`` of each lane.
    inv : ndarray, shape (2, LANES)
        ``1 / P_0`` and ``1 / s0`` of each lane (C-contiguous).

    Examples
    --------
    >>> import numpy as np
    >>> W = np.zeros((3, 6, LANES))
    >>> W[:, 3] = [[1.0], [2.0], [1.0]]  # P = (1 + tau)^2: L = ln(1 + tau) = tau - tau^2/2
    >>> megno_orders(W, 2, np.ones(LANES), np.ones((2, LANES)))
    >>> W[:, 0, 0].tolist()
    [0.0, 1.0, -0.5]
    """
    for k in range(1, order + 1):
        inv_k = 1.0 / k
        acc = 0.0 * W[0, 0]
        for j in range(1, k):
            acc = acc + W[j, 5] * W[k - j, 3]
        Lk = 0.5 * ((W[k, 3] - 2.0 * acc * inv_k) * inv[0])
        W[k, 0] = Lk
        W[k, 5] = k * Lk
        W[k, 1] = s0 * Lk + (k - 1) * inv_k * W[k - 1, 0]
        W[k, 2] = 2.0 * W[k - 1, 4] * inv_k
        W[k, 4] = (W[k, 1] - W[k - 1, 4]) * inv[1]


def _megno_orders_typer(typingctx: Any, W: Any, order: Any, s0: Any, inv: Any) -> Any:
    """The vector code of :func:`megno_orders`: per order one chain of fused
    multiply-adds for the logarithm's convolution, then the five rows as lane vectors."""
    sig = types.void(W, order, s0, inv)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        _tune(builder)
        wt, ot, st, it = signature.args
        w_, o_, s_, i_ = args
        intp = context.get_value_type(types.intp)
        dbl = ir.DoubleType()
        vec, fma = _vector_fma(builder)
        zero = ir.Constant(intp, 0)

        def const(v: int) -> Any:
            return ir.Constant(intp, v)

        arr = context.make_array(wt)(context, builder, w_)
        shape = cgutils.unpack_tuple(builder, arr.shape)
        strides = cgutils.unpack_tuple(builder, arr.strides)

        def pointer(k: Any, row: int) -> Any:
            p = cgutils.get_item_pointer2(context, builder, data=arr.data, shape=shape,
                                          strides=strides, layout=wt.layout,
                                          inds=[k, const(row), zero])
            return builder.bitcast(p, vec.as_pointer())

        def load(k: Any, row: int) -> Any:
            return builder.load(pointer(k, row), align=8)

        def store(v: Any, k: Any, row: int) -> None:
            builder.store(v, pointer(k, row), align=8)

        def splat(x: Any) -> Any:
            v = ir.Constant(vec, ir.Undefined)
            for lane in range(LANES):
                v = builder.insert_element(v, x, ir.Constant(ir.IntType(32), lane))
            return v

        def vector(aryty: Any, ary: Any, row: int | None) -> Any:
            a = context.make_array(aryty)(context, builder, ary)
            inds = [zero] if row is None else [const(row), zero]
            p = cgutils.get_item_pointer2(
                context, builder, data=a.data, shape=cgutils.unpack_tuple(builder, a.shape),
                strides=cgutils.unpack_tuple(builder, a.strides), layout=aryty.layout,
                inds=inds)
            return builder.load(builder.bitcast(p, vec.as_pointer()), align=8)

        s0v = vector(st, s_, None)
        inv_p0 = vector(it, i_, 0)
        inv_s0 = vector(it, i_, 1)
        half = ir.Constant(vec, [0.5] * LANES)
        two = ir.Constant(vec, [2.0] * LANES)
        zvec = ir.Constant(vec, [0.0] * LANES)
        order_i = context.cast(builder, o_, ot, types.intp)
        acc = cgutils.alloca_once(builder, vec)
        with cgutils.for_range_slice(builder, const(1), builder.add(order_i, const(1)),
                                     const(1), intp=intp) as (k, _):
            builder.store(zvec, acc)
            with cgutils.for_range_slice(builder, const(1), k, const(1), intp=intp) as (j, _):
                builder.store(builder.call(fma, [load(j, 5), load(builder.sub(k, j), 3),
                                                 builder.load(acc)]), acc)
            kf = builder.sitofp(k, dbl)
            inv_k = builder.fdiv(ir.Constant(dbl, 1.0), kf)
            c_k = builder.fmul(builder.fsub(kf, ir.Constant(dbl, 1.0)), inv_k)
            inv_kv = splat(inv_k)
            k1 = builder.sub(k, const(1))
            ell = builder.fmul(builder.fsub(load(k, 3), builder.fmul(
                builder.fmul(two, builder.load(acc)), inv_kv)), inv_p0)
            Lk = builder.fmul(half, ell)
            store(Lk, k, 0)
            store(builder.fmul(splat(kf), Lk), k, 5)
            Nk = builder.fadd(builder.fmul(s0v, Lk), builder.fmul(splat(c_k), load(k1, 0)))
            store(Nk, k, 1)
            g1 = load(k1, 4)
            store(builder.fmul(builder.fmul(two, g1), inv_kv), k, 2)
            store(builder.fmul(builder.fsub(Nk, g1), inv_s0), k, 4)
        return context.get_dummy_value()

    return sig, codegen


_megno_orders: Any = intrinsic(_megno_orders_typer)


@overload(megno_orders, jit_options={"nogil": True})
def _megno_orders_overload(W: Any, order: Any, s0: Any, inv: Any) -> Any:
    """Compiled :func:`megno_orders`: the intrinsic (C-contiguous float64 arrays)."""
    if not _c_float64(W, s0, inv):
        return None

    def impl(W: Any, order: Any, s0: Any, inv: Any) -> None:
        _megno_orders(W, order, s0, inv)

    return impl
