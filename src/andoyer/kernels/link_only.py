"""Numba functions compiled only into their callers: no optimisation or machine code
of their own.

Numba compiles every jitted function into its own *library*: an LLVM module that is
optimised (the full module pipeline) and emitted as machine code into the process,
whoever calls it. A compiled caller links the optimised modules of its callees into its
own and optimises and emits the whole again; the code that runs is the caller's copy.
With the Taylor kernels' helpers nested three deep (an entry point, the orbit loop, the
step and the section search, the jets), every helper was optimised once per level above
it and emitted once more for nothing. Of the 6.2 s of CPU of the taylor engine's cold
first ``propagate`` + ``poincare`` (W4), LLVM's module passes and emission took 2.6 s,
1.7 s of it on the helpers' own libraries (0.9 s passes, 0.8 s emission), whose code
never ran (measured with Numba's library timings); with this module the same calls take
3.8-4.0 s.

:class:`LinkOnlyCompiler`, given to ``numba.njit(pipeline_class=...)``, compiles a
function into a :class:`LinkOnlyLibrary`: Numba's own typing, lowering and per-function
LLVM passes, then nothing more. Its module is linked, as it is, into each caller, whose
module passes optimise the entry point and everything it calls once, as one unit; only
the library's *environment* globals (the word Numba writes a pointer into when it
registers the function) go into the process's JIT engine. Such a function has no
address: only other compiled code can use it (helpers of :func:`kernel_jit
<andoyer.kernels.common.kernel_jit>`, which have no Python entry anyway). A
process that loads an entry point from the cache links nothing and never needed the
helpers' own code.

Same results: the Taylor kernels (every entry point of :mod:`andoyer.kernels.taylor.flow`
and :mod:`andoyer.kernels.taylor.tangent`, 4 orbits x 2 bodies, all 15 section kinds x 2
directions, tangent, renormalised, attitude and jets: 146 arrays) gave the same floats,
bit for bit, compiled fresh and loaded from the cache, as with Numba's pipeline; the
machine code differs in register allocation and in the copies LLVM duplicates (the same
floating-point operations, as the arrays show), and the W1/W2 kernel times did not
change (within the 5 % noise of a loaded machine). A test compiles the kernels with
Numba's pipeline in a fresh process and compares (``tests/kernels/test_link_only.py``).

It leans on Numba internals (``CPUCodeLibrary._finalize_final_module``,
``_optimize_final_module``, a pipeline class's ``state.library``), so :func:`supported`
checks them once and :func:`link_only_options` leaves the pipeline out where they are
missing: the helpers are then compiled as plain Numba functions (slower to compile).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

__all__ = ["LinkOnlyCompiler", "LinkOnlyLibrary", "link_only_options", "link_only_jit",
           "supported"]


def _classes() -> tuple[type, type] | None:
    """Numba's JIT library and compiler classes, if they have what this module uses."""
    try:
        from numba.core import codegen, compiler
    except ImportError:  # pragma: no cover - numba is a dependency
        return None
    library = getattr(codegen, "JITCodeLibrary", None)
    if library is None or not all(hasattr(library, name) for name in (
            "_finalize_final_module", "_finalize_dynamic_globals", "_verify_declare_only_symbols",
            "_optimize_final_module",
            "_finalize_specific")):
        return None  # pragma: no cover - another Numba's internals
    base = getattr(compiler, "Compiler", None)
    if base is None or not hasattr(base, "compile_extra"):
        return None  # pragma: no cover
    return library, base


@functools.cache
def supported() -> bool:
    """Whether this Numba has the internals :class:`LinkOnlyLibrary` uses (and the
    JIT codegen makes libraries of that class).

    Examples
    --------
    >>> supported()
    True
    """
    found = _classes()
    if found is None:
        return False
    from numba.core import codegen

    return getattr(codegen.JITCPUCodegen, "_library_class", None) is found[0]


def _build_classes() -> tuple[type, type]:
    found = _classes()
    assert found is not None
    jit_library, compiler = found
    import llvmlite.binding as ll

    class _Library(jit_library):  # type: ignore[misc, valid-type]
        """A library whose functions are linked into callers, never emitted.

        Parameters
        ----------
        codegen : numba.core.codegen.JITCPUCodegen
            Numba's code generator of the process.
        name : str
            The library's name (the function's qualified name).
        """

        def _finalize_final_module(self) -> None:
            # As CPUCodeLibrary._finalize_final_module, but the module handed to the JIT
            # engine holds only the final module's environment globals (common,
            # null-initialised words): Numba's set_env writes the function's environment
            # into its own one. _final_module itself stays, for the callers to link in.
            self._finalize_dynamic_globals()
            self._verify_declare_only_symbols()
            final = self._final_module
            lines = [str(g) for g in final.global_variables
                     if not g.is_declaration and g.name.startswith("_ZN08NumbaEnv")]
            stub = ll.parse_assembly("\n".join(lines))
            stub.triple = final.triple
            stub.data_layout = str(final.data_layout)
            stub.name = final.name + ".env"
            self._codegen._add_module(stub)
            self._codegen._scan_and_fix_unresolved_refs(stub)
            self._codegen._engine.finalize_object()
            self._finalized = True

        def _optimize_final_module(self) -> None:
            # Left to the caller, which optimises its module with this one linked in:
            # each entry point's code is optimised once, as one unit (not once per level
            # of helpers and again in each caller).
            pass

        def serialize_using_object_code(self) -> Any:  # pragma: no cover - not cached
            raise RuntimeError(f"{self.name} is compiled into its callers only; it has "
                               "no machine code to cache")

    class _Compiler(compiler):  # type: ignore[misc, valid-type]
        """Numba's nopython pipeline into a :class:`LinkOnlyLibrary`.

        Parameters
        ----------
        typingctx, targetctx
            Numba's typing and target contexts.
        library : LinkOnlyLibrary or None
            The library to compile into (None: a new one).
        args : tuple
            The argument types.
        return_type
            The return type (None: inferred).
        flags
            Numba's compilation flags.
        locals : dict
            Types of local variables.
        """

        def compile_extra(self, func: Any) -> Any:
            if self.state.library is None:
                codegen = self.state.targetctx.codegen()
                self.state.library = _Library(codegen, func.__qualname__)
                # Numba's own lowering would have created the library with object
                # caching on; a link-only library is never cached (no object code).
            return super().compile_extra(func)

    _Library.__name__ = _Library.__qualname__ = "LinkOnlyLibrary"
    _Compiler.__name__ = _Compiler.__qualname__ = "LinkOnlyCompiler"
    return _Library, _Compiler


if supported():
    LinkOnlyLibrary, LinkOnlyCompiler = _build_classes()
else:  # pragma: no cover - another Numba
    LinkOnlyLibrary = LinkOnlyCompiler = None  # type: ignore[assignment]


def link_only_options() -> dict[str, Any]:
    """Options of :func:`numba.njit` compiling a function into its callers only: the
    pipeline of :class:`LinkOnlyCompiler`, with neither the Python nor the C-callback
    wrapper (nothing could call them); only the wrappers' removal where this Numba lacks
    the internals (:func:`supported`).

    Examples
    --------
    >>> sorted(link_only_options())
    ['no_cfunc_wrapper', 'no_cpython_wrapper', 'pipeline_class']
    """
    options: dict[str, Any] = {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}
    if supported():
        options["pipeline_class"] = LinkOnlyCompiler
    return options


def _kernel_only() -> type:
    from numba.core.registry import CPUDispatcher

    class KernelOnly(CPUDispatcher):
        """A Numba function compiled only into other compiled code: calling it from
        Python raises TypeError (it has no Python entry)."""

        def __call__(self, *args: object, **kwargs: object) -> object:
            raise TypeError(f"{self.py_func.__qualname__} runs inside andoyer's compiled "
                            "kernels only (no Python entry point); call it from a Numba "
                            "function")

    return KernelOnly


_KernelOnly = _kernel_only()


def link_only_jit(**options: Any) -> Callable[[Callable[..., Any]], Any]:
    """``numba.njit(**options)`` with :func:`link_only_options`: a helper that only
    compiled code calls, compiled into each caller only. Its dispatcher refuses a call
    from Python (TypeError) instead of reaching the missing wrapper.

    Parameters
    ----------
    **options
        Options of :func:`numba.njit` (``nogil``, ``fastmath``, ...).

    Returns
    -------
    callable
        A decorator; under ``NUMBA_DISABLE_JIT`` the function itself.

    Examples
    --------
    >>> @link_only_jit(nogil=True)
    ... def twice(x):
    ...     return 2.0 * x
    >>> try:
    ...     twice(1.0)
    ... except TypeError as e:
    ...     print(str(e)[:44])
    twice runs inside andoyer's compiled kernels
    """
    import numba
    from numba.core.registry import CPUDispatcher

    def decorate(function: Callable[..., Any]) -> Any:
        dispatcher = numba.njit(**options, **link_only_options())(function)
        if isinstance(dispatcher, CPUDispatcher):  # not under NUMBA_DISABLE_JIT
            dispatcher.__class__ = _KernelOnly
        return dispatcher

    return decorate
