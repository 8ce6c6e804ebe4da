"""What every integration method of :mod:`andoyer.kernels` shares, defined once.

The methods (:mod:`andoyer.kernels.dop853`, :mod:`andoyer.kernels.taylor`) import this
module and :mod:`andoyer.kernels.generated`, never each other (an import contract of
``pyproject.toml``). Here:

* the start of the crossings, :data:`T_START`: a section root at ``t <= T_START`` is
  the initial state lying on the section (to round-off), not a crossing -- "crossings
  after t = 0" must not depend on the sign of the round-off in the section function at
  ``y0``; every engine and the periodic-orbit section maps apply it;
* the ``info`` columns and status codes of every entry point (:data:`INFO`,
  :data:`SUCCESS`, :data:`STEP_TOO_SMALL`, :data:`MAX_STEPS`, :data:`STATUS_MESSAGES`);
* the layout of a renormalised tangent state (:func:`dimension`, :func:`n_vectors`,
  :func:`layout`) and the MEGNO shift :data:`MEGNO_DELTA`, which every engine uses;
* the fast-math flags :data:`FASTMATH` and the JIT decorators: :func:`kernel_jit`
  (a helper compiled into its callers only), :func:`fast_jit` (a helper with a Python
  entry), :func:`entry_jit` (a cached entry point) and :func:`exact_jit` (a cached
  function without fast-math);
* :func:`source_stamp`, the hash that keys an entry point's cache on its sources.

Importing this module loads no Numba: the decorators import it when they are applied.

Examples
--------
>>> dimension(1), n_vectors(dimension(3)), STATUS_MESSAGES[SUCCESS]
(15, 3, 'success')
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = [
    "variant",
    "kernel_variant",
    "T_START",
    "N_STATE",
    "INFO",
    "SUCCESS",
    "STEP_TOO_SMALL",
    "MAX_STEPS",
    "STATUS_MESSAGES",
    "MEGNO_DELTA",
    "MAX_VECTORS",
    "N_MEGNO",
    "dimension",
    "n_vectors",
    "layout",
    "FASTMATH",
    "kernel_jit",
    "fast_jit",
    "entry_jit",
    "exact_jit",
    "source_stamp",
]

#: A section root at ``t <= T_START`` is the initial state on the section, not a crossing.
T_START = 1e-10

#: Dimension of the Euler-Poisson state (G1, G2, G3, gamma1, gamma2, gamma3).
N_STATE = 6

#: Columns of the ``info`` arrays returned by every entry point.
INFO = ("status", "accepted", "rejected", "nfev")
#: Status codes (column ``"status"`` of ``info``).
SUCCESS, STEP_TOO_SMALL, MAX_STEPS = 0, 1, 2
STATUS_MESSAGES = {
    SUCCESS: "success",
    STEP_TOO_SMALL: "step size fell below 10 ulp of t (non-finite or too stiff state)",
    MAX_STEPS: "maximum number of steps reached",
}

#: Time shift of the MEGNO weights ``1 / (t + delta)`` (Cincotta & Simo 2000): the one
#: value of every engine (the kernels, :mod:`andoyer.integrate.variational` and the
#: heyoka engine import it).
MEGNO_DELTA = 1e-6
#: Most tangent vectors per orbit: a full fundamental matrix of (1).
MAX_VECTORS = 6
#: The two MEGNO quadratures at the end of a tangent state.
N_MEGNO = 2


def dimension(k: int) -> int:
    """Floats per orbit of a renormalised tangent state with ``k`` vectors: ``6 + 7 k + 2``.

    Parameters
    ----------
    k : int
        Tangent vectors.

    Examples
    --------
    >>> dimension(1)
    15
    """
    return N_STATE + 7 * k + N_MEGNO


def n_vectors(dim: int) -> int:
    """The number of tangent vectors ``k`` of a state of ``dim`` floats.

    Parameters
    ----------
    dim : int
        Floats per orbit.

    Examples
    --------
    >>> n_vectors(dimension(3))
    3
    """
    k, r = divmod(dim - N_STATE - N_MEGNO, 7)
    if r or not 1 <= k <= MAX_VECTORS:
        raise ValueError(f"{dim} floats is not a tangent state (6 + 7 k + 2, "
                         f"1 <= k <= {MAX_VECTORS})")
    return k


def layout(k: int) -> dict[str, slice | int]:
    """Where each part of a renormalised tangent state with ``k`` vectors lives.

    Parameters
    ----------
    k : int
        Tangent vectors.

    Returns
    -------
    dict
        ``"y"``: slice of the Euler-Poisson state; ``"u"``: slice of the ``6 k`` vector
        components (vector ``i`` at ``6 + 6 i``); ``"rho"``: slice of the ``k`` log
        norms; ``"megno_num"``, ``"megno_int"``: indices of the quadratures.

    Examples
    --------
    >>> layout(2)["rho"], layout(2)["megno_int"]
    (slice(18, 20, None), 21)
    """
    n = N_STATE
    return {"y": slice(0, n), "u": slice(n, n + 6 * k), "rho": slice(n + 6 * k, n + 7 * k),
            "megno_num": n + 7 * k, "megno_int": n + 7 * k + 1}


#: LLVM fast-math flags of every kernel: reassociation and contraction (FMA) let LLVM
#: vectorise the stage sums, norms and Cauchy products; reciprocals replace divisions.
#: Not ``nnan``/``ninf``: the step control relies on NaN comparisons to stop a
#: non-finite orbit. Faster steps at the same accuracy (measured:
#: benchmarks/NOTES.md#fast-math).
FASTMATH = frozenset({"reassoc", "contract", "arcp"})


def kernel_jit(function: Callable[..., Any]) -> Any:
    """A helper that only compiled code calls, compiled into each caller only.

    ``numba.njit(nogil=True, fastmath=FASTMATH)`` through
    :func:`andoyer.kernels.link_only.link_only_jit`: no Python or C-callback wrapper
    and no optimisation or machine code of its own (its module is optimised once,
    inside each entry point that calls it; cold compiles are shorter, the floats the
    same bit for bit -- measured: benchmarks/NOTES.md#link-only). A call from Python
    raises TypeError instead of reaching the missing wrapper.

    Parameters
    ----------
    function : callable
        The Python function to compile.

    Returns
    -------
    numba.core.registry.CPUDispatcher
        Its dispatcher (the function itself under ``NUMBA_DISABLE_JIT``).
    """
    from andoyer.kernels.link_only import link_only_jit

    return link_only_jit(nogil=True, fastmath=set(FASTMATH))(function)


def fast_jit(function: Callable[..., Any]) -> Any:
    """``numba.njit(nogil=True, fastmath=FASTMATH)``: a helper with a Python entry (not
    cached; tests call it).

    Parameters
    ----------
    function : callable
        The Python function to compile.

    Returns
    -------
    numba.core.registry.CPUDispatcher
        Its dispatcher.
    """
    import numba

    return numba.njit(nogil=True, fastmath=set(FASTMATH))(function)


def entry_jit(function: Callable[..., Any]) -> Any:
    """A cached entry point: :func:`andoyer.kernels.cache.cached_njit` with ``nogil``
    and :data:`FASTMATH`. Build it in a factory closing over a :func:`source_stamp` of
    every source it compiles in (the notes of :mod:`andoyer.kernels.dop853.flow`).

    Parameters
    ----------
    function : callable
        The Python function to compile.

    Returns
    -------
    numba.core.registry.CPUDispatcher
        Its dispatcher, cached in :func:`andoyer.kernels.cache.cache_folder`.
    """
    from andoyer.kernels.cache import cached_njit

    return cached_njit(nogil=True, fastmath=set(FASTMATH))(function)


def exact_jit(function: Callable[..., Any]) -> Any:
    """A cached function without fast-math (``nogil``, no C-callback wrapper): the
    Taylor method's entry points (whose helpers carry :data:`FASTMATH` themselves) and
    the generated fields of :mod:`andoyer.kernels.dop853.fields`, which Python callers
    compare with NumPy.

    Parameters
    ----------
    function : callable
        The Python function to compile.

    Returns
    -------
    numba.core.registry.CPUDispatcher
        Its dispatcher, cached in :func:`andoyer.kernels.cache.cache_folder`.
    """
    from andoyer.kernels.cache import cached_njit

    return cached_njit(nogil=True, fastmath=False, no_cfunc_wrapper=True)(function)


def variant(tag: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Name a factory-made kernel after its variant: ``tag`` is appended to the function's
    ``__qualname__`` before Numba compiles it.

    Numba names a function's machine code after its qualified name and a counter of the
    process that compiles it. Two variants of one factory's function (the same qualified
    name, other closure constants: the state's or the tangent vectors' jets, a section
    family) compiled in two processes can so get one symbol, and a process that loads both
    from the on-disk cache runs one body for both (numba/numba#10486; seen here: tangent
    crossings running the state's loop on a cache two test workers wrote). A tag per
    variant keeps their names, and their cache entries, apart.

    Parameters
    ----------
    tag : str
        What tells the variant from the factory's others (letters, digits, ``_``).

    Examples
    --------
    >>> @variant("tangent")
    ... def step(x):
    ...     return x
    >>> step.__qualname__
    'step__tangent'
    """
    if not tag.replace("_", "").isalnum():
        raise ValueError(f"tag must be letters, digits and _, got {tag!r}")

    def name(function: Callable[..., Any]) -> Callable[..., Any]:
        function.__qualname__ = f"{function.__qualname__}__{tag}"
        return function

    return name


def kernel_variant(tag: str) -> Callable[[Callable[..., Any]], Any]:
    """:func:`kernel_jit` of a factory-made helper named after its variant
    (:func:`variant`): the decorator of a factory's kernels.

    Parameters
    ----------
    tag : str
        The variant's tag (:func:`variant`).
    """
    name = variant(tag)
    return lambda function: kernel_jit(name(function))


def source_stamp(*files: str | Path | None) -> str:
    """SHA-256 of the bytes of ``files``: a cache key for compiled entry points whose
    helpers live in other modules (the notes of :mod:`andoyer.kernels.dop853.flow`).

    Parameters
    ----------
    *files : str or pathlib.Path
        The source files whose bytes make the key (a module's ``__file__``).

    Examples
    --------
    >>> source_stamp(__file__) == source_stamp(__file__) != source_stamp()
    True
    """
    h = hashlib.sha256()
    for f in files:
        if f is None:
            raise ValueError("a module without a source file cannot key a cache")
        h.update(Path(f).read_bytes())
    return h.hexdigest()
