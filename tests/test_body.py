"""RigidBody: validation, Hess conditions (2) and (8), phi0 (11), kappa (13), presets."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from andoyer import RigidBody
from andoyer.body import PAPER_BODY


# --------------------------------------------------------------------------- validation
@pytest.mark.parametrize("moments", [(0.0, 1.0, 1.0), (1.0, -2.0, 1.5), (1.0, 1.0, -0.0)])
def test_non_positive_moment_rejected(moments):
    with pytest.raises(ValueError, match="finite positive moment"):
        RigidBody(*moments)


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
@pytest.mark.parametrize("position", [0, 1, 2])
def test_non_finite_moment_rejected(bad, position):
    moments = [1.0, 1.2, 1.5]
    moments[position] = bad
    with pytest.raises(ValueError, match="finite positive moment"):
        RigidBody(*moments)


def test_non_numeric_moment_rejected():
    with pytest.raises(ValueError, match="real number"):
        RigidBody("heavy", 1.0, 1.0)  # type: ignore[arg-type]


@pytest.mark.parametrize(("moments", "which"), [
    ((3.1, 1.0, 2.0), "A <= B \\+ C"),
    ((1.0, 3.1, 2.0), "B <= C \\+ A"),
    ((1.0, 2.0, 3.1), "C <= A \\+ B"),
])
def test_triangle_inequality_violation_rejected(moments, which):
    with pytest.raises(ValueError, match=f"triangle inequality {which}"):
        RigidBody(*moments)


def test_flat_body_is_allowed():
    # Equality in the triangle inequality is a plane lamina: physical.
    body = RigidBody(1.0, 2.0, 3.0)
    assert body.C == 3.0


@pytest.mark.parametrize("mu", [-1e-3, math.nan, math.inf])
def test_bad_mu_rejected(mu):
    with pytest.raises(ValueError, match="mu .*finite and >= 0"):
        RigidBody(1.0, 1.2, 1.5, mu=mu)


def test_zero_r_with_weight_rejected():
    with pytest.raises(ValueError, match=r"r = \(0, 0, 0\) with mu > 0"):
        RigidBody(1.0, 1.2, 1.5, mu=0.5, r=(0.0, 0.0, 0.0))


def test_zero_r_without_weight_is_euler_poinsot():
    body = RigidBody(1.0, 1.2, 1.5, mu=0.0, r=(0.0, 0.0, 0.0))
    assert np.linalg.norm(body.r) == pytest.approx(1.0)


@pytest.mark.parametrize("r", [(1.0, 0.0), (1.0, 0.0, 0.0, 0.0), ((1.0, 0.0, 0.0),),
                               (1.0, math.nan, 0.0), (math.inf, 0.0, 0.0)])
def test_bad_r_rejected(r):
    with pytest.raises(ValueError, match=r"r must be 3 finite numbers"):
        RigidBody(1.0, 1.2, 1.5, mu=0.5, r=r)


@given(st.tuples(*[st.floats(-10, 10, allow_subnormal=False)] * 3)
       .filter(lambda v: np.linalg.norm(v) > 1e-6))
def test_r_is_normalised(r):
    body = RigidBody(1.0, 1.2, 1.5, mu=0.5, r=r)
    assert np.linalg.norm(body.r) == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(body.r, np.asarray(r) / np.linalg.norm(r), atol=1e-15)


def test_body_is_frozen_and_params_order():
    body = RigidBody(2.0, 3.0, 4.0, mu=0.25, r=(0.0, 3.0, 4.0))
    with pytest.raises(AttributeError):
        body.mu = 1.0  # type: ignore[misc]
    assert body.params == pytest.approx((0.5, 1 / 3, 0.25, 0.25, 0.0, 0.6, 0.8))


# --------------------------------------------------------------------------- Hess bodies
@pytest.mark.parametrize("moments", [(2.5, 2.2, 2.0),   # A > B > C
                                     (2.0, 2.5, 2.2),   # B > C > A
                                     (2.2, 2.0, 2.2),   # A = C
                                     (2.5, 2.2, 2.2)])  # C = B
def test_hess_requires_A_gt_C_gt_B(moments):
    with pytest.raises(ValueError, match="A > C > B"):
        RigidBody.hess(*moments)


@pytest.mark.parametrize("branch", [0, 2, -2, 0.5])
def test_hess_branch_must_be_pm1(branch):
    with pytest.raises(ValueError, match=r"branch must be \+1 or -1"):
        RigidBody.hess(2.5, 2.0, 2.2, branch=branch)


@st.composite
def hess_moments(draw):
    """``A > C > B`` with the triangle inequality ``A <= B + C``."""
    B = draw(st.floats(0.1, 10.0))
    C = B * draw(st.floats(1.001, 1.9))
    A = C + (B - 1e-9 * (B + C)) * draw(st.floats(0.001, 0.999))
    return A, B, C


@given(hess_moments(), st.sampled_from([1, -1]), st.floats(0.0, 5.0))
def test_hess_body_satisfies_conditions(moments, branch, mu):
    A, B, C = moments
    body = RigidBody.hess(A, B, C, mu=mu, branch=branch)
    a, b, c = 1 / A, 1 / B, 1 / C
    assert body.is_hess
    assert body.e3 == 0.0
    assert body.mu == mu
    # Eq. (8): (c - b) e1^2 = (a - c) e2^2, and the paper's form of (2).
    assert (c - b) * body.e1**2 == pytest.approx((a - c) * body.e2**2, rel=1e-12)
    assert body.e1 * math.sqrt(A * (C - B)) - branch * body.e2 * math.sqrt(B * (A - C)) \
        == pytest.approx(0.0, abs=1e-12 * math.sqrt(A * B * (A + C)))
    # kappa after Eq. (13).
    assert body.kappa == pytest.approx(a - b, rel=1e-15)
    assert body.kappa == pytest.approx((a - c) / body.e1**2, rel=1e-12)
    # phi0 of Eq. (11).
    assert math.tan(body.phi0) ** 2 == pytest.approx((c - b) / (a - c), rel=1e-12)
    assert (body.e1, body.e2) == pytest.approx((math.cos(body.phi0), math.sin(body.phi0)),
                                               abs=1e-15)
    if branch == 1:
        assert 0.0 < body.phi0 < math.pi / 2
    else:
        assert -math.pi / 2 < body.phi0 < 0.0


def test_paper_body_values():
    body = RigidBody.paper()
    assert body == PAPER_BODY
    assert (body.A, body.B, body.C, body.mu) == (2.5, 2.0, 2.2, 0.01)
    assert body.is_hess
    assert (body.a, body.b, body.c) == pytest.approx((0.4, 0.5, 1 / 2.2), rel=1e-15)
    # tan^2 phi0 = A (C - B) / (B (A - C)) = 2.5 * 0.2 / (2.0 * 0.3) = 5/6.
    assert math.tan(body.phi0) ** 2 == pytest.approx(5 / 6, rel=1e-13)
    assert body.phi0 == pytest.approx(math.atan(math.sqrt(5 / 6)), rel=1e-15)
    assert body.r == pytest.approx((math.sqrt(6 / 11), math.sqrt(5 / 11), 0.0), rel=1e-14)
    assert body.kappa == pytest.approx(-0.1, rel=1e-13)
    assert body.with_mu(0.2).mu == 0.2 and body.with_mu(0.2).r == body.r


@pytest.mark.parametrize("body", [
    RigidBody(2.5, 2.0, 2.2, mu=0.01, r=(1.0, 0.0, 0.0)),       # wrong r
    RigidBody(2.5, 2.0, 2.2, mu=0.01, r=(0.74, 0.67, 0.01)),    # e3 != 0
    RigidBody(2.0, 2.5, 2.2, mu=0.01, r=(0.74, 0.67, 0.0)),     # wrong axis order
])
def test_non_hess_bodies(body):
    assert not body.is_hess


def test_phi0_needs_planar_centre_of_mass():
    with pytest.raises(ValueError, match="e3 = 0"):
        _ = RigidBody(1.3, 1.7, 2.1, mu=0.7, r=(0.3, -0.5, 0.8)).phi0
    assert RigidBody(1.0, 1.0, 1.0, r=(0.0, -2.0, 0.0)).phi0 == pytest.approx(-math.pi / 2)


# --------------------------------------------------------------------------- presets
def test_euler_poinsot_preset():
    body = RigidBody.euler_poinsot(1.0, 2.0, 2.5)
    assert (body.A, body.B, body.C, body.mu) == (1.0, 2.0, 2.5, 0.0)


def test_lagrange_preset():
    body = RigidBody.lagrange(2.0, 1.5, mu=0.3)
    assert (body.A, body.B, body.C, body.mu) == (2.0, 2.0, 1.5, 0.3)
    assert body.r == (0.0, 0.0, 1.0)


def test_kovalevskaya_preset():
    body = RigidBody.kovalevskaya(C=0.7, mu=2.0)
    assert (body.A, body.B, body.C, body.mu) == (1.4, 1.4, 0.7, 2.0)
    assert body.r == (1.0, 0.0, 0.0)


def test_goryachev_chaplygin_preset():
    body = RigidBody.goryachev_chaplygin(C=0.5, mu=3.0)
    assert (body.A, body.B, body.C, body.mu) == (2.0, 2.0, 0.5, 3.0)
    assert body.r == (1.0, 0.0, 0.0)


def test_attrs_are_flat():
    attrs = RigidBody.paper().attrs()
    assert attrs["is_hess"] == 1 and attrs["body_name"] == "paper"
    assert all(isinstance(v, (int, float, str)) for v in attrs.values())


# ---------------------------------------------------------------------- near-Hess bodies
def test_near_hess_turns_the_centre_of_mass_and_states_the_drift_of_the_relation():
    import numpy as np

    from andoyer.kernels.generated.equations import ep_field

    rng = np.random.default_rng(3)
    for eps, e3 in ((0.0, 0.0), (1e-3, 0.0), (-0.05, 0.0), (0.02, 0.1)):
        body = RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.3, epsilon=eps, e3=e3)
        assert abs(np.linalg.norm(body.r) - 1.0) < 1e-15
        assert body.is_hess == (eps == 0.0 and e3 == 0.0)
        a, b, c = body.a, body.b, body.c
        e1, e2, z = body.r
        for _ in range(20):
            y = rng.normal(size=6)
            y[3:] /= np.linalg.norm(y[3:])
            f = np.array(ep_field(*y, *body.params))
            rate = float(np.dot(body.r, f[:3]))          # d(G, r)/dt from Euler's equations
            Gr = e1 * y[0] + e2 * y[1] + z * y[2]
            Gn = (-e2 * y[0] + e1 * y[1]) / np.hypot(e1, e2)
            rho2 = e1 * e1 + e2 * e2
            # The documented law, written for the in-plane part and the e3 lift.
            kH = ((c - b) * e1**2 - (a - c) * e2**2) / rho2
            law = (y[2] * ((a - b) * e1 * e2 / rho2 * (Gr - z * y[2]) + kH * Gn * np.sqrt(rho2))
                   + z * (b - a) * y[0] * y[1])
            assert abs(rate - law) < 1e-12
    # kappa_H vanishes on the Hess direction and grows like 2 sigma epsilon.
    paper = RigidBody.paper()
    for eps in (1e-6, 1e-4):
        kH = RigidBody.near_hess(2.5, 2.0, 2.2, 0.01, eps).hess_defect
        assert abs(kH / (2 * paper.sigma * eps) - 1) < 50 * eps
