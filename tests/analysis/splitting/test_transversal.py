"""Stage 3: transversal splitting at finite mu, proved (validated local manifold, Lohner
transport of a piece of it, sign change on Fix R, slope of the tangent)."""

from __future__ import annotations

import json

import pytest
from flint import arb, arb_mat

from andoyer.analysis.splitting import transversal as tr
from andoyer.analysis.splitting.certificate import (
    _digest,
    prove_transversal_certificate,
    verify_certificate,
)
from andoyer.errors import CertificateError
from andoyer.integrate.validated.arithmetic import BodySpec, working_precision

#: The near-Hess body of the theorem: (2.5, 1.0, 1.6) turned by 0.1, mu = 0.05.
SPEC = BodySpec("2.5", "1.0", "1.6", 1, "0.1", "0.05")
#: A frame near the eigenvectors of DF(p) (any invertible frame serves the fast tests).
FRAME = ((0.6029, -0.5949), (0.7978, 0.8038))


def test_reversor_holds_exactly_and_a_wrong_one_does_not(monkeypatch):
    assert tr.reversor_holds()
    monkeypatch.setattr(tr, "E3_ZERO_REVERSAL", (1, 1, -1, 1, 1, 1))
    assert not tr.reversor_holds()


def test_chart_lies_on_the_levels():
    with working_precision(128):
        st = tr._setting(SPEC, "1", 128, 1)
        x = tr._chart(st, (arb("0.001"), arb("-0.002")))
        G1, G2, G3, g1, g2, g3 = x
        H = (st.a * G1**2 + st.b * G2**2 + st.c * G3**2) / 2 + st.mu * st.e1 * g1
        assert (H - st.h).contains(0) and abs(H - st.h) < 1e-35
        assert abs(G1 * g1 + G2 * g2 + G3 * g3) < 1e-35
        assert abs(g1**2 + g2**2 + g3**2 - 1) < 1e-35
        # the chart's derivative is the kernel of the constraints
        D = tr._chart_derivative(st, x)
        h = arb("1e-20")
        xp = tr._chart(st, (arb("0.001") + h, arb("-0.002")))
        for i in range(6):
            assert abs((xp[i] - x[i]) / h - D[i, 0]) < 1e-15


def _inside(x0, frame, coords, point):
    """Whether ``point`` is in ``x0 + Q r`` (solve for r, compare with the balls)."""
    Q = arb_mat([[arb(v) for v in row] for row in frame])
    d = arb_mat([[point[i] - x0[i]] for i in range(6)])
    r = Q.solve(d)
    return all(coords[i].overlaps(r[i, 0]) for i in range(6))


def test_piece_holds_the_graph_region():
    """The Lohner set of a piece holds chi(E (u, v)) on the corners of
    [u_a, u_b] x [-kappa u_b, kappa u_b]: fails if the chart's curvature remainder
    ((chi'(hull) - mid) W) is dropped."""
    kappa = 1e-3
    u_a, u_b = 2.0e-4, 2.6e-4
    with working_precision(128):
        st = tr._setting(SPEC, "1", 128, 1)
        E = tr._mat(FRAME)
        x0, frame, coords, _ = tr._piece(st, E, 1, kappa, u_a, u_b)
        for u in (u_a, u_b, 0.5 * (u_a + u_b)):
            for v in (-kappa * u_b, kappa * u_b, 0.0):
                q = (E[0, 0] * arb(u) + E[0, 1] * arb(v), E[1, 0] * arb(u) + E[1, 1] * arb(v))
                assert _inside(x0, frame, coords, tr._chart(st, q)), (u, v)


def test_cone_condition_accepts_a_hyperbolic_block_and_refuses_a_sheared_one():
    with working_precision(64):
        good = arb_mat([[arb(18, 0.01), arb(0, 0.01)], [arb(0, 0.01), arb(0.05, 0.01)]])
        holds, kappa, m = tr._cone(good, 1e-5, None)
        assert holds and 0 < kappa < 0.01 and m > 17
        # a cone too narrow for the shear is refused
        assert not tr._cone(good, 1e-5, 1e-5)[0]
        sheared = arb_mat([[arb(1.2), arb(0)], [arb(5), arb(1.1)]])
        assert not tr._cone(sheared, 1e-5, None)[0]


def test_saddle_test_reads_trace_and_determinant():
    with working_precision(64):
        lam, ok = tr._saddle(arb_mat([[arb(18), arb(1)], [arb(0), arb(1) / 18]]))
        assert ok and lam.contains(18)
        assert not tr._saddle(arb_mat([[arb(2), arb(0)], [arb(0), arb(1.5)]]))[1]
        assert not tr._saddle(arb_mat([[arb(0), arb(-1)], [arb(1), arb(0)]]))[1]


def test_local_manifold_cone_on_a_small_box():
    lm = tr.local_unstable_manifold(SPEC, radius=1e-6, order=20)
    assert lm.holds and lm.kappa < 1e-4
    lam = arb(lm.multiplier)
    assert 18 < lam < 19 and arb(lm.expansion) > 1


def test_arguments_are_refused_by_name():
    with pytest.raises(ValueError, match="rotation"):
        tr.local_unstable_manifold(SPEC, rotation=0)
    with pytest.raises(ValueError, match="radius"):
        tr.local_unstable_manifold(SPEC, radius=0.5)
    with pytest.raises(ValueError, match="mu"):
        tr.local_unstable_manifold(SPEC.with_mu("0"))
    with pytest.raises(ValueError, match="side"):
        tr.prove_transversal(SPEC, side=2)
    with pytest.raises(ValueError, match="half_width"):
        tr.prove_transversal(SPEC, half_width=0.1)
    for piece in ({}, {0: 1e-6, 1: 2e-6}, (1e-6, 2e-6, 3e-6), (1e-6,), "ab", (1e-6, "x"),
                  (1e-6, float("nan")), [[1e-6, 2e-6]]):
        with pytest.raises(ValueError, match="piece must be two finite numbers"):
            tr.prove_transversal(SPEC, piece=piece)


def _fake(**changes):
    cert = {"format": "andoyer-certificate", "version": 1,
            "kind": "heteroclinic-transversality", "statement": "x"}
    cert.update(changes)
    cert["digest"] = _digest(cert)
    return cert


def test_bad_transversal_certificates_get_one_line_errors():
    with pytest.raises(CertificateError, match="lacks the field"):
        verify_certificate(_fake())
    full = {k: {} for k in ("body", "mu_interval", "level", "local_manifold", "piece",
                            "boxes")}
    cert = _fake(**full, precision_bits=128, order=24, run_seconds=1.0,
                 libraries={"python-flint": "0.0.1"})
    with pytest.raises(CertificateError, match="python-flint 0.0.1"):
        verify_certificate(cert)


@pytest.fixture(scope="module")
def certificate():
    return prove_transversal_certificate(SPEC)


@pytest.mark.slow
def test_theorem_closes_and_holds_the_measured_angle(certificate):
    """The Hess line theta1 = 0 of the turned body at mu = 0.05: the measured angle of
    separatrix_splitting lies inside the proved enclosure."""
    from andoyer import RigidBody
    from andoyer.analysis.splitting.measure import separatrix_splitting

    angle = arb(certificate["boxes"]["angle"])
    assert angle < 0 and angle.rad() < 1e-4
    body = RigidBody.near_hess(2.5, 1.0, 1.6, mu=0.05, epsilon=0.1)
    out = separatrix_splitting(body, [0.05], branch="theta1=0", sheet=-1, n_phase=16,
                               delta=1e-5)
    measured = out["intersections"].angle.values[0]
    assert any(abs(m - float(angle.mid())) < float(angle.rad()) for m in measured)
    assert verify_certificate(certificate)["angle"] == certificate["boxes"]["angle"]


def _altered(cert, path, value):
    new = json.loads(json.dumps(cert))
    node = new
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value(node[path[-1]])
    new["digest"] = _digest(new)
    return new


@pytest.mark.slow
@pytest.mark.parametrize("path, change", [
    (("boxes", "point_box"), lambda b: [b[0].replace("[0.8", "[0.7", 1)] + b[1:]),
    (("boxes", "ends_gamma3"), lambda b: [b[1], b[0]]),
    (("boxes", "angle"), lambda a: a.replace("+/-", "+/- 1") if "+/-" in a else a + "1"),
    (("piece", "u"), lambda u: [u[0], u[0] * (1 + 1e-15)]),
    (("local_manifold", "kappa"), lambda k: k * 1e-3),
    (("body", "epsilon"), lambda e: "0.11"),
])
def test_an_altered_box_or_parameter_is_rejected(certificate, path, change):
    with pytest.raises(CertificateError):
        verify_certificate(_altered(certificate, path, change))


def test_tampered_digest_is_rejected_fast():
    from andoyer.integrate.validated.arithmetic import FLINT_VERSION

    full = {k: {} for k in ("body", "mu_interval", "level", "local_manifold", "piece",
                            "boxes")}
    cert = _fake(**full, precision_bits=128, order=24, run_seconds=1.0,
                 libraries={"python-flint": FLINT_VERSION})
    cert["statement"] = "changed"
    with pytest.raises(CertificateError, match="altered"):
        verify_certificate(cert)


def test_failure_message_names_the_widths():
    from andoyer.analysis.splitting.certificate import _failure

    w = {"end_gamma3_a_mid": 1e-9, "end_gamma3_a": 1e-8, "end_gamma3_b_mid": 2e-9,
         "end_gamma3_b": 1e-8, "tangent_gamma3_mid": 1.0, "tangent_gamma3": 2.0,
         "slope_mid": 1e-3, "slope": 1e-2, "piece_image": 1e-5}
    text = _failure(w)
    assert "opposite signs" in text and "1e-05" in text


@pytest.mark.slow
def test_paper_body_line_4phi0_closes_and_its_hess_line_does_not():
    """The paper's body at mu = 0.01 (4 min per rotation): W^u(P-) crosses W^s(P+) at the
    measured angle -9.905e-7 (separatrix_splitting, theta1 = 4 phi0); on the Hess line
    (W^u(P+), the invariant Hess surface) the slope's ball holds 0."""
    spec = BodySpec("2.5", "2.0", "2.2", 1, "0", "0.01")
    split = tr.prove_transversal(spec, rotation=-1, half_width=1e-11, t_max=400.0)
    assert split.proved
    angle = arb(split.angle)
    assert angle.rad() < 1e-8 and abs(float(angle.mid()) + 9.905e-7) < 1e-9
    hess = tr.prove_transversal(spec, rotation=1, half_width=1e-11, t_max=400.0)
    assert not hess.proved and arb(hess.slope).contains(0)


def test_mu_interval_is_exact_decimals_and_refuses_a_wide_radius():
    assert tr.mu_interval({"mu": "0.05", "mu_radius": "5e-8"}) == ("0.04999995", "0.05000005")
    assert tr.mu_interval({"mu": "0.05"}) == ("0.05", "0.05")
    spec = tr._spec(SPEC, "1e-9")
    with working_precision(128):
        mu = spec.balls(128).mu
        assert mu.contains(arb("0.050000001")) and mu.contains(arb("0.049999999"))
        assert not mu.contains(arb("0.050000002"))
    with pytest.raises(ValueError, match="mu_radius"):
        tr._spec(SPEC, "0.03")


@pytest.mark.slow
def test_theorem_for_a_mu_interval():
    """Every mu in [0.05 - 5e-8, 0.05 + 5e-8] at once: the ends' gamma3 widen by the mu
    ball (~1e3 mu_radius), so the piece is 1e5 times longer than at one mu."""
    proof = tr.prove_transversal(SPEC, mu_radius="5e-8", half_width=1e-4)
    assert proof.proved and "every mu in [0.04999995, 0.05000005]" in proof.statement
    assert arb(proof.angle).contains(arb("-0.0037482582"))
