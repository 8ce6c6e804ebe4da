r"""The island chain to second and third order in ``mu``: the Lie-Deprit normal form of (R2).

(S1) The reduced Hamiltonian of the section map (R2): solving ``H0(I1, G) + mu V = h`` for
     ``G = G0(I1) + mu G1 + mu^2 G2 + mu^3 G3``,
     ``K = -G = K0(I1) + mu K1 + mu^2 K2 + mu^3 K3``, ``K1 = V / omega_g``,
     ``K2 = -(V V_G / omega_g^2 - (d omega_g/dG) V^2 / (2 omega_g^3))``, the derivatives in
     ``G`` at fixed ``I1`` (``d/dG|_I = d/dG|_h + omega_g d/dh|_G``, from tori off the level).
(S1') ``K3 = -G3``,
     ``G3 = -(H0_GG G1 G2 + H0_GGG G1^3 / 6 + V_G G2 + V_GG G1^2 / 2) / omega_g``
     (``d/dG`` at fixed ``I1`` as in (S1), ``H0_G = omega_g``; a second
     derivative ``f_GG|_I = f_GG + 2 omega_g f_Gh + omega_g^2 f_hh + H0_GG f_h`` from a
     3 x 3 stencil of tori in ``(h, G)``).
(S2) The jets of (D1) about the resonant torus ``I1*``: seven tori on the level at
     ``G* + j d`` (``j = -3 .. 3``), their actions ``x_j = I1 - I1* = -int dG / W``
     (Gauss-Legendre on :func:`~andoyer.analysis.resonance.predict.free_top_at_gap`),
     every Fourier coefficient of ``K1``, ``K2``, ``K3`` and ``G0`` interpolated in ``x``;
     ``omega(x) = W`` likewise, with ``omega_0 = p/q``.
(S3) The resonant normal form to order ``N`` (1 to 3) by Deprit's triangle
     (:func:`~andoyer.analysis.resonance.deprit.lie_deprit`), resonance
     ``k1 p + k2 q = 0`` (``t = phi2``).
(S4) The centre of the island on a line of the section: at the new angles of a point,
     the action where ``dKt/dJ = p/q`` (the innermost level curve of the slow Hamiltonian
     touches the line there), mapped back to the old ``(I1, phi1)`` by (D4), then
     ``G = -K`` and the plane point's free-top label ``G_label = sqrt(G^2 + 2 mu V/s(l))``
     (exact: ``H0(l, L, G_label) = h``, ``s = a sin^2 l + b cos^2 l``), with ``(l, L)``
     and ``V`` on the free-top torus ``(h - mu V, G)`` through the state (fixed point).
     The half-width: where the separatrix (the slow Hamiltonian's level at the unstable
     equilibrium) crosses the same line; the libration frequency from the slow
     Hamiltonian's Hessian at the stable equilibrium (the jets' exact derivatives).

Errors, for ``p = 1`` (``x ~ mu^(1/2)`` across the island): the position errs by
``O(mu^(N+1))``. ``V`` holds ``k2 = +-1`` only, so a product of ``n`` of its harmonics
has ``k2`` of the parity of ``n``: the resonant harmonic ``(q, -1)`` enters the normal
form at the odd orders only, and order 2 brings the twist's ``O(mu^2)`` part. The
relative error of the half-width (and of the libration frequency) is ``O(mu)`` for the
pendulum (R6), ``O(mu^2)`` at orders 1 and 2 (the jets hold the ``O(mu)`` corrections;
the ``mu^3`` harmonic is missing) and ``O(mu^3)`` at order 3 (the jets' degree
:data:`DEGREE`). For ``p = 2`` the resonant harmonic enters at order 2.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from andoyer.analysis.resonance.deprit import JetSpace, lie_deprit, transform
from andoyer.analysis.resonance.predict import ResonantChain, free_top_at_gap
from andoyer.analysis.resonance.torus import (
    fourier_coefficients,
    perturbation,
    sample_torus,
)
from andoyer.charts.andoyer_deprit import from_andoyer

__all__ = ["SecondOrderChain", "island_prediction"]

#: Degree of the jets in ``x``: the half-width to ``O(mu^2)`` needs ``K0`` through ``x^6``
#: (``omega`` through ``x^5``: ``x^6 ~ mu^3`` against the island's ``mu``); at degree 4 the
#: second-order half-width of Hess(3, 1, 2)'s 3:1 chain errs 10x more at mu = 2e-4.
DEGREE = 5
#: Half the number of tori of the interpolation in ``x`` (S2).
_HALF = 3
#: Their spacing, as a fraction of the distance to the nearer end of the regime.
_SPACING = 0.03


def _at(body: Any, h: float, G: float, M: float, sign: int, n: int, n2: int
        ) -> tuple[Any, NDArray[np.complex128]]:
    t = sample_torus(body, h, G, M, sign, n)
    return t, fourier_coefficients(body, t, n2)


#: Step of the second derivatives of (S1') in ``h`` and ``G`` (relative), and twice it:
#: the two 3 x 3 stencils are combined by Richardson's extrapolation (the paper's 7:1
#: chain's harmonics vary fast with the torus: one stencil at 1e-4 erred 5e-4 in the
#: order-3 half-width at mu = 0.01; extrapolated, steps 1e-4 and 5e-5 agree to 4e-6).
_STEP2 = 1e-4


def _third(body: Any, h: float, G: float, M: float, sign: int, n1: int, n2: int,
           v: NDArray[np.float64], v1: NDArray[np.float64], w: float, w1: float
           ) -> NDArray[np.float64]:
    """(S1'): ``G3`` on the ``(phi1, phi2)`` grid from ``V``, ``V' = V_G``, ``omega_g``
    and ``omega_g' = H0_GG`` (derivatives at fixed ``I1``), with the second derivatives
    ``f'' = f_GG + 2 omega_g f_Gh + omega_g^2 f_hh + omega_g' f_h`` from 3 x 3 stencils
    of tori in ``(h, G)`` at two steps, extrapolated (Richardson)."""
    grid = n1 * n2
    vals: dict[tuple[int, int], tuple[NDArray[np.float64], float]] = {}
    for i in (-2, -1, 0, 1, 2):
        for j in (-2, -1, 0, 1, 2):
            if abs(i) == abs(j) or 0 in (i, j):     # the two 3 x 3 stencils
                t, V = _at(body, h + i * _STEP2 * h, G + j * _STEP2 * G, M, sign, n1, n2)
                vals[(i, j)] = ((np.fft.ifft2(V) * grid).real, t.omega_g)

    def second(k: int, m: int) -> Any:
        f = {key: val[k] for key, val in vals.items()}
        dh, dG = m * _STEP2 * h, m * _STEP2 * G
        f_h = (f[(m, 0)] - f[(-m, 0)]) / (2 * dh)
        f_hh = (f[(m, 0)] - 2 * f[(0, 0)] + f[(-m, 0)]) / dh**2
        f_GG = (f[(0, m)] - 2 * f[(0, 0)] + f[(0, -m)]) / dG**2
        f_Gh = (f[(m, m)] - f[(m, -m)] - f[(-m, m)] + f[(-m, -m)]) / (4 * dh * dG)
        return f_GG + 2 * w * f_Gh + w * w * f_hh + w1 * f_h

    v2 = (4.0 * second(0, 1) - second(0, 2)) / 3.0
    w2 = float((4.0 * second(1, 1) - second(1, 2)) / 3.0)
    g1 = -v / w
    g2 = -(0.5 * w1 * g1**2 + v1 * g1) / w
    return np.asarray(-(w1 * g1 * g2 + w2 * g1**3 / 6.0 + v1 * g2 + 0.5 * v2 * g1**2) / w)


class SecondOrderChain:
    """(S1)-(S4) for one chain of :class:`~andoyer.analysis.resonance.predict.ResonantChain`.

    Parameters
    ----------
    chain : ResonantChain
        The first-order chain (its torus, ``p``, ``q``, the level).
    order : int
        Order in ``mu`` of the normal form (1 to 4; ``K4`` is taken as zero, so order 4
        only estimates the size of the fourth-order terms).
    like : SecondOrderChain, optional
        A chain of the same ``ResonantChain`` whose reduced Hamiltonian (S1)-(S2) is
        reused (it took it to at least ``min(order, 3)``).
    """

    space: JetSpace
    built: int
    x_nodes: NDArray[np.float64]
    omega: list[float]
    G_poly: NDArray[np.float64]
    K1: NDArray[np.complex128]
    K2: NDArray[np.complex128]
    K: list[NDArray[np.complex128]]

    def __init__(self, chain: ResonantChain, order: int = 2, *,
                 like: SecondOrderChain | None = None) -> None:
        self.chain, self.order = chain, int(order)
        p, q = chain.p, chain.q
        if like is not None and like.chain is chain and like.built >= min(self.order, 3):
            self.space, self.x_nodes, self.omega, self.G_poly = (
                like.space, like.x_nodes, like.omega, like.G_poly)
            self.built, self.K1, self.K2 = like.built, like.K1, like.K2
            self.K = (like.K + [self.space.zeros()] * self.order)[: self.order]
        else:
            self._reduce(chain, min(self.order, 3))
            self.K = (self.K + [self.space.zeros()] * self.order)[: self.order]
        H = [math.factorial(n + 1) * k for n, k in enumerate(self.K)]
        self.Ht, self.Ws = lie_deprit(self.space, H, self.omega, (p, q))
        xj = self.space.zeros()
        xj[1, 0, 0] = 1.0
        self.dHt = [self.space.d_x(f) for f in self.Ht]
        self.pHt = [self.space.d_phi(f) for f in self.Ht]
        self.X = transform(self.space, xj, self.Ws)
        self.P = transform(self.space, None, self.Ws)
        # X's and P's jets of orders 1 .. order stacked, (X, P) x order: the Fourier sums
        # of all at a point in one pass (JetSpace.rows), the same numbers as one by one
        self._XP = np.stack([np.stack(self.X[1:self.order + 1]),
                             np.stack(self.P[1:self.order + 1])])

    def _reduce(self, chain: ResonantChain, order: int) -> None:
        """(S1)-(S2): the jets of ``K_1 .. K_order`` and of ``omega`` about ``I1*``."""
        body, h, M, T = chain.body, chain.h, chain.M, chain.torus
        p, q, G0 = chain.p, chain.q, T.G
        self.built = max(order, 2)
        n1, n2 = T.phi1.size, 8
        self.space = JetSpace(DEGREE, n1, n2)
        row = chain.row
        d = _SPACING * min(G0 - row["lo"], row["hi"] - G0)
        Gs = G0 + d * np.arange(-_HALF, _HALF + 1)
        e0 = row["gap"]
        qc = sorted((body.a, body.b, body.c))[1]

        def W_of(G: float) -> float:
            return free_top_at_gap(body, h, e0 + qc * (G - G0) * (G + G0) / (2 * h)
                                   ).rotation_number

        nodes, weights = np.polynomial.legendre.leggauss(12)
        xs = []
        for G in Gs:   # x = -int_{G0}^{G} dG / W
            mid, half = 0.5 * (G + G0), 0.5 * (G - G0)
            xs.append(-half * sum(w / W_of(mid + half * z)
                                  for z, w in zip(nodes, weights, strict=True)))
        self.x_nodes = x = np.array(xs)
        K1s, K2s, K3s, Ws = [], [], [], []
        dh, dG = 1e-5 * h, 1e-5 * G0
        for G in Gs:
            t, V = _at(body, h, G, M, T.sign, n1, n2)
            tp, vp = _at(body, h + dh, G, M, T.sign, n1, n2)
            tm, vm = _at(body, h - dh, G, M, T.sign, n1, n2)
            gp, wp = _at(body, h, G + dG, M, T.sign, n1, n2)
            gm, wm = _at(body, h, G - dG, M, T.sign, n1, n2)
            wg = t.omega_g
            V_G = (wp - wm) / (2 * dG) + wg * (vp - vm) / (2 * dh)          # (S1)
            H0_GG = ((gp.omega_g - gm.omega_g) / (2 * dG)
                     + wg * (tp.omega_g - tm.omega_g) / (2 * dh))
            grid = n1 * n2
            v = np.fft.ifft2(V) * grid
            vg = np.fft.ifft2(V_G) * grid
            G2 = (v * vg).real / wg**2 - H0_GG * (v.real ** 2) / (2 * wg**3)
            K1s.append(V / wg)
            K2s.append(np.fft.fft2(-G2) / grid)
            if order >= 3:
                K3s.append(np.fft.fft2(-_third(body, h, G, M, T.sign, n1, n2, v.real,
                                               vg.real, wg, H0_GG)) / grid)
            Ws.append(W_of(G))
        vander = np.vander(x, 2 * _HALF + 1, increasing=True)
        inv = np.linalg.inv(vander)

        def jet(values: list[NDArray[np.complex128]]) -> NDArray[np.complex128]:
            c = np.tensordot(inv, np.array(values), axes=(1, 0))
            return np.asarray(c[: DEGREE + 1])

        self.K1, self.K2 = jet(K1s), jet(K2s)
        #: ``K_1 .. K_built`` (S1), (S1'); beyond, zero (the triangle's own terms of that
        #: order then estimate the next order's size)
        self.K = [self.K1, self.K2] + ([jet(K3s)] if K3s else [])
        self.omega = list(np.real(inv @ np.array(Ws))[: DEGREE + 1])
        self.omega[0] = p / q
        self.G_poly = inv @ Gs                    # G0(I1* + x)

    # ------------------------------------------------------------------ series
    def _series(self, which: int, x: float, phi: float, t: float) -> float:
        """The change (D4) at new ``(x, phi, t)``: ``x_old - x`` (``which`` 0) or
        ``phi - phi_old`` (1)."""
        return self._sum(self.space.rows(self._XP[which], phi, t), x)

    def _series_both(self, x: float, phi: float, t: float) -> tuple[float, float]:
        """:meth:`_series` 0 and 1 at once."""
        rows = self.space.rows(self._XP, phi, t)
        return self._sum(rows[0], x), self._sum(rows[1], x)

    def _sum(self, rows: NDArray[np.complex128], x: float) -> float:
        """``sum_n mu^n / n! f_n`` at ``x`` of the Fourier sums ``rows[n - 1]`` of ``f_n``."""
        mu, sp = self.chain.body.mu, self.space
        return sum(mu**n / math.factorial(n) * sp.at(rows[n - 1], x).real
                   for n in range(1, self.order + 1))

    def _dKt_rows(self, phi: float, t: float) -> list[NDArray[np.complex128]]:
        """:meth:`JetSpace.rows` of the jets of :meth:`_dKt` at ``(phi, t)``."""
        return [self.space.rows(self.dHt[n - 1], phi, t) for n in range(1, self.order + 1)]

    def _dKt(self, x: float, phi: float, t: float,
             rows: list[NDArray[np.complex128]] | None = None) -> float:
        """``dKt/dJ`` of the normal form at new ``(x, phi, t)`` (``rows``:
        :meth:`_dKt_rows` at ``(phi, t)``, for several ``x`` there)."""
        mu, sp = self.chain.body.mu, self.space
        rows = self._dKt_rows(phi, t) if rows is None else rows
        w = sum(c * x**j for j, c in enumerate(self.omega))
        return w + sum(mu**n / math.factorial(n) * sp.at(rows[n - 1], x).real
                       for n in range(1, self.order + 1))

    def centre(self, phi_old: float, t: float) -> tuple[float, float]:
        """(S4): the old ``(x, G)`` of the island's centre at old phase ``phi_old`` and
        time ``t = phi2``."""
        c = self.chain
        target = c.p / c.q
        x_new, phi_new = 0.0, phi_old
        for _ in range(30):
            # Newton in x on dKt/dJ = p/q (numerical derivative), then the new phase
            rows = self._dKt_rows(phi_new, t)
            f = self._dKt(x_new, phi_new, t, rows) - target
            h = 1e-6 * (abs(x_new) + 1e-6)
            df = (self._dKt(x_new + h, phi_new, t, rows)
                  - self._dKt(x_new - h, phi_new, t, rows)) / (2 * h)
            x_step = f / df
            x_new -= x_step
            phi_next = phi_old - self._series(1, x_new, phi_new, t)
            done = abs(x_step) < 1e-15 and abs(phi_next - phi_new) < 1e-14
            phi_new = phi_next
            if done:
                break
        x_old = x_new + self._series(0, x_new, phi_new, t)
        mu, sp = c.body.mu, self.space
        G0 = float(sum(g * x_old**j for j, g in enumerate(self.G_poly)))
        G = G0 - sum(mu**n * sp.evaluate(k, x_old, phi_old, t).real
                     for n, k in enumerate(self.K, 1))
        return x_old, G

    def label(self, phi_old: float, g_star: float) -> float:
        """(S4): ``G_label - G*`` of the island's centre where the section ``g = g*`` meets
        the old phase ``phi_old``."""
        c = self.chain
        body, h, M, T = c.body, c.h, c.M, c.torus
        t = g_star - float(np.interp(phi_old, np.append(T.phi1, 2 * math.pi),
                                     np.append(T.rho, T.rho[0])))
        hp = h
        for _ in range(6):
            x_old, G = self.centre(phi_old, t)
            tor = sample_torus(body, hp, G, M, T.sign, T.phi1.size)
            from andoyer.analysis.resonance.predict import trig_interpolate

            l = float(trig_interpolate(tor, np.unwrap(tor.l), np.array([phi_old]))[0])
            L = float(trig_interpolate(tor, tor.L, np.array([phi_old]))[0])
            rho = float(trig_interpolate(tor, tor.rho, np.array([phi_old]))[0])
            t = g_star - rho
            state = from_andoyer([l, g_star, L, G, M])
            V = float(perturbation(body, state))
            hp = h - body.mu * V
        s = body.a * math.sin(l) ** 2 + body.b * math.cos(l) ** 2
        return math.sqrt(G * G + 2 * body.mu * V / s) - T.G

    def _to_new(self, G: float, phi_old: float, t: float) -> tuple[float, float]:
        """New ``(x, phi)`` of the old state ``(G, phi1, phi2)``: ``x_old`` from
        ``G = G0(x) - mu K1 - mu^2 K2`` (Newton), then (D4) inverted by iteration."""
        mu, sp = self.chain.body.mu, self.space

        rows = [sp.rows(k, phi_old, t) for k in self.K]

        def G_of(x: float) -> float:
            out = float(sum(g * x**j for j, g in enumerate(self.G_poly)))
            return out - sum(mu**n * sp.at(r, x).real for n, r in enumerate(rows, 1))

        x = 0.0
        for _ in range(40):
            hstep = 1e-7
            d = (G_of(x + hstep) - G_of(x - hstep)) / (2 * hstep)
            step = (G_of(x) - G) / d
            x -= step
            if abs(step) < 1e-16:
                break
        x_new, phi_new = x, phi_old
        for _ in range(40):
            dx, dphi = self._series_both(x_new, phi_new, t)
            x_next = x - dx
            phi_next = phi_old - dphi
            done = abs(x_next - x_new) < 1e-16 and abs(phi_next - phi_new) < 1e-15
            x_new, phi_new = x_next, phi_next
            if done:
                break
        return x_new, phi_new

    def _line(self, phase: float, g_star: float) -> Any:
        """``s -> (x, phi, t)`` in the new variables of the seed line's state at ``s``."""
        from andoyer.analysis.resonance.predict import trig_interpolate
        from andoyer.analysis.resonance.torus import free_top_phase
        from andoyer.integrate.fill import section_roots

        c = self.chain
        body, h, M, T = c.body, c.h, c.M, c.torus
        mom0 = c.states(np.array([phase]))
        l0, L0 = float(np.arctan2(mom0[0, 0], mom0[0, 1])), float(mom0[0, 2])
        dl, dL = (float(v[0]) for v in c.normal(mom0))

        def new(s: float) -> tuple[float, float, float]:
            l, L = l0 + s * dl, L0 + s * dL
            roots = section_roots(body, h, M, ("g", g_star), [l], [L])[0]
            G = float(roots[np.argmin(np.abs(roots - (T.G + s)))])
            mom = from_andoyer([l, g_star, L, G, M])[:3]
            phi = float(free_top_phase(body, mom)[0]) % (2 * math.pi)
            h_free = 0.5 * (body.a * mom[0] ** 2 + body.b * mom[1] ** 2 + body.c * mom[2] ** 2)
            tor = sample_torus(body, h_free, G, M, T.sign, T.phi1.size)
            t = g_star - float(trig_interpolate(tor, tor.rho, np.array([phi]))[0])
            x, ph = self._to_new(G, phi, t)
            return x, ph, t

        return new

    def stable_s(self, phase: float, g_star: float) -> float:
        """(S4) on the seed line of :func:`~andoyer.analysis.resonance.measure.measure_island`:
        the ``s`` (``G`` units along the normal through the torus point of phase ``phase``)
        where the slow Hamiltonian ``Kt - (p/q) J`` is extremal along the line (the
        innermost level curve touches it: the orbit of least libration), by secant steps
        on its derivative in ``s``."""
        c = self.chain
        mu, sp, p, q = c.body.mu, self.space, c.p, c.q
        new = self._line(phase, g_star)

        def slope(s: float) -> float:
            ds = 1e-3 * (c.dG if math.isfinite(c.dG) else 1e-6)
            a, b = new(s - ds), new(s + ds)
            x, ph, t = new(s)
            dx, dpsi = (b[0] - a[0]) / (2 * ds), (q * (b[1] - a[1]) - p * (b[2] - a[2])) / (2 * ds)
            Kx = self._dKt(x, ph, t) - p / q
            Kphi = sum(mu**n / math.factorial(n)
                       * sp.evaluate(self.pHt[n - 1], x, ph, t).real
                       for n in range(1, self.order + 1))
            return Kx * dx + Kphi / q * dpsi

        s0 = float(c.stable_shift(np.array([phase]))[0])
        if not math.isfinite(s0):        # p >= 2: no first-order offset
            s0 = 0.0
        s1 = s0 + 1e-2 * (c.dG if math.isfinite(c.dG) else 1e-6)
        f0, f1 = slope(s0), slope(s1)
        for _ in range(20):
            if f1 == f0:
                break
            s0, s1, f0 = s1, s1 - f1 * (s1 - s0) / (f1 - f0), f1
            if abs(s1 - s0) < 1e-13 * max(1e-3, abs(s1)):
                break
            f1 = slope(s1)
        return s1

    # ------------------------------------------------------------ the slow pendulum
    def slow(self, x: float, phi: float, t: float) -> float:
        """``Kt - (p/q) J`` less its value at ``x = 0`` of ``K0`` (S4): the slow
        Hamiltonian of the resonant normal form, conserved along its flow."""
        mu, sp = self.chain.body.mu, self.space
        k0 = sum(w * x ** (j + 1) / (j + 1) for j, w in enumerate(self.omega) if j >= 1)
        return float(k0 + sum(mu**n / math.factorial(n)
                              * sp.evaluate(self.Ht[n - 1], x, phi, t).real
                              for n in range(1, self.order + 1)))

    def _x_at(self, phi: float, t: float) -> float:
        c = self.chain
        rows = self._dKt_rows(phi, t)
        x = 0.0
        for _ in range(40):
            f = self._dKt(x, phi, t, rows) - c.p / c.q
            h = 1e-6 * (abs(x) + 1e-6)
            df = (self._dKt(x + h, phi, t, rows) - self._dKt(x - h, phi, t, rows)) / (2 * h)
            step = f / df
            x -= step
            if abs(step) < 1e-16:
                break
        return x

    def _hessian(self, x: float, phi: float, t: float) -> tuple[float, float, float]:
        """``(K_xx, K_phiphi, K_xphi)`` of the slow Hamiltonian, from the jets (exact
        polynomials in ``x``, Fourier series in ``phi``: no finite differences)."""
        mu, sp = self.chain.body.mu, self.space
        out = [sum(j * w * x ** (j - 1) for j, w in enumerate(self.omega) if j >= 1), 0.0, 0.0]
        for n in range(1, self.order + 1):
            c, f = mu**n / math.factorial(n), self.Ht[n - 1]
            dx = sp.d_x(f)
            for k, g in enumerate((sp.d_x(dx), sp.d_phi(sp.d_phi(f)), sp.d_phi(dx))):
                out[k] += c * sp.evaluate(g, x, phi, t).real
        return out[0], out[1], out[2]

    def equilibria(self) -> dict[str, tuple[float, float, float]]:
        """The stable and unstable equilibria of the slow Hamiltonian: ``kind ->
        (psi, x, libration or growth rate per radian of phi2)`` (``t = 0``,
        ``phi = psi / q``); NaN where the normal form has no resonant harmonic."""
        from scipy.optimize import brentq

        c, sp, mu = self.chain, self.space, self.chain.body.mu
        q = c.q

        def dpsi(psi: float) -> float:
            x = self._x_at(psi / q, 0.0)
            return sum(mu**n / math.factorial(n)
                       * sp.evaluate(self.pHt[n - 1], x, psi / q, 0.0).real
                       for n in range(1, self.order + 1)) / q

        grid = np.linspace(0.0, 2 * math.pi, 97)
        vals = np.array([dpsi(float(v)) for v in grid])
        out: dict[str, tuple[float, float, float]] = {}
        scale = float(np.max(np.abs(vals)))
        if not scale > 1e-300:
            nan = (math.nan, math.nan, math.nan)
            return {"stable": nan, "unstable": nan}
        for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
            psi = brentq(dpsi, float(grid[i]), float(grid[i + 1]), xtol=1e-14)
            x = self._x_at(psi / q, 0.0)
            Kxx, Kpp, Kxp = self._hessian(x, psi / q, 0.0)
            det = Kxx * Kpp - Kxp * Kxp
            kind = "stable" if det > 0 else "unstable"
            if kind not in out:
                out[kind] = (float(psi), float(x), math.sqrt(abs(det)))
        return out

    def half_width(self, phase: float, g_star: float, s_stable: float) -> float:
        """Half the distance between the two crossings of the separatrix (the level of the
        slow Hamiltonian at the unstable equilibrium) with the seed line, in ``G`` units."""
        from scipy.optimize import brentq

        eq = self.equilibria()
        psi_u, x_u, _r = eq.get("unstable", (math.nan,) * 3)
        if not math.isfinite(psi_u):
            return math.nan
        K_u = self.slow(x_u, psi_u / self.chain.q, 0.0)
        new = self._line(phase, g_star)

        def f(s: float) -> float:
            x, ph, t = new(s)
            return self.slow(x, ph, t) - K_u

        f0 = f(s_stable)
        w = 2.0 * abs(self.chain.W) * math.sqrt(2.0 * abs(f0 / self.omega[1])) \
            if self.omega[1] else 1e-6
        edges = []
        for direction in (-1.0, 1.0):
            step = 0.5 * w
            b = s_stable + direction * step
            for _ in range(40):
                if np.sign(f(b)) != np.sign(f0):
                    break
                step *= 1.5
                b = s_stable + direction * step
            edges.append(brentq(f, min(s_stable, b), max(s_stable, b), xtol=1e-15,
                                rtol=1e-12))
        return 0.5 * (edges[1] - edges[0])


_META = {
    "stable_s": ("\\delta G", "the stable periodic orbit on the seed line of measure_island "
                 "(G units from the resonant torus)", "1", "(S4)"),
    "stable_s_error": ("", "estimated size of the next order of stable_s (order 1: the "
                       "mean second-order term (R12); order 2: the change to order 3; "
                       "order 3: the fourth-order terms of the triangle from K1-K3)", "1",
                       "(R12), (S4)"),
    "half_width": ("\\Delta G", "half the distance between the separatrix's crossings of "
                   "the seed line", "1", "(S4)"),
    "libration_frequency": ("\\Omega", "small-oscillation frequency about the stable "
                            "equilibrium, per radian of phi2", "1", "(S4)"),
    "residue_stable": ("R_s", "Greene's residue sin^2(pi q Omega)", "1", "(R8)"),
    "stable_angle": ("\\psi_s", "slow angle q phi - p phi2 of the stable equilibrium (new "
                     "variables)", "rad", "(S4)"),
    "unstable_angle": ("\\psi_u", "slow angle of the unstable equilibrium", "rad", "(S4)"),
    "stable_action": ("x_s", "action offset J - J* of the stable equilibrium (new "
                      "variables)", "1", "(S4)"),
    "unstable_action": ("x_u", "action offset of the unstable equilibrium", "1", "(S4)"),
}


def island_prediction(body: Any, h: float, M: float, resonance: str, *, order_mu: int = 2,
                      axis: int | None = None, sign: int = 1, g_star: float = 0.0) -> Any:
    """A ``q:p`` island chain predicted to order ``order_mu`` in ``mu`` by the Lie-Deprit
    normal form (S1)-(S4), each order with the estimated size of the next.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia; its ``mu`` > 0 sets the chain.
    h, M : float
        The energy level (> 0) and the area constant.
    resonance : str
        ``"q:p"`` (``W = p/q``); ``p >= 2`` chains have a width from order 2 on.
    order_mu : int
        Highest order in ``mu`` (1 to 3); every order up to it is returned.
    axis : int, optional
        Body axis (1 or 2) of the regime; default: the first the level lists.
    sign : int
        Sign (+1, -1) of the momentum on that axis.
    g_star : float
        The section ``g = g*`` of the seed line (a line through the first-order stable
        point, normal to the resonant torus, as :func:`~andoyer.analysis.resonance.measure.
        measure_island` seeds).

    Returns
    -------
    xarray.Dataset
        On dim ``order_mu``: ``stable_s``, ``stable_s_error``, ``half_width``,
        ``libration_frequency``, ``residue_stable``, ``stable_angle``, ``unstable_angle``,
        ``stable_action``, ``unstable_action``; attrs ``p``, ``q``, ``axis``, ``sign``,
        ``stable_phase`` (the line's free-top phase), ``G_star``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = island_prediction(RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3), 1.0, 0.0, "3:1",
    ...                        axis=1)   # doctest: +SKIP
    """
    import xarray as xr

    from andoyer.analysis.resonance.predict import check_level_args, resonant_rows
    from andoyer.integrate import Section
    from andoyer.integrate.results import describe_variables, provenance
    from andoyer.validation import finite, integer

    h, M, _ = check_level_args(body, h, M, 2)
    if not isinstance(resonance, str):
        raise ValueError(f"resonance must be a string 'q:p', got {resonance!r}")
    try:
        q, p = (int(v) for v in resonance.split(":"))
    except ValueError:
        raise ValueError(f"resonance must be 'q:p' with whole numbers, got "
                         f"{resonance!r}") from None
    if not (1 <= q <= 100 and 1 <= p <= 100 and math.gcd(p, q) == 1):
        raise ValueError(f"resonance {resonance!r}: q and p must be coprime, 1 to 100")
    order_mu = integer("order_mu", order_mu, 1, 3)
    if axis is not None:
        axis = integer("axis", axis, 1, 2)
    if isinstance(sign, bool) or sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {sign!r}")
    g_star = finite("g_star", g_star)
    if not body.mu > 0.0:
        raise ValueError("island_prediction needs mu > 0: at mu = 0 there is no island")
    rows = [r for r in resonant_rows(body, h, M, p + q) if r["p"] == p and r["q"] == q
            and r["sign"] == sign and (axis is None or r["axis"] == axis)]
    if not rows:
        raise ValueError(f"no torus with W = {p}/{q} on h = {h!r}, M = {M!r}"
                         + (f" about axis {axis}" if axis is not None else ""))
    sec = Section("g", g_star, 1)
    chain = ResonantChain(body, h, M, rows[0], sec)
    top = SecondOrderChain(chain, order_mu + 1)    # the reduced Hamiltonian once
    chains = {n: SecondOrderChain(chain, n, like=top) for n in range(1, order_mu + 1)}
    chains[order_mu + 1] = top
    psi_s = chain.psi_s if chain.mu_order == 1 else \
        chains[order_mu].equilibria().get("stable", (math.nan,) * 3)[0]
    phase = chain.points(psi_s) if math.isfinite(psi_s) else np.empty(0)
    if phase.size == 0:
        raise ValueError(f"resonance {resonance!r}: the normal form to order {order_mu} has "
                         "no stable equilibrium (no resonant harmonic up to that order)")
    ph = float(phase[0])
    names = list(_META)
    cols: dict[str, list[float]] = {k: [] for k in names}
    for n in range(1, order_mu + 1):
        so = chains[n]
        eq = so.equilibria()
        st = so.stable_s(ph, g_star)
        nxt = chains[n + 1].stable_s(ph, g_star) if n >= 2 else \
            st + chain.second_order_mean_shift()
        if n < p:     # (R3): each order brings |k2| <= 1 more; no resonant harmonic yet
            eq = {}
        width = so.half_width(ph, g_star, st) if n >= p else math.nan
        om = eq.get("stable", (math.nan,) * 3)[2]
        vals = {"stable_s": st, "stable_s_error": abs(nxt - st), "half_width": width,
                "libration_frequency": om, "residue_stable": math.sin(math.pi * q * om) ** 2,
                "stable_angle": eq.get("stable", (math.nan,) * 3)[0],
                "unstable_angle": eq.get("unstable", (math.nan,) * 3)[0],
                "stable_action": eq.get("stable", (math.nan,) * 3)[1],
                "unstable_action": eq.get("unstable", (math.nan,) * 3)[1]}
        for k in names:
            cols[k].append(float(vals[k]))
    ds = xr.Dataset({k: ("order_mu", np.array(v)) for k, v in cols.items()},
                    coords={"order_mu": np.arange(1, order_mu + 1)},
                    attrs=provenance(body, h=h, M=M, p=p, q=q, label=resonance,
                                     axis=int(rows[0]["axis"]), sign=sign, g_star=g_star,
                                     stable_phase=ph, G_star=chain.torus.G,
                                     method="Lie-Deprit normal form in mu (Deprit's "
                                            "triangle) on jets about the resonant torus",
                                     derivation="andoyer.analysis.resonance.second_order "
                                                "(S1)-(S4), deprit (D1)-(D4)"))
    return describe_variables(ds, _META)
