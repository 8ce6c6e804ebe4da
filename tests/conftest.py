"""Shared fixtures and Hypothesis profiles for the core test suite.

Profiles (select with ``HYPOTHESIS_PROFILE=<name>``):

* ``dev`` (default): 100 examples per property, no deadline (Numba/NumPy warm-up
  makes first calls slow, which is not what a deadline should measure);
* ``ci``: the same, derandomized so that a CI failure reproduces exactly;
* ``thorough``: 2000 examples, for a hunt near the singular sets.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

from andoyer import RigidBody

settings.register_profile("dev", max_examples=100, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", parent=settings.get_profile("dev"), derandomize=True)
settings.register_profile("thorough", parent=settings.get_profile("dev"), max_examples=2000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "dev"))


@pytest.fixture(scope="session")
def paper_body() -> RigidBody:
    """The paper's Hess body (A, B, C) = (2.5, 2.0, 2.2), mu = 0.01, branch +1."""
    return RigidBody.paper()


@pytest.fixture(scope="session")
def hess_minus_body() -> RigidBody:
    """A Hess body on the other branch of (2): phi0 in (-pi/2, 0), heavier than the paper's."""
    return RigidBody.hess(2.5, 2.0, 2.2, mu=0.3, branch=-1)


@pytest.fixture(scope="session")
def general_body() -> RigidBody:
    """No symmetry, no Hess condition, centre of mass off every principal plane."""
    return RigidBody(1.3, 1.7, 2.1, mu=0.7, r=(0.3, -0.5, 0.8))
