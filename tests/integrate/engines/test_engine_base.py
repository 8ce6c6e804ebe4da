"""What EngineBase provides the engines of compiled ensemble kernels (numba, taylor): one
check of their options, one slice of the kernels' parameters, one failure message, one
repr (these were written out in each engine)."""

from __future__ import annotations

import numpy as np
import pytest

from andoyer import RigidBody, from_andoyer
from andoyer.errors import IntegrationError
from andoyer.integrate.engines import ENGINES, engine_class
from andoyer.integrate.engines.base import PAR, EngineBase, Tolerance, runtime_parameters
from andoyer.integrate.engines.values import Tolerance as ValuesTolerance

ENSEMBLE = {"numba": "numba DOP853", "taylor": "Taylor integration"}
Y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4], [0.1, 0.4, 0.3, 1.0, 0.2]])


def test_the_seam_reexports_its_values() -> None:
    assert Tolerance is ValuesTolerance


@pytest.mark.parametrize("name", sorted(ENSEMBLE))
@pytest.mark.parametrize(("option", "bad"), [("max_steps", 0), ("chunksize", -1),
                                             ("n_threads", 0), ("n_threads", True),
                                             ("max_steps", 2.5)])
def test_ensemble_options_are_checked_naming_them(name, option, bad) -> None:
    with pytest.raises(ValueError, match=option):
        engine_class(name)(**{option: bad})


@pytest.mark.parametrize("name", sorted(ENSEMBLE))
def test_a_failed_orbit_is_named_with_its_reason(name) -> None:
    eng = engine_class(name)(max_steps=3, n_threads=1)
    assert repr(eng) == (f"{type(eng).__name__}(max_steps=3, chunksize=1, "
                         + ("tolerance_factor=0.025, " if name == "numba" else "")
                         + "n_threads=1)")
    with pytest.raises(IntegrationError, match=rf"^{ENSEMBLE[name]} failed in propagate "
                                               r"for 2 orbit\(s\), first orbit 0: .* after "
                                               r"3 steps$"):
        eng.propagate(Y0, np.array([0.0, 100.0]), RigidBody.paper().engine_params,
                      Tolerance(1e-12, 1e-12))


def test_kernel_params_are_the_bodys_part_of_par() -> None:
    par = runtime_parameters(RigidBody.paper().engine_params, None, 2.0)
    k = EngineBase._kernel_params(par)
    assert k.flags.c_contiguous and k.size == PAR["phi0"] + 1 == 8
    np.testing.assert_array_equal(k, RigidBody.paper().engine_params)


def test_every_engine_has_a_repr_of_its_options() -> None:
    for name in ENGINES:
        cls = engine_class(name)
        assert set(cls.repr_options) <= set(cls.__init__.__code__.co_varnames), name


def test_measured_defaults_pick_the_engine_per_workload(monkeypatch):
    """Where heyoka is installed, a workload listed in MEASURED_DEFAULTS runs on the
    engine measured faster there, and every other workload on heyoka; ``poincare`` names
    its workload by the section (an angle, or a state component)."""
    import numpy as np

    from andoyer import RigidBody
    from andoyer.integrate import Section, engines, poincare
    from andoyer.integrate.engines import default_engine_name, resolve_engine
    from andoyer.integrate.engines.base import Capability

    monkeypatch.setattr(engines, "heyoka_available", lambda: True)
    monkeypatch.setattr(engines, "MEASURED_DEFAULTS", {"angle_section": "numba"})
    assert default_engine_name(Capability.CROSSINGS, workload="angle_section") == "numba"
    assert default_engine_name(Capability.CROSSINGS, workload="component_section") == "heyoka"
    assert default_engine_name(Capability.CROSSINGS) == "heyoka"
    # an engine without the capability asked for is not taken
    monkeypatch.setattr(engines, "MEASURED_DEFAULTS", {"tangent": "scipy"})
    assert default_engine_name(Capability.TANGENT_CROSSINGS, workload="tangent") == "heyoka"
    with pytest.raises(ValueError, match="workload must be one of"):
        default_engine_name(workload="W2")
    monkeypatch.setattr(engines, "MEASURED_DEFAULTS", {"angle_section": "numba",
                                                       "component_section": "scipy"})
    seen = []
    real = engines.resolve_engine

    def spy(*args, **kwargs):
        eng = real(*args, **kwargs)
        seen.append(eng.name)
        return eng

    monkeypatch.setattr("andoyer.integrate.api.resolve_engine", spy)
    body = RigidBody.paper()
    y0 = np.array([[0.3, 0.0, 0.3, 1.0, 0.0]])
    poincare(body, y0, Section("theta2", 0.0), 2, chart="andoyer", progress=False)
    poincare(body, y0, Section("G3", 0.0), 2, chart="andoyer", progress=False)
    assert seen == ["numba", "scipy"]
    assert resolve_engine("scipy", Capability.CROSSINGS, workload="angle_section").name == \
        "scipy"  # a named engine is the engine named


#: Every option of every engine's constructor, with values it must refuse naming it:
#: beyond its range (a count the kernels' int64 cannot hold, 10**30), of the wrong type.
ENGINE_OPTIONS = {
    "max_steps": [10**30, 0, True, "x", 2.5, None, float("nan")],
    "chunksize": [10**30, -1, True, "x"],
    "n_threads": [10**6, 0, True, "x", 2.5],
    "tolerance_factor": [True, "x", float("nan"), 0.0, 2.0, None, float("inf")],
    "batch_size": [10**30, 0, True, "x"],
}


def _constructor_options(name):
    import inspect

    params = inspect.signature(engine_class(name)).parameters
    return [p for p in params if p != "self"]


@pytest.mark.parametrize("name", sorted(ENGINES))
def test_every_engine_constructor_refuses_bad_options_naming_them(name) -> None:
    """TaylorEngine(max_steps=10**30) was accepted and propagate raised OverflowError from
    kernels/threads.py; a string tolerance_factor raised "'<' not supported"."""
    if name == "heyoka":
        pytest.importorskip("heyoka")
    options = _constructor_options(name)
    assert set(options) <= set(ENGINE_OPTIONS), set(options) - set(ENGINE_OPTIONS)
    for option in options:
        for bad in ENGINE_OPTIONS[option]:
            if bad is None and option in ("n_threads", "batch_size"):
                continue  # None means the default
            with pytest.raises(ValueError, match=rf"^{option} must be"):
                engine_class(name)(**{option: bad})


@pytest.mark.parametrize("name", sorted(ENSEMBLE))
def test_the_largest_max_steps_accepted_reaches_the_kernels(name) -> None:
    from andoyer.integrate.engines.values import MAX_STEPS

    eng = engine_class(name)(max_steps=MAX_STEPS, n_threads=1)
    out = eng.propagate(Y0, np.array([0.0, 0.5]), RigidBody.paper().engine_params,
                        Tolerance(1e-10, 1e-10))
    assert np.isfinite(out).all()
