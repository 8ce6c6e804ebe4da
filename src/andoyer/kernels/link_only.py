"""Numba functions compiled only into their callers: no optimisation or machine code
of their own.

Numba compiles every jitted function into its own *library*: an LLVM module that is
optimised (the full module pipeline) and emitted as machine code into the process,
whoever calls it. A compiled caller links the optimised modules of its callees into its
own and optimises and emits the whole again; the code that runs is the caller's copy.
With the kernels' helpers nested three deep (an entry point, the orbit loop, the step and
the section search, the jets), every helper was optimised once per level above it and
emitted once more for nothing: most of a cold first call's LLVM time went to the
helpers' own libraries, whose code never runs (measured: benchmarks/NOTES.md#link-only).

:class:`LinkOnlyCompiler`, given to ``numba.njit(pipeline_class=...)``, compiles a
function into a :class:`LinkOnlyLibrary`: Numba's own typing, lowering and per-function
LLVM passes, then nothing more. Its module is linked, as it is, into each caller, whose
module passes optimise the entry point and everything it calls once, as one unit; only
the library's *environment* globals (the word Numba writes a pointer into when it
registers the function) go into the process's JIT engine. Such a function has no
address: only other compiled code can use it (the helpers of
:func:`~andoyer.kernels.common.kernel_jit`, which have no Python entry anyway). A process
that loads an entry point from the cache links nothing and never needed the helpers' own
code. The kernels give the same floats, bit for bit, with this pipeline and with Numba's
(``tests/kernels/test_link_only.py`` compiles them both ways in fresh processes).

It overrides private Numba methods (``CPUCodeLibrary._finalize_final_module``,
``_optimize_final_module``, a pipeline class's ``state.library``), so it is used only
where :func:`enabled`:

* on the Numba releases it was tested with, :data:`TESTED_NUMBA` (a test fails when the
  installed Numba is not on the list, so a new release is tested before it is added);
* when those internals are there (:func:`supported`);
* unless the environment variable :data:`SWITCH_ENV` (``ANDOYER_LINK_ONLY``) is ``0``,
  ``false``, ``no`` or ``off``, read once, when this module is imported.

Elsewhere the helpers are compiled as plain Numba functions (without their Python and
C-callback wrappers, through Numba's own pipeline): the same floats, a longer cold
compile, and no warning (nothing is wrong; the switch and the list are documented in
the guide's numerics page).
"""

from __future__ import annotations

import functools
import os
import re
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["LinkOnlyCompiler", "LinkOnlyLibrary", "link_only_options", "link_only_jit",
           "supported", "enabled", "switched_on", "numba_release", "TESTED_NUMBA", "SWITCH_ENV"]

#: Numba releases (major, minor) whose internals this module was tested with; on any other
#: the helpers are plain Numba functions. Add a release only after
#: ``tests/kernels/test_link_only.py`` passed on it.
TESTED_NUMBA: tuple[tuple[int, int], ...] = ((0, 68),)

#: Environment variable that turns the link-only pipeline off (``0``, ``false``, ``no``,
#: ``off``); unset or anything else: on where :func:`supported`.
SWITCH_ENV = "ANDOYER_LINK_ONLY"
_OFF = frozenset({"0", "false", "no", "off"})


def switched_on(environ: Mapping[str, str] | None = None) -> bool:
    """Whether :data:`SWITCH_ENV` leaves the link-only pipeline on.

    Parameters
    ----------
    environ : mapping, optional
        The environment to read (default ``os.environ``).

    Examples
    --------
    >>> switched_on({}), switched_on({"ANDOYER_LINK_ONLY": "0"})
    (True, False)
    >>> switched_on({"ANDOYER_LINK_ONLY": " Off "}), switched_on({"ANDOYER_LINK_ONLY": "1"})
    (False, True)
    """
    value = (os.environ if environ is None else environ).get(SWITCH_ENV, "")
    return value.strip().lower() not in _OFF


def numba_release(version: str | None = None) -> tuple[int, int] | None:
    """``(major, minor)`` of a Numba version string (default the installed Numba's);
    None if it does not start with two integers.

    Parameters
    ----------
    version : str, optional
        A version such as ``"0.68.1"`` or ``"0.69.0rc1"``.

    Examples
    --------
    >>> numba_release("0.68.1"), numba_release("0.70rc1"), numba_release("x")
    ((0, 68), (0, 70), None)
    """
    if version is None:
        import numba

        version = numba.__version__
    found = re.match(r"(\d+)\.(\d+)", version)
    return (int(found[1]), int(found[2])) if found else None


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
    """Whether this Numba is a tested release (:data:`TESTED_NUMBA`) with the internals
    :class:`LinkOnlyLibrary` uses (and its JIT codegen makes libraries of that class).
    A release off the list is not looked into at all.

    Examples
    --------
    >>> supported() == (numba_release() in TESTED_NUMBA)
    True
    """
    if numba_release() not in TESTED_NUMBA:
        return False
    found = _classes()
    if found is None:
        return False
    from numba.core import codegen

    return getattr(codegen.JITCPUCodegen, "_library_class", None) is found[0]


@functools.cache
def enabled() -> bool:
    """Whether helpers are compiled link-only in this process: :func:`supported` and
    :func:`switched_on` (read once: the first answer holds for the process).

    Examples
    --------
    >>> enabled() == (supported() and switched_on())
    True
    """
    return switched_on() and supported()


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


if enabled():
    LinkOnlyLibrary, LinkOnlyCompiler = _build_classes()
else:  # switched off, or another Numba: Numba's own pipeline, no private method touched
    LinkOnlyLibrary = LinkOnlyCompiler = None  # type: ignore[assignment]


def link_only_options() -> dict[str, Any]:
    """Options of :func:`numba.njit` compiling a function into its callers only: the
    pipeline of :class:`LinkOnlyCompiler`, with neither the Python nor the C-callback
    wrapper (nothing could call them); only the wrappers' removal where the pipeline is
    not :func:`enabled` (Numba's own pipeline).

    Examples
    --------
    >>> sorted(link_only_options()) == (["no_cfunc_wrapper", "no_cpython_wrapper"]
    ...                                 + ["pipeline_class"] * enabled())
    True
    """
    options: dict[str, Any] = {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}
    if enabled():
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
