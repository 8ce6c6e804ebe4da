"""Tests that hunt: random bad types, NaN/inf, out-of-range and huge values at the public
entries and on the command line. Each call must end in a clear ``ValueError``/``TypeError``
(our ``CostLimitError`` and ``ArgumentTypeError`` included) or a correct result, quickly.

The public API is enumerated from ``__all__`` (see ``API`` below), so a function is hunted
the day it lands."""

import functools
import importlib
import inspect
import math
import pkgutil
import re
import tempfile
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from andoyer import RigidBody
from andoyer.analysis.chaos.specs import IndicatorRun
from andoyer.analysis.resonance.deprit import JetSpace
from andoyer.cli import EXIT_CODES, main
from andoyer.errors import CostLimitError
from andoyer.integrate.validated.arithmetic import BodySpec

B = RigidBody.paper()
Y0 = [0.0, 0.0, 1.0, 0.0, 0.6, 0.8]

BAD = st.one_of(
    st.none(), st.text(max_size=5), st.booleans(),
    st.sampled_from([math.nan, math.inf, -math.inf, -1.0, 0.0, 1e300, -1e300, 10**30]),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=7),
    st.dictionaries(st.text(max_size=2), st.integers(), max_size=1),
)

ARGS = st.sampled_from(["nan", "inf", "-1", "0", "1e300", "x", "", "1,2", "-0"])
FLAGS = {
    "orbit": ["--t-end", "--n-out", "--rtol", "--andoyer", "--mu", "--body"],
    "section": ["--energy", "--M", "--n-orbits", "--n-crossings", "--section"],
    "chaos-map": ["--n", "--t-end", "--energy", "--tol"],
}


@settings(max_examples=40, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow,
                                 HealthCheck.function_scoped_fixture])
@given(command=st.sampled_from(sorted(FLAGS)), data=st.data())
def test_command_line_never_shows_a_traceback(command, data, tmp_path_factory, capsys):
    flag = data.draw(st.sampled_from(FLAGS[command]))
    value = data.draw(ARGS)
    out = tmp_path_factory.mktemp("cli") / "out.nc"
    argv = [command, "--out", str(out), flag, value]
    if command == "orbit" and flag != "--andoyer":
        argv += ["--andoyer", "0.3,1,0.2,1,0", "--t-end" if flag != "--t-end" else "--n-out",
                 "1" if flag != "--t-end" else "3"]
    if command == "section":
        argv += ["--n-orbits", "2", "--n-crossings", "2"] if flag not in (
            "--n-orbits", "--n-crossings") else []
    if command == "chaos-map":
        argv += ["--n", "3", "--t-end", "2"] if flag not in ("--n", "--t-end") else []
    try:
        main(argv)
    except SystemExit as exc:
        assert exc.code in (0, *EXIT_CODES.values()), argv
    err = capsys.readouterr().err
    assert "Traceback" not in err, (argv, err)


# ----------------------------------------------------------------------------- the public API
# Hunted from ``__all__``, not from a list kept by hand: every public callable of the
# top-level package, of ``integrate`` and ``charts``, and of every module of the
# ``analysis`` sub-packages (their packages re-export the same objects, hunted in their
# modules). A function added tomorrow is hunted tomorrow; if the hunt cannot call it, the
# test says which required argument needs a good value below.
HUNTED = ("andoyer", "andoyer.integrate", "andoyer.charts", "andoyer.analysis")
#: Modules below those packages whose ``__all__`` is hunted too: the attitude API (the
#: charts' and integrate's package APIs do not re-export it whole).
HUNTED_MODULES = ("andoyer.charts.rotation", "andoyer.integrate.orientation")
#: Public functions of otherwise unhunted packages that take user input: the explorer's
#: figure builders (its side panel passes them the selected orbit).
HUNTED_CALLABLES = {"andoyer.plot.space": ("gyroscope_plotly", "gyroscope_animation")}
#: Public subpackages not hunted here, and why (a new subpackage must be placed).
NOT_HUNTED = {
    "andoyer.cli": "the command line is hunted by test_command_line_never_shows_a_traceback",
    "andoyer.explore": "the explorer's forms convert through validation (tests/explore)",
    "andoyer.scan": "scan configurations are hunted in tests/scan (parse_config)",
    "andoyer.plot": "figures of datasets the library made; they compute nothing (but the "
                    "explorer's figure builders, HUNTED_CALLABLES)",
    "andoyer.io": "files the library wrote; damaged files are tested in tests/io",
    "andoyer.report": "the paper report, run from the command line",
    "andoyer.kernels": "Numba kernels on plain floats, below the validating layer",
    "andoyer.symbolic": "SymPy derivations: no user input",
    "andoyer.validation": "the checkers themselves, tested in tests/validation",
}
#: Result records: built by the library, returned to the user, not validated on input.
RECORDS = {"CheckRow", "Crossing", "EquilibriumSet", "EulerAngles", "EulerPoissonEquilibrium",
           "EulerPoinsotFrequencies", "FixedPoint", "FixedPointSet", "Floquet", "Formula",
           "Lines", "ManifoldBranch", "ManifoldCurve", "Monodromy", "PermanentRotation",
           "RotationOrbit", "SectionReturn", "Singular", "Stability", "Torus",
           "CertifiedMelnikov", "MelnikovZero", "HyperbolicRotation", "LocalManifold",
           "TransversalProof"}
#: Public names that take no user input worth hunting (documented acceptance).
NO_INPUT = {"derive_reduced_hamiltonian": "no arguments (a SymPy derivation)",
            "paper_check": "n and seed are hunted in tests/analysis/paper/test_check.py"}


def _public_modules():
    for name in HUNTED:
        pkg = importlib.import_module(name)
        if hasattr(pkg, "__all__"):
            yield pkg
        if name == "andoyer.analysis":
            for info in pkgutil.walk_packages(pkg.__path__, prefix=f"{name}."):
                if not info.ispkg and info.name.count(".") == 3:
                    yield importlib.import_module(info.name)
    for name in HUNTED_MODULES:
        yield importlib.import_module(name)


def _public_callables() -> dict[str, Any]:
    out: dict[str, Any] = {}
    for mod in _public_modules():
        for name in mod.__all__:
            obj = getattr(mod, name)
            if (callable(obj) and not isinstance(obj, type | dict) and name not in RECORDS
                    and name not in NO_INPUT):
                out.setdefault(name, obj)
    for modname, names in HUNTED_CALLABLES.items():
        mod = importlib.import_module(modname)
        for name in names:
            out.setdefault(name, getattr(mod, name))
    return out


API = _public_callables()

HESS = RigidBody.hess(2.5, 1.0, 1.6, mu=0.01)
#: A folder for the functions that write or read a file.
_HUNT_FOLDER = Path(tempfile.mkdtemp(prefix="andoyer-hunt-"))
(_HUNT_FOLDER / "read.json").write_text('{"format": "andoyer-certificate"}')
FREE = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
#: Public functions that need heyoka itself (skipped where it is not installed).
HEYOKA_ONLY: set[str] = set()
#: Good values of required arguments, by name (the paper's symbols mean one thing).
GOOD: dict[str, Any] = {
    "A": 2.5, "B": 2.0, "C": 2.2, "coord": "g", "body": B, "h": 0.2466, "M": 0.0, "G": 1.0,
    "G0": [0.3, 0.8, 0.5], "J1": 0.05, "J2": 1.0, "L": 0.5, "L0": 0.1, "y0": Y0, "y": Y0,
    "x": [0.3, 0.0, 0.3, 1.0, 0.0],
    "x0": [0.0, 4.7, 0.03, 0.1, 0.0], "t": [0.0, 1.0, 2.0], "t_end": 5.0, "T": 5.0,
    "W": np.eye(6)[:3], "w1": [1.0, 0, 0, 0, 0, 0], "w2": [0, 1.0, 0, 0, 0, 0],
    "z": np.exp(0.7j * np.arange(64)), "dt": 0.1, "section": ("theta2", 0.0),
    "n_crossings": 2, "theta2": 0.3, "theta2_0": [0.0, 1.0], "psi": 0.5, "epsilon": [0.05],
    "mu": [0.01], "c": 0.45, "q": 0.1, "p": 0.1, "q0": 0.1, "p0": 0.1, "l": 0.1, "g": 0.2,
    "vartheta": 0.1, "vartheta0": 0.1, "k": 2, "n": 8, "m": 0.3, "nu": 0.5, "tol": 1e-6,
    "scale": 1.0, "eigenvalues": [1j, -1j], "ev": np.array([1j, -1j]),
    "branch": "theta1=0", "sheet": 1, "stability": "unstable", "kind": "G1=0",
    "direction": 1, "chart": "andoyer", "action": 1.0, "period": 10.0, "what": "x",
    "value": 0.3, "phi0": 0.7, "lstar": None, "n_times": 5, "M_values": [0.0],
    "n_check": 2, "chaotic": np.ones((2, 6), bool), "accessible": np.ones((2, 6), bool),
    "theta1": (np.arange(6) + 0.5) * np.pi / 3,
}
#: The near-Hess body of the finite-mu proof (decimals).
NEAR_HESS_SPEC = BodySpec("2.5", "1.0", "1.6", 1, "0.1", "0.05")
#: Jets of degree 2 on a 4 x 1 Fourier grid (the Lie-Deprit triangle's arguments).
_JETS = JetSpace(2, 4, 1)
#: Where a function needs other values than the shared ones (and small sizes: cost guard).
OVERRIDES: dict[str, dict[str, Any]] = {
    "chaos_map": {"grid": 4, "run": IndicatorRun(t_end=5.0), "engine": "numba"},
    "chaos_border": {"body": HESS, "h": 0.3125, "n": 4, "t_end": 5.0, "engine": "numba"},
    "regular_reference": {"body": HESS, "h": 0.3125, "n": 4, "t_end": 5.0,
                          "engine": "numba"},
    "chaos_border_map": {"body": HESS, "h": 0.3125, "n": 4, "t_end": 5.0,
                         "engine": "numba", "mu": [0.01], "epsilon": [0.05]},
    "melnikov_off_hess": {"body": HESS, "epsilon": 0.05},
    "prove_certificate": {"branch": "theta1=4phi0", "digits": 10},
    "local_unstable_manifold": {"body": NEAR_HESS_SPEC, "radius": 1e-6, "order": 12,
                                "bits": 64},
    "prove_transversal": {"body": NEAR_HESS_SPEC},
    "prove_transversal_certificate": {"body": NEAR_HESS_SPEC},
    "mu_interval": {"body": {"mu": "0.05", "mu_radius": "0"}},
    "chosen": {"indicator": "both"},
    "lie_deprit": {"space": _JETS, "H": [_JETS.zeros()], "omega": [0.5, 1.0],
                   "resonance": (1, 2)},
    "transform": {"space": _JETS, "f": _JETS.zeros(), "Ws": [_JETS.zeros()]},
    "check_grid_size": {"what": "n"},
    "elliptic_pi": {"n": 0.3},
    "lagrange_top": {"body": RigidBody.lagrange(1.0, 0.6, 1.0),
                     "y0": [0.2, 0.1, 1.5, 0.0, math.sin(0.8), math.cos(0.8)]},
    "euler_poinsot_frequencies": {"body": FREE, "h": 0.21},
    "euler_poinsot_momentum": {"body": FREE},
    "orbit_frequencies": {"body": FREE, "t_end": 500.0, "n_samples": 64},
    "alignment_indices": {"t_end": 5.0, "n_times": 5},
    "indicators": {"t_end": 5.0, "n_times": 5, "engine": "numba"},
    "hamiltonian": {"x": Y0}, "vector_field": {"x": Y0},
    "event_projector": {"kind": "psi"}, "flow_to_section": {"kind": "psi"},
    "return_map": {"x": [0.0, 0.0]}, "section_state": {"x": [0.0, 0.0]},
    "poincare": {"section": "G3=0"},
    "resonance_widths": {"section": "g=0", "max_order": 9},
    "resonant_tori": {"max_order": 9},
    "free_top_at_gap": {"gap": 0.01},
    "island_prediction": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3), "h": 1.0,
                          "resonance": "3:1", "axis": 1, "order_mu": 1},
    "free_top_phase": {"momentum": [0.3, 0.9, 0.1]},
    "elliptic_f": {"phi": 0.7},
    "measure_island": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3), "h": 1.0,
                       "resonance": "3:1", "axis": 1, "n_crossings": 60, "n_seeds": 1,
                       "n_rounds": 1, "engine": "numba"},
    "island_rotation_numbers": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3), "h": 1.0,
                                "resonance": "3:1", "s": [0.0], "axis": 1, "n_crossings": 60,
                                "engine": "numba"},
    "periodic_orbit_normal_form": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=1e-2), "h": 1.0,
                                   "seed": [0.0, 0.0], "degree": 3, "engine": "numba"},
    "orbit_rotation_numbers": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=1e-2), "h": 1.0,
                               "amplitudes": [0.05], "n_returns": 64, "engine": "numba"},
    "resonant_normal_form": {"body": RigidBody(2.5, 1.0, 2.0, 1e-3, (0.6, 0.48, 0.64)),
                             "h": 1.0, "resonance": "2:1", "axis": 2},
    "splitting_vs_epsilon": {"body": HESS, "n_phase": 8},
    "last_torus": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3), "h": 1.0, "head": (2,),
                   "axis": 2, "n_convergents": 1, "progress": False},
    "critical_mu_curve": {"body": RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3), "h_values": [1.0],
                          "mu_range": (0.05, 0.0501), "progress": False, "head": (2,),
                          "axis": 2, "n_convergents": 1},
    "convergents": {"head": (2,), "n": 3}, "noble_number": {"head": (2,)},
    # the attitude API: quaternions (scalar first), rotation matrices, Euler angles
    **{f: {"q": [0.9, 0.1, -0.3, 0.2]} for f in ("quaternion_conjugate", "rotation_matrix",
                                                 "euler_angles")},
    "quaternion_product": {"left": [0.9, 0.1, -0.3, 0.2], "right": [0.5, 0.5, -0.5, 0.5]},
    "quaternion_from_matrix": {"R": np.eye(3)},
    "quaternion_from_euler": {"psi": 0.3, "theta": 1.1, "phi": -0.4},
    "quaternion_from_vertical": {"gamma": [0.0, 0.6, 0.8]},
    "attitude_variables": {"q": [[1.0, 0.0, 0.0, 0.0]], "G": [[0.0, 0.0, 1.0]],
                           "dims": ("time",)},
    "gyroscope_animation": {"fps": 20},
    "write_certificate": {"path": str(_HUNT_FOLDER / "cert.json")},
    "read_certificate": {"path": str(_HUNT_FOLDER / "read.json")},
    **{f: {"mu": 0.01} for f in ("pendulum_energy", "pendulum_modulus", "pendulum_motion",
                                 "pendulum_period", "pendulum_solution",
                                 "predicted_splitting")},
}
#: Arguments that are results of the library (built once, on first use).
LAZY_USERS = {"verify_certificate", "write_certificate", "grow_manifold",
              "measure_splitting", "splitting_at", "orbits_dataset",
              "axis_trace", "precession_nutation", "herpolhode", "normal_form_frequency",
              "gyroscope_plotly", "gyroscope_animation", "orbit_rotation_numbers"}
LAZY = {
    "branch": lambda: _manifold()[0], "wu": lambda: _manifold()[1],
    "ws": lambda: _manifold()[2], "orbits": lambda: [_manifold()[0].orbit],
    "nf": lambda: _normal_form(), "I": lambda: [0.01],
    "ds": lambda: _attitude_dataset(),
    "cert": lambda: _certificate(),
    "normal_form": lambda: _periodic_normal_form(),
}


@functools.cache
def _periodic_normal_form() -> xr.Dataset:
    from andoyer.analysis.resonance.normal_form import periodic_orbit_normal_form

    return periodic_orbit_normal_form(RigidBody.hess(3.0, 1.0, 2.0, mu=1e-2), 1.0, 0.0,
                                      [0.0, 0.0], degree=3, engine="numba")


@functools.cache
def _certificate() -> dict[str, Any]:
    from andoyer.analysis.splitting.certificate import prove_certificate

    return prove_certificate(B, branch="theta1=4phi0", digits=10)


@functools.cache
def _attitude_dataset() -> xr.Dataset:
    from andoyer.integrate import attitude

    return attitude(FREE, [0.3, 0.8, 0.5, 0.0, 0.6, 0.8], [0.0, 0.5, 1.0], engine="numba")


@functools.cache
def _normal_form() -> Any:
    from andoyer.analysis.resonance.birkhoff import birkhoff_normal_form

    return birkhoff_normal_form(B, 1.0, order=4)


@functools.cache
def _manifold() -> tuple[Any, Any, Any]:
    from andoyer.analysis.splitting.manifolds import grow_manifold, manifold_branch
    from andoyer.analysis.splitting.section_map import rotation_energy

    h = rotation_energy(HESS)
    wu = manifold_branch(HESS, h, "unstable", delta=1e-4)
    ws = manifold_branch(HESS, h, "stable", delta=1e-4)
    return wu, grow_manifold(wu, max_points=200), grow_manifold(ws, max_points=200)


def _good_args(name: str, func: Any) -> dict[str, Any]:
    args: dict[str, Any] = {}
    for p in inspect.signature(func).parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        if p.name in OVERRIDES.get(name, {}):
            args[p.name] = OVERRIDES[name][p.name]
        elif p.default is inspect.Parameter.empty and p.name in LAZY and (
                name in LAZY_USERS):
            args[p.name] = LAZY[p.name]()
        elif p.default is inspect.Parameter.empty:
            assert p.name in GOOD, (f"{name}: no good value for its argument {p.name!r}: "
                                    "add one to GOOD or OVERRIDES so that it is hunted")
            args[p.name] = GOOD[p.name]
    return args


#: Bad values by class. ``shape``: an array of the wrong rank where a number or a vector
#: belongs. Each must be refused naming the argument, or give a finite correct answer.
BAD_CLASSES: dict[str, Any] = {
    "bool": True, "str": "x", "nan": math.nan, "inf": math.inf, "huge": 1e300,
    "negative": -1.0, "shape": [[[1.0, 2.0]]], "none": None,
}
#: Classes that must be refused before any work (so they are hunted in ``make test`` for
#: every function); the numeric extremes may start work the cost guard bounds (slow run).
TYPE_CLASSES = ("bool", "str", "shape", "none", "nan")
#: The numeric extremes, hunted in the slow run (the type classes are in the fast one).
EXTREME_CLASSES = tuple(c for c in BAD_CLASSES if c not in TYPE_CLASSES)
#: (argument, class) pairs a function legitimately accepts: the class is the argument's
#: type (``progress=True``, ``name="x"``) or its ``None`` means "the default". An array
#: argument (``ArrayLike``) may take another shape (functions are elementwise or take
#: several states); the answer must then be finite.
ACCEPTED = {("name", "str"), ("what", "str"), ("axis", "str")}


def _accepts(param: inspect.Parameter, cls: str) -> bool:
    """Whether ``cls`` is a legitimate value of ``param`` (its annotation says so)."""
    ann = str(param.annotation)
    if (param.name, cls) in ACCEPTED:
        return True
    if cls == "bool" and "bool" in ann:
        return True
    if cls == "none" and (param.default is None or "None" in ann):
        return True
    return False


#: Words a message may use for an argument instead of its name.
ALIASES = {"coord": ("section coordinate",), "value": ("section value",),
           "direction": ("section direction",)}


def _names(message: str, name: str) -> bool:
    return any(re.search(rf"(?<![A-Za-z0-9_]){re.escape(word)}(?![A-Za-z0-9_])", message)
               for word in (name, *ALIASES.get(name, ())))


def _nonfinite(res: Any) -> bool:
    if isinstance(res, xr.Dataset):
        # NaN as a documented separator of polylines is data; so is NaN at the points
        # the dataset's own mask marks inaccessible (off the energy level).
        mask = res.get("accessible")

        def values(v: xr.DataArray) -> Any:
            if mask is not None and set(mask.dims) <= set(v.dims):
                return v.where(mask, 0.0).values
            return v.values
        return any(_nonfinite(values(v)) for v in res.data_vars.values()
                   if "(NaN: " not in str(v.attrs.get("long_name", "")))
    if isinstance(res, np.ndarray):
        return res.dtype.kind in "fc" and not bool(np.all(np.isfinite(res)))
    if isinstance(res, float):
        return not math.isfinite(res)
    if isinstance(res, tuple | list):
        return any(_nonfinite(v) for v in res)
    return False


def _call(func: Any, args: dict[str, Any]) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return func(**args)


_BASELINES: dict[str, bool] = {}


def _baseline_nonfinite(name: str, func: Any, args: dict[str, Any]) -> bool:
    if name not in _BASELINES:
        _BASELINES[name] = _nonfinite(_call(func, args))
    return _BASELINES[name]


def _hunt(name: str, classes: tuple[str, ...]) -> list[str]:
    """Every argument of ``name`` with every bad class: the failures, described."""
    func = API[name]
    args = _good_args(name, func)
    base_nonfinite = _baseline_nonfinite(name, func, args)
    failures = []
    for param in inspect.signature(func).parameters.values():
        if param.kind in (param.VAR_POSITIONAL, param.VAR_KEYWORD):
            continue
        for cls in classes:
            if _accepts(param, cls):
                continue
            call = f"{name}({param.name}={cls})"
            t0 = time.perf_counter()
            try:
                res = _call(func, {**args, param.name: BAD_CLASSES[cls]})
            except CostLimitError:
                continue  # the cost guard names its limit and how to raise it
            except (ValueError, TypeError) as exc:
                if not _names(str(exc), param.name):
                    failures.append(f"{call}: {type(exc).__name__} not naming "
                                    f"{param.name!r}: {str(exc)[:120]}")
                continue
            except Exception as exc:  # noqa: BLE001 -- what leaked is the finding
                failures.append(f"{call}: leaked {type(exc).__name__}: {str(exc)[:120]}")
                continue
            finally:
                if time.perf_counter() - t0 > 20.0:
                    failures.append(f"{call}: took {time.perf_counter() - t0:.0f} s")
            array = "ArrayLike" in str(param.annotation)
            if cls in ("bool", "str", "none") or (cls == "shape" and not array):
                failures.append(f"{call}: accepted silently")
            elif _nonfinite(res) and not base_nonfinite:
                failures.append(f"{call}: accepted, returned NaN or infinity")
    return failures


def test_every_public_subpackage_is_hunted_or_placed():
    import andoyer

    subpackages = {f"andoyer.{m.name}" for m in pkgutil.iter_modules(andoyer.__path__)
                   if m.ispkg and not m.name.startswith("_")}
    assert subpackages <= set(HUNTED) | set(NOT_HUNTED), subpackages - set(HUNTED) - set(
        NOT_HUNTED)
    for mod in _public_modules():
        assert isinstance(mod.__all__, list | tuple), mod.__name__
    assert {"naff", "gali", "sali", "orbit_frequencies", "euler_poinsot_momentum",
            "melnikov_off_hess", "chaos_border", "propagate", "cite"} <= set(API)


@pytest.mark.timeout(120)  # a hang is a finding, not a stuck suite
@pytest.mark.parametrize("name", sorted(API))
def test_public_api_refuses_bad_types_naming_the_argument(name):
    """bool, text, a wrong shape, None and NaN for every argument of every public
    function: a ValueError/TypeError naming that argument, never a leaked message."""
    if name in HEYOKA_ONLY:
        pytest.importorskip("heyoka")
    failures = _hunt(name, TYPE_CLASSES)
    assert not failures, "\n".join(failures)


@pytest.mark.slow
@pytest.mark.timeout(600)
@pytest.mark.parametrize("name", sorted(API))
def test_public_api_refuses_extreme_values_or_stays_finite(name):
    """The numeric extremes (inf, 1e300, -1) for every argument of every public
    function: refused naming the argument (or by the cost guard), or a finite answer.
    About 5 minutes on one core for the whole API (``-m slow -k extreme``)."""
    if name in HEYOKA_ONLY:
        pytest.importorskip("heyoka")
    failures = _hunt(name, EXTREME_CLASSES)
    assert not failures, "\n".join(failures)


#: Seconds a call with one bad value may take before it counts as a hang, where the good
#: arguments alone are a validated computation (a cone proof: 2-4 s on an idle core; the
#: theorem, where a bad value leaves the search to run: 20-60 s).
ALLOWED_SECONDS = {"local_unstable_manifold": 60.0, "prove_transversal": 120.0}


@pytest.mark.timeout(180)
@pytest.mark.parametrize("name", sorted(API))
@settings(max_examples=8, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_public_entries_reject_bad_values_clearly(name, data):
    """Random bad values (hypothesis) at a random argument of every public callable of
    ``API`` (enumerated from ``__all__``): a clear ``ValueError``/``TypeError`` or a
    result, quickly."""
    if name in HEYOKA_ONLY:
        pytest.importorskip("heyoka")
    func = API[name]
    params = [p.name for p in inspect.signature(func).parameters.values()
              if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    if not params:
        return
    param = data.draw(st.sampled_from(params))
    value = data.draw(BAD)
    if value is None and inspect.signature(func).parameters[param].default is None:
        return  # the argument's default, not a bad value: the whole computation
    args = {**_good_args(name, func), param: value}
    t0 = time.perf_counter()
    try:
        _call(func, args)
    except (ValueError, TypeError) as exc:
        assert str(exc), name  # a message, naming something
    assert time.perf_counter() - t0 < ALLOWED_SECONDS.get(name, 20.0), name


#: |G| between what the integrators take (MAX_MOMENTUM) and what a closed form takes
#: (MAX_ACTION), and beyond both.
BETWEEN, BEYOND = 1e120, 2e150


#: What each argument name means in the paper's vocabulary (one name, one meaning:
#: tests/test_vocabulary.py), hence the range a decorated function must give it
#: (``ranges=`` of ``validation.checks_arguments``; the decorator infers nothing from names).
QUANTITIES: dict[str, str] = {
    **dict.fromkeys(("h", "h0", "energy"), "energy"),
    **dict.fromkeys(("L", "M", "J1", "J2", "J3", "L0", "p", "p0"), "action"),
    **dict.fromkeys(("G", "G0", "action"), "length"),
    **dict.fromkeys(("l", "g", "theta1", "theta2", "theta3", "psi", "psi0", "vartheta",
                     "vartheta0", "q", "q0", "phi0", "t0"), "angle"),
    **dict.fromkeys(("t_end", "T", "period", "duration"), "time"),
    **dict.fromkeys(("mu", "c"), "scale"),
    **dict.fromkeys(("epsilon", "value"), "finite"),
    **dict.fromkeys(("tol", "xtol", "rtol", "atol"), "tolerance"),
    **dict.fromkeys(("sheet",), "sheet"),
    **dict.fromkeys(("n", "k", "steps", "mu_steps", "window", "points_per_period",
                     "boundary_grid", "n_check", "n_times", "n_samples", "n_initial",
                     "n_levels", "n_curve", "n_phase", "n_orbits", "n_crossings", "n_freq",
                     "n_points"), "count"),
}


def _decorated_functions():
    """``(dotted name, function)`` of every function of andoyer decorated by
    ``checks_arguments`` (directly or through ``checks_body``)."""
    import andoyer

    seen = {}
    for info in pkgutil.walk_packages(andoyer.__path__, "andoyer."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if callable(obj) and hasattr(obj, "__checks__") \
                    and getattr(obj, "__module__", None) == info.name:
                seen[f"{info.name}.{name}"] = obj
    return sorted(seen.items())


def test_every_decorated_function_gives_its_quantities_their_ranges():
    """The ranges are given at decoration, explicitly; this checks them against the
    vocabulary: an argument named like a quantity and annotated as a number (an ``int``
    for counts and sheets) is given the range of its name, and no argument another."""
    from andoyer.validation.arguments import _scalar_kind

    wrong = []
    found = _decorated_functions()
    assert len(found) > 100
    for dotted, func in found:
        ranges = dict(func.__checks__.ranges)
        namespace = getattr(inspect.unwrap(func), "__globals__", None)
        for p in inspect.signature(func).parameters.values():
            kind = _scalar_kind(p.annotation, namespace)
            want = QUANTITIES.get(p.name)
            qualifies = kind is not None and want is not None and (
                kind[0] == "int" if want in ("count", "sheet") else kind[0] in ("float", "array"))
            if ranges.get(p.name) != (want if qualifies else None):
                wrong.append(f"{dotted}({p.name}): {ranges.get(p.name)}, its name says {want}")
    assert wrong == []


def _momentum_arguments() -> list[tuple[str, str]]:
    """``(function, argument)``: every public argument that is an action, a length or an
    energy level of a body (the quantities :func:`validation.momentum_limit` bounds)."""
    out = []
    for name, func in sorted(API.items()):
        params = inspect.signature(func).parameters
        for p in params:
            kind = QUANTITIES.get(p)
            if kind in ("action", "length") or (kind == "energy" and "body" in params):
                out.append((name, p))
    return out


def _at(name: str, param: str, G: float, good: Any) -> Any:
    """The value of ``param`` that means ``|G| = G`` (an energy: the level reaching it; a
    vector where the good value is one: ``good`` scaled)."""
    if QUANTITIES[param] != "energy":
        vector = np.asarray(good, dtype=float) if np.ndim(good) else None
        return G if vector is None else list(G * vector / np.linalg.norm(vector))
    body = {**GOOD, **OVERRIDES.get(name, {})}["body"]
    return G * G * min(body.a, body.b, body.c) / 2.0 - body.mu


@pytest.mark.parametrize("name, param", _momentum_arguments())
def test_one_momentum_limit_for_actions_and_levels(name, param):
    """One rule (``validation.momentum_limit``) for every action and every level of a body:
    a function of closed forms (decorated ``closed_form=True``) takes ``|G|`` up to
    MAX_ACTION, any other up to MAX_MOMENTUM (what the integrators take), whether ``|G|``
    is given or reached by a level. Before, closed forms took an action J2 = 1e120 but
    refused the level reaching it ("beyond what the integrators take"), and an integrating
    function took it and refused its own state, naming y0."""
    from andoyer.validation import MAX_ACTION, MAX_MOMENTUM

    func = API[name]
    checks = getattr(func, "__checks__", None)
    closed = checks.closed_form if checks is not None else bool(
        getattr(importlib.import_module(func.__module__), "CLOSED_FORM", False))
    args = _good_args(name, func)
    limit = MAX_ACTION if closed else MAX_MOMENTUM
    for G in (BETWEEN, BEYOND):
        try:
            _call(func, {**args, param: _at(name, param, G, args.get(param, 1.0))})
        except (ValueError, TypeError) as exc:
            said = str(exc)
            if G > limit:  # refused, naming the argument (its own range may come first)
                assert _names(said, param), f"{name}({param} at |G| = {G:g}): {said[:160]}"
            else:  # a closed form: its own ranges only, not the integrators' limit
                assert f"{MAX_MOMENTUM:g}" not in said, \
                    f"{name}({param} at |G| = {G:g}) refused by the integrators' limit: " \
                    f"{said[:160]}"
            continue
        except CostLimitError:
            assert G <= limit
            continue
        assert G <= limit, f"{name}({param} at |G| = {G:g}) was accepted beyond {limit:g}"


# ------------------------------------------------------------------ engine constructors
def _engine_options() -> list[tuple[str, str]]:
    """``(engine, option)``: every keyword of every registered engine's constructor
    (from the registry, so an engine added tomorrow is hunted tomorrow)."""
    from andoyer.integrate.engines import ENGINES, engine_class

    return [(name, p) for name in sorted(ENGINES)
            for p in inspect.signature(engine_class(name)).parameters]


#: Values no engine option takes: the bad classes of the API hunt and counts beyond what
#: the compiled kernels hold (``max_steps=10**30`` was accepted, then propagate raised
#: OverflowError from kernels/threads.py).
ENGINE_BAD = {**BAD_CLASSES, "zero": 0, "huge_int": 10**30, "fraction": 2.5}
#: Documented values of the classes above: chunksize=0 splits the orbits evenly up front.
ENGINE_ACCEPTED = {("chunksize", "zero")}


@pytest.mark.parametrize("engine, option", _engine_options())
def test_engine_constructors_refuse_bad_options_naming_them(engine, option):
    from andoyer.integrate.engines import engine_class

    if engine == "heyoka":
        pytest.importorskip("heyoka")
    param = inspect.signature(engine_class(engine)).parameters[option]
    failures = []
    for cls, value in ENGINE_BAD.items():
        if (_accepts(param, cls) or (option, cls) in ENGINE_ACCEPTED
                or (cls == "fraction" and "float" in str(param.annotation))):
            continue
        try:
            eng = engine_class(engine)(**{option: value})
        except (ValueError, TypeError) as exc:
            if not _names(str(exc), option):
                failures.append(f"{engine}({option}={cls}): not naming it: {exc}")
            continue
        except Exception as exc:  # noqa: BLE001 -- what leaked is the finding
            failures.append(f"{engine}({option}={cls}): leaked {type(exc).__name__}: {exc}")
            continue
        failures.append(f"{engine}({option}={cls}): accepted, {eng!r}")
    assert not failures, "\n".join(failures)
