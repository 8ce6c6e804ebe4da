"""The splitting problem is prepared once (:mod:`andoyer.analysis.splitting.problem`): the
nearest Hess body is computed once per call of ``separatrix_splitting``, and an engine
object passed by the user is the one whose kernels run (its options are kept)."""

from __future__ import annotations

import pytest

from andoyer.analysis.splitting.measure import separatrix_splitting
from andoyer.analysis.splitting.periodic import rotation_energy, rotation_orbit
from andoyer.analysis.splitting.problem import splitting_problem
from andoyer.analysis.splitting.section_map import flow_engine
from andoyer.body import RigidBody
from andoyer.errors import IntegrationError
from andoyer.integrate.engines import resolve_engine


def test_an_engine_instance_is_kept_as_given():
    eng = resolve_engine("numba", max_steps=10**7)
    assert flow_engine(eng) is eng
    body = RigidBody.paper()
    assert splitting_problem(body, rotation_energy(body), engine=eng).engine is eng


def test_the_engines_options_reach_the_kernel(monkeypatch):
    """Spy on the engine object: every flow of the orbit runs on it, and its step limit
    is the kernel's (a limit of 5 steps fails, the same engine by name does not)."""
    body = RigidBody.paper()
    h = rotation_energy(body)
    eng = resolve_engine("numba", max_steps=10**7)
    seen = []
    original = eng._tangent_crossings

    def spy(*args, **kwargs):
        seen.append(eng.max_steps)
        return original(*args, **kwargs)

    monkeypatch.setattr(eng, "_tangent_crossings", spy)
    orbit = rotation_orbit(body, h, engine=eng)
    assert orbit.flow is eng and orbit.engine == "numba"
    assert seen and set(seen) == {10**7}
    starved = resolve_engine("numba", max_steps=5)
    with pytest.raises(IntegrationError, match="max_steps=5"):
        rotation_orbit(body, h, engine=starved)


def test_separatrix_splitting_keeps_the_engine_and_finds_the_hess_body_once(monkeypatch):
    body = RigidBody.near_hess(2.5, 1.0, 1.6, 0.01, 0.1)
    calls = []
    nearest = RigidBody.nearest_hess

    def counted(self):
        calls.append(self)
        return nearest(self)

    monkeypatch.setattr(RigidBody, "nearest_hess", counted)
    with pytest.raises(IntegrationError, match="max_steps=5"):
        separatrix_splitting(body, [0.01], n_phase=4, delta=1e-4,
                             engine=resolve_engine("numba", max_steps=5))
    assert len(calls) == 1
    calls.clear()
    eng = resolve_engine("numba", max_steps=10**7)
    out = separatrix_splitting(body, [0.01, 0.02], n_phase=8, delta=1e-4, engine=eng)
    assert len(calls) == 1
    assert out["splitting"].attrs["engine"] == out["orbit_leaves"].attrs["engine"]
