"""The Lie-Deprit triangle (D1)-(D4) on model problems with known answers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from andoyer.analysis.resonance.deprit import JetSpace, lie_deprit, transform

J_STAR = 1.3


def _cos(space, k, amp, degree=0):
    f = space.zeros()
    f[degree, k, 0] = f[degree, -k, 0] = amp / 2
    return f


def _pendulum_energy(J, mu):
    """The rotating pendulum H = J^2/2 + mu cos(phi): energy of the orbit of action J."""
    def action(E):
        return quad(lambda f: math.sqrt(2 * (E - mu * math.cos(f))), 0, 2 * math.pi,
                    epsabs=1e-15, epsrel=1e-15, limit=200)[0] / (2 * math.pi)
    return brentq(lambda E: action(E) - J, J * J / 2 - 2 * mu, J * J / 2 + 2 * mu,
                  xtol=1e-16, rtol=1e-15)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("order, slope", [(2, 4), (4, 6)])
def test_pendulum_energy_to_order_N(order, slope):
    """H = J^2/2 + mu cos(phi) normalised away from resonance: the energy of the torus J
    is J^2/2 + mu^2/(4 J^2) + ... ; against the action integral inverted by quadrature,
    the error of order N falls like mu^(N+2) (odd orders vanish), measured slope within
    0.2 of it."""
    space = JetSpace(8, 16, 1)
    Ht, _W = lie_deprit(space, [_cos(space, 1, 1.0)] + [space.zeros()] * (order - 1),
                        [J_STAR, 1.0], (0, 1))
    assert Ht[1][0, 0, 0].real / 2 == pytest.approx(1 / (4 * J_STAR**2), rel=1e-13)
    mus = np.array([0.01, 0.02, 0.04])
    err = []
    for mu in mus:
        E = J_STAR**2 / 2 + sum(mu**n / math.factorial(n) * Ht[n - 1][0, 0, 0].real
                                for n in range(1, order + 1))
        err.append(abs(E - _pendulum_energy(J_STAR, mu)))
    assert abs(np.polyfit(np.log(mus), np.log(err), 1)[0] - slope) < 0.2, err


@pytest.mark.parametrize("order", [1, 2, 3])
def test_old_variables_from_new_compose_to_the_normal_form(order):
    """(D4): K(J(new), phi(new)) = Kt(new) + O(mu^(N+1)) for K = J^2/2 + mu (cos phi +
    0.4 cos 2 phi + 0.3 x cos phi), x = J - J*, at a point off J*: measured slope N + 1
    within 0.1."""
    space = JetSpace(8, 32, 1)
    H1 = _cos(space, 1, 1.0) + _cos(space, 2, 0.4) + _cos(space, 1, 0.3, degree=1)
    Ht, Ws = lie_deprit(space, [H1] + [space.zeros()] * (order - 1), [J_STAR, 1.0], (0, 1))
    x_jet = space.zeros()
    x_jet[1, 0, 0] = 1.0
    X, P = transform(space, x_jet, Ws), transform(space, None, Ws)
    x, ph = 0.01, 0.7
    mus = np.array([1e-3, 2e-3, 4e-3])
    err = []
    for mu in mus:
        def series(parts, mu=mu):
            return sum(mu**n / math.factorial(n) * space.evaluate(parts[n], x, ph, 0.0).real
                       for n in range(1, order + 1))
        xo, po = x + series(X), ph + series(P)
        old = (J_STAR + xo) ** 2 / 2 + mu * (math.cos(po) + 0.4 * math.cos(2 * po)
                                             + 0.3 * xo * math.cos(po))
        new = (J_STAR + x) ** 2 / 2 + sum(mu**n / math.factorial(n)
                                          * space.evaluate(Ht[n - 1], x, ph, 0.0).real
                                          for n in range(1, order + 1))
        err.append(abs(old - new))
    assert abs(np.polyfit(np.log(mus), np.log(err), 1)[0] - (order + 1)) < 0.1, err


def test_resonant_harmonic_is_kept_and_the_rest_removed():
    """(D3): with a forcing in t, H1 = cos(phi - t) + cos(phi) at omega* = 1 (p = q = 1):
    the resonant harmonic stays in Ht_1, the non-resonant one goes into W_1 with the
    divisor i (k1 omega* + k2)."""
    space = JetSpace(3, 16, 8)
    H1 = space.zeros()
    H1[0, 1, -1] = H1[0, -1, 1] = 0.5
    H1[0, 1, 0] = H1[0, -1, 0] = 0.5
    Ht, Ws = lie_deprit(space, [H1], [1.0, 1.0], (1, 1))
    assert Ht[0][0, 1, -1] == pytest.approx(0.5) and abs(Ht[0][0, 1, 0]) < 1e-15
    assert Ws[0][0, 1, 0] == pytest.approx(0.5 / 1j)
    assert abs(Ws[0][0, 1, -1]) == 0.0
