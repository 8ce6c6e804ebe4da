"""Arguments shared by the commands: the body, the integration engine, number flags."""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any, Literal, NamedTuple

from andoyer.body import PRESETS
from andoyer.integrate.engines import ENGINES, FALLBACK_DEFAULTS
from andoyer.notation import VOCABULARY
from andoyer.outputs import guard_file, guard_folder
from andoyer.validation import finite, floats, integer
from andoyer.validation import positive as _positive

__all__ = ["add_body_args", "body_from_args", "add_engine_args", "add_energy_args",
           "add_level_args", "add_term", "add_state_args", "state_from_args", "floats",
           "output_file", "output_folder", "distinct_outputs", "count", "real", "Inputs",
           "inputs_from_args", "ENGINE_HELP"]

#: The body flags each --body takes (others are refused, not ignored): the presets'.
BODY_FLAGS = {name: preset.flags for name, preset in PRESETS.items()}


# ---------------------------------------------------------------------- number flags
def count(minimum: int | None = None, maximum: int | None = None) -> Callable[[str], int]:
    """An argparse ``type`` for a whole number in range: a bad value fails at parsing,
    before any work, and argparse names the flag (``argument --n-crossings: must be an
    integer >= 1, got '0'``).

    >>> count(1)("1e3"), count(0, 9)("7")
    (1000, 7)
    """
    def check(name: str, text: str) -> int:
        value: Any = text
        for convert in (int, float):
            try:
                value = convert(text)
                break
            except ValueError:
                continue
        return integer(name, value, minimum, maximum)
    return _flag_type("count", check)


def real(*, positive: bool = False) -> Callable[[str], float]:
    """An argparse ``type`` for a finite real number (``positive``: also > 0).

    >>> real(positive=True)("1e-12")
    1e-12
    """
    check = _positive if positive else finite

    def parse(name: str, text: str) -> float:
        try:
            value: Any = float(text)
        except ValueError:
            value = text  # refused by the check, with its message
        return check(name, value)
    return _flag_type("real", parse)


def _flag_type(kind: str, check: Callable[[str, str], Any]) -> Callable[[str], Any]:
    """An argparse ``type`` from a :mod:`andoyer.validation` check: its message without
    the argument's name (argparse puts the flag in front) and with the text as typed."""
    def parse(text: str) -> Any:
        try:
            return check("value", text)
        except ValueError as e:
            message = str(e).removeprefix("value ")
            raise argparse.ArgumentTypeError(
                message[:message.rfind(", got ")] + f", got {text!r}") from None
    parse.__name__ = kind
    return parse


# ---------------------------------------------------------------------- the vocabulary
def add_term(p: Any, api: str, **kwargs: Any) -> argparse.Action:
    """Add the flag of the API parameter ``api`` with its name from the vocabulary
    (:data:`andoyer.notation.TERMS`): ``dest`` is the API name, the help starts from the
    table's meaning."""
    term = VOCABULARY[api]
    kwargs.setdefault("help", term.meaning)
    return p.add_argument(term.flag, dest=api, **kwargs)


# ---------------------------------------------------------------------- outputs
def _writable_folder(folder: Path, flag: str, text: str) -> None:
    if not folder.exists():
        raise ValueError(f"{flag} {text!r}: folder {str(folder)!r} does not exist; create it "
                         "first")
    if not folder.is_dir():
        raise ValueError(f"{flag} {text!r}: {str(folder)!r} is a file, not a folder")
    # os.access says yes to root everywhere: a folder with no write bit at all is
    # read-only on purpose, and is refused for root too.
    if not os.access(folder, os.W_OK | os.X_OK) or not folder.stat().st_mode & 0o222:
        raise ValueError(f"{flag} {text!r}: folder {str(folder)!r} is not writable")


def output_file(text: str, suffix: str, flag: str = "--out",
                beside: Iterable[str] = ()) -> Path:
    """Check an output file named on the command line before any computation.

    It must end in ``suffix``, must not be a folder, and its folder must exist and be
    writable. It and the files written beside it (``beside``: endings that replace
    ``suffix``, e.g. ``(".png",)`` or ``("-fli.png",)``) are then locked for the rest of
    the command, and refused if they exist and andoyer did not write them
    (:func:`andoyer.outputs.guard_file`: the manifest of their folder lists what andoyer
    wrote there; a second run writing them is refused, naming this one). Raises
    ``ValueError`` naming the flag and its value, or the file.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from andoyer.outputs import release_all
    >>> output_file(str(pathlib.Path(tempfile.mkdtemp()) / "sec.nc"), ".nc").name
    'sec.nc'
    >>> release_all()  # what the command line does when the command ends
    >>> output_file("sec.png", ".nc")
    Traceback (most recent call last):
    ...
    ValueError: --out 'sec.png' must name a .nc file (other outputs are written beside it)
    """
    path = Path(text)
    if path.suffix.lower() != suffix:
        raise ValueError(f"{flag} {text!r} must name a {suffix} file (other outputs are "
                         "written beside it)")
    if path.is_dir():
        raise ValueError(f"{flag} {text!r} is an existing folder; name a file")
    _writable_folder(path.parent if str(path.parent) else Path("."), flag, text)
    for p in (path, *(path.with_name(path.stem + end) for end in beside)):
        if p.is_dir():
            raise ValueError(f"{flag} {text!r}: {str(p)!r} would be written beside it and is "
                             "an existing folder; choose another name")
        guard_file(p, flag)
    return path


def output_folder(text: str, flag: str = "--out") -> Path:
    """Check an output folder: an existing writable folder, or one that can be created.

    It is then locked for the rest of the command, and refused if it holds files andoyer
    did not write there (:func:`andoyer.outputs.guard_folder`: a folder's manifest lists
    what andoyer wrote).
    """
    path = Path(text)
    if path.exists():
        if not path.is_dir():
            raise ValueError(f"{flag} {text!r} is an existing file; name a folder")
        _writable_folder(path, flag, text)
    else:
        parent = path.parent
        while not parent.exists() and parent != parent.parent:
            parent = parent.parent
        _writable_folder(parent, flag, text)
        path.parent.mkdir(parents=True, exist_ok=True)
    guard_folder(path, flag)
    return path


def distinct_outputs(outputs: Iterable[Path], inputs: Iterable[Path] = ()) -> None:
    """Refuse outputs that would overwrite each other or an input."""
    seen: dict[Path, Path] = {}
    for p in inputs:
        seen[Path(os.path.abspath(p))] = Path(p)
    for p in outputs:
        key = Path(os.path.abspath(p))
        if key in seen:
            raise ValueError(f"output {str(p)!r} would overwrite {str(seen[key])!r}; choose "
                             "another --out")
        seen[key] = Path(p)


# ---------------------------------------------------------------------- bodies
def add_body_args(p: argparse.ArgumentParser) -> None:
    """The body group of every command that takes a body (:func:`body_from_args`)."""
    g = p.add_argument_group("body")
    g.add_argument("--body", default="paper", choices=tuple(PRESETS),
                   help="each body with its flags: " + "; ".join(
                       f"{k}: {' '.join('--' + f for f in p.flags)} ({p.help})"
                       for k, p in PRESETS.items())
                   + "; --epsilon turns a paper or hess body off the Hess direction")
    for name in ("A", "B", "C"):
        add_term(g, name, type=real(positive=True))
    add_term(g, "mu", type=real())
    add_term(g, "epsilon", type=real(),
             help="turn the Hess body's centre of mass by this angle (rad) in the (e1, e2) "
                  "plane off the Hess direction (RigidBody.near_hess; default 0: Hess)")
    add_term(g, "r", type=real(), nargs=3, metavar=("E1", "E2", "E3"),
             help="direction of the centre of mass (general bodies)")


def body_from_args(args: argparse.Namespace) -> Any:
    """The body of ``--body`` and its flags (:data:`andoyer.body.PRESETS`); a flag the
    body does not take is refused.

    ``--epsilon`` turns a paper or Hess body's centre of mass off the Hess direction
    (:meth:`~andoyer.body.RigidBody.near_hess`, same moments, ``mu`` and branch).
    """
    preset = PRESETS[args.body]
    values = {n: getattr(args, n, None) for n in ("A", "B", "C", "mu", "epsilon", "r")}
    extra = [n for n, v in values.items() if v is not None and n not in preset.flags]
    if extra:
        takes = ", ".join(f"--{n}" for n in preset.flags)
        raise ValueError(f"--body {args.body} does not take --{', --'.join(extra)} (it takes "
                         f"{takes}); for a body of your own use --body hess or --body general")
    missing = [n for n in preset.required if values[n] is None]
    if missing:
        raise ValueError(f"--body {args.body} needs --{', --'.join(missing)}")
    return preset.make(**{n: values[n] for n in preset.flags})


#: Initial-state flag -> (chart, components).
STATE_FLAGS = {"--y0": ("euler_poisson", "G1,G2,G3,gamma1,gamma2,gamma3"),
               "--andoyer": ("andoyer", "l,g,L,G,M"),
               "--hess": ("hess", "theta1,theta2,J1,J2,J3")}


def add_state_args(p: argparse.ArgumentParser, *, required: bool = True) -> None:
    """The initial state of one orbit, in one of the three charts."""
    title = "initial state (one of)" if required else \
        "initial state (one of; none: the whole section plane)"
    st = p.add_argument_group(title)
    st.add_argument("--y0", help="Euler-Poisson state 'G1,G2,G3,gamma1,gamma2,gamma3'")
    st.add_argument("--andoyer", help="Andoyer-Deprit state 'l,g,L,G,M'")
    st.add_argument("--hess", help="Hess-chart state 'theta1,theta2,J1,J2,J3'")


def state_from_args(args: argparse.Namespace, body: Any, *, required: bool = True
                    ) -> tuple[Any, str] | None:
    """``(state, chart)`` of ``--y0`` / ``--andoyer`` / ``--hess`` (checked on the body:
    errors name the flag), or None when none is given and none is required."""
    from andoyer.integrate.api import initial_states

    given = [(flag, getattr(args, flag[2:])) for flag in STATE_FLAGS
             if getattr(args, flag[2:]) is not None]
    if len(given) > 1 or (required and not given):
        raise ValueError("give exactly one initial state: --y0, --andoyer or --hess")
    if not given:
        return None
    flag, text = given[0]
    chart = STATE_FLAGS[flag][0]
    state = floats(text, 6 if chart == "euler_poisson" else 5, flag)
    initial_states(body, state, chart, name=flag)  # errors name the flag, not y0
    return state, chart


class Inputs(NamedTuple):
    """What a command checked before any work (:func:`inputs_from_args`)."""

    out: Path
    """The output file, checked and locked (:func:`output_file`)."""
    body: Any
    """The body of ``--body`` and its flags (:func:`body_from_args`)."""
    state: list[float] | None
    """The initial state of ``--y0`` / ``--andoyer`` / ``--hess``, or None."""
    chart: str | None
    """Its chart (``euler_poisson``, ``andoyer``, ``hess``), or None."""
    section: Any
    """The :class:`~andoyer.integrate.engines.values.Section` of ``--section``, or None."""
    h: float | None
    """The energy level: ``--energy``, or the default level of the body and ``--M``."""


def inputs_from_args(args: argparse.Namespace, suffix: str = ".nc", *,
                     state: Literal["none", "required", "optional"] = "none",
                     level: bool = False, beside: Iterable[str] = (".png",)) -> Inputs:
    """The inputs of a command that integrates a body, checked in one order before any
    work: the output file (``--out``, ending in ``suffix``; figures are written beside
    it), the body, the initial state where the command takes one (``state``), and, where
    the command seeds orbits on a section plane (``level``) and no initial state was
    given, the section and the energy level: ``--energy``, or by default the level of
    :func:`andoyer.integrate.fill.default_h` on ``--M``, checked on the body
    (:func:`andoyer.integrate.budget.check_level`, naming ``--energy``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line (flags of :func:`add_body_args`, :func:`add_state_args`
        where ``state`` is not ``"none"``, :func:`add_level_args` where ``level``).
    suffix : str, default ".nc"
        What ``--out`` must end in.
    beside : iterable of str, default (".png",)
        Endings of the files the command writes beside ``--out`` (:func:`output_file`:
        each is refused if it exists and andoyer did not write it).
    state : {"none", "required", "optional"}, default "none"
        Whether the command takes an initial state, and must have one.
    level : bool, default False
        Whether the command seeds orbits on a section plane of a level (when no initial
        state is given).

    Returns
    -------
    Inputs
        ``out, body, state, chart, section, h`` (None where not asked for or not given).
    """
    out = output_file(args.out, suffix, beside=beside)
    body = body_from_args(args)
    given = None if state == "none" else state_from_args(args, body,
                                                         required=state == "required")
    y0, chart = given if given is not None else (None, None)
    section = h = None
    if level and given is None:
        from andoyer.integrate import Section, budget

        section = Section.parse(args.section)
        h = args.h
        if h is None:
            from andoyer.integrate.fill import default_h

            h = default_h(body, args.M)
        budget.check_level(body, h, "--energy")
    return Inputs(out, body, y0, chart, section, h)


#: The help of ``--engine``: the default is :func:`andoyer.integrate.engines.default_engine_name`'s.
ENGINE_HELP = ("integration engine (default: taylor for orbits, sections and chaos maps, "
               "where it was measured faster; heyoka where installed for the rest; "
               f"else the first of {', '.join(FALLBACK_DEFAULTS)} that can do what the "
               "command asks)")


def add_engine_args(p: argparse.ArgumentParser, *, tolerances: bool = True) -> None:
    """``--engine`` and, where the integration has the mixed criterion, ``--rtol``,
    ``--atol``."""
    add_term(p, "engine", choices=tuple(ENGINES), default=None, help=ENGINE_HELP)
    if tolerances:
        add_term(p, "rtol", type=real(positive=True), default=1e-12,
                 help="relative tolerance (default 1e-12)")
        add_term(p, "atol", type=real(positive=True), default=1e-12,
                 help="absolute tolerance (default 1e-12)")


def add_energy_args(p: argparse.ArgumentParser) -> None:
    """``--energy``, ``--M``: energy level ``h`` (``-h`` is help) and area constant."""
    add_term(p, "h", type=real(), default=None, metavar="H",
             help="energy level H = h (default: H of (l, g, L, G, M) = (0.3, 0, 0.3, 1, M))")
    add_term(p, "M", type=real(), default=0.0,
             help="area constant (G, gamma) = M (default 0)")


def add_level_args(p: argparse.ArgumentParser, *, directed: bool = True) -> None:
    """:func:`add_energy_args` and ``--section``: energy level, area constant and
    section."""
    add_energy_args(p)
    add_term(p, "section", default="theta2=0",
             help="'theta2=VALUE' (plane theta1, J1) or 'g=VALUE' (plane l, L)"
                  + ("; append ':-' for the decreasing direction" if directed else "")
                  + " (default theta2=0)")
