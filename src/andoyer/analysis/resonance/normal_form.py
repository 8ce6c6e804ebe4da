r"""Birkhoff normal form of the section map at an elliptic periodic orbit of the heavy top.

The perturbed system's (``mu > 0``) section map ``P`` of ``g = g*`` on ``H = h`` (the
plane ``(l, L)``, canonical: ``P`` preserves ``dl ^ dL``) has elliptic fixed points: the
free top's centres moved by ``mu``, and the stable periodic orbits of the island chains
(fixed points of ``P^n``, ``n = q`` returns). About one, the map's Taylor polynomial to
degree ``N`` comes from jet transport (:mod:`andoyer.integrate.jet_transport`, (J1)-(J4));
its Birkhoff normal form gives the rotation number as a function of the action:

- (P1) The fixed point by Newton on ``P^n(x) - x`` with the degree-1 jets (the Jacobian).
- (P2) ``x - x* = w v + conj(w v)`` with ``v`` the eigenvector of ``lambda =
  exp(2 pi i omega0)`` (``0 < omega0 < 1/2``: the rotation in the ``w`` plane), scaled
  so that the circle ``|w| = r`` encloses the area ``2 pi r^2`` (``|w|^2`` is the action
  to first order); ``w' = F(w, wbar)``.
- (P3) Degree by degree ``d = 2 .. N``, the conjugacy ``w = Phi(z) = z + phi(z, zbar)`` and
  the normal form ``G(z)``: with ``R`` the degree-``d`` part of ``F(Phi) - Phi(G)``
  (lower degrees already set), the term ``z^j zbar^k`` is removed,
  ``phi_jk = -R_jk / (lambda - lambda^(j - k))``, unless ``j - k = 1`` (resonant:
  ``g_jk = R_jk``, ``phi_jk = 0``). ``G(z) = z (lambda + sum_k a_k |z|^(2k))``.
- (P4) ``rho(|z|^2) = arg(lambda + sum_k a_k |z|^(2k)) / (2 pi)`` (turns per iterate of
  ``P^n``); its modulus is 1 to the order computed (the map preserves area:
  ``radial_defect`` says by how much it is not).
- (P5) The action of the invariant curve ``|z| = r``: ``I = area / (2 pi) = sum_m m |W_m(r)|^2``
  (``Phi(r e^(i t)) = sum_m W_m(r) e^(i m t)``), a series in ``r^2``; reverted and
  composed, ``rho(I) = omega0 + tau_1 I + tau_2 I^2 + ...`` -- the twist coefficients,
  invariant under symplectic changes of coordinates.

Degree ``N = 2K + 1`` gives ``tau_1 .. tau_K``; the rotation number of an orbit of
amplitude ``r`` errs by ``O(r^(2K + 2))`` (the next resonant term), which
:func:`orbit_rotation_numbers` (NAFF on the orbits through an engine) measures.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.integrate import Section
from andoyer.integrate.jet_transport import MAX_DEGREE, JetBasis, SectionJet, section_map_jet
from andoyer.integrate.results import describe_variables, provenance
from andoyer.validation import finite, integer, positive, real_array

__all__ = ["periodic_orbit_normal_form", "orbit_rotation_numbers", "MAX_DEGREE"]

#: Newton steps allowed for the fixed point (P1).
_NEWTON = 12
#: Smallest ``|lambda - lambda^m|`` of the homological equation (P3) accepted: below it the
#: fixed point is too near a low-order resonance for the normal form to mean anything.
MIN_DIVISOR = 1e-6


# ------------------------------------------------------------- the map through an engine
def _section_points(body: RigidBody, h: float, M: float, g_star: float, l: NDArray[np.float64],
                    L: NDArray[np.float64], G: NDArray[np.float64], n: int, engine: Any,
                    tol: float) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                         NDArray[np.float64]]:
    """``(l, L, t)`` of the first ``n`` crossings of ``g = g*`` (direction +1) of the orbits
    seeded at ``(l, g*, L, G, M)``, through the engine seam."""
    from andoyer.charts.andoyer_deprit import from_andoyer
    from andoyer.integrate.api import poincare

    y0 = from_andoyer(np.stack([l, np.full_like(l, g_star), L, G, np.full_like(l, M)], -1))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = poincare(body, y0, Section("g", g_star, 1), n, engine=engine, rtol=tol, atol=tol)
    lo = np.arctan2(ds.G1.values, ds.G2.values)
    return lo, ds.G3.values, ds.t.values


def _root(body: RigidBody, h: float, M: float, g_star: float, l: float, L: float,
          G_near: float | None, name: str = "seed") -> float:
    from andoyer.integrate.fill import section_roots

    roots = section_roots(body, h, M, ("g", g_star), [l], [L])[0]
    if roots.size == 0:
        raise ValueError(f"{name}: the point (l, L) = ({l!r}, {L!r}) is not on the level "
                         f"h = {h!r} (no root G of H = h above it)")
    if G_near is None:
        if roots.size > 1:
            raise ValueError(f"seed: {roots.size} roots G of H = h above ({l!r}, {L!r}): "
                             f"{roots.tolist()}; give G (the one near the orbit)")
        return float(roots[0])
    return float(roots[np.argmin(np.abs(roots - G_near))])


class _Map:
    """``P^n`` of the section ``g = g*`` as jets about any base point."""

    def __init__(self, body: RigidBody, h: float, M: float, g_star: float, period: int,
                 engine: Any, tol: float, G: float | None) -> None:
        self.body, self.h, self.M, self.g_star = body, h, M, g_star
        self.period, self.engine, self.tol, self.G = period, engine, tol, G

    def jet(self, l0: float, L0: float, degree: int, n_steps: int | None,
            error_estimate: bool = True) -> tuple[SectionJet, float]:
        G0 = _root(self.body, self.h, self.M, self.g_star, l0, L0, self.G)
        _l, _L, t = _section_points(self.body, self.h, self.M, self.g_star, np.array([l0]),
                                    np.array([L0]), np.array([G0]), self.period, self.engine,
                                    self.tol)
        T = float(t[0, self.period - 1])
        if not math.isfinite(T):
            raise ValueError("seed: the orbit does not return to the section g = g_star "
                             f"{self.period} times")
        steps = n_steps if n_steps is not None else 2 * max(16, math.ceil(
            40.0 * T * max(self.body.a, self.body.b, self.body.c) * G0 / (2 * math.pi)))
        return section_map_jet(self.body, self.h, self.M, self.g_star, l0, L0, G0, T,
                               degree=degree, n_steps=steps, phi0=self.body.phi0,
                               error_estimate=error_estimate), G0


def _fixed_point(m: _Map, l0: float, L0: float, n_steps: int | None
                 ) -> tuple[float, float, float]:
    x = np.array([l0, L0])
    step = np.array([np.inf, np.inf])
    for _ in range(_NEWTON):
        jet, _G = m.jet(float(x[0]), float(x[1]), 1, n_steps, error_estimate=False)
        f = np.array([jet.l[0] - x[0], jet.L[0] - x[1]])
        step = np.linalg.solve(jet.matrix() - np.eye(2), -f)
        if not np.max(np.abs(step)) < 0.5:
            raise ValueError(f"seed: Newton's step for the fixed point of P^{m.period} is "
                             f"{np.max(np.abs(step)):.3g} (no fixed point near the seed, or "
                             "a linear map near the identity: a 1:1 resonance)")
        x = x + step
        if np.max(np.abs(step)) < 1e-14 * max(1.0, float(np.max(np.abs(x)))):
            break
    return float(x[0]), float(x[1]), float(np.max(np.abs(step)))


# ------------------------------------------------------------------ complex jets (P2)-(P5)
def _conj(basis: JetBasis, c: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``conj(f(z, zbar))`` as a jet in ``(z, zbar)``: ``c_ij -> conj(c_ji)``."""
    swap = np.array([basis.index[(j, i)] for i, j in basis.powers])
    return np.conj(c[swap])


def _compose(basis: JetBasis, f: NDArray[Any], x: NDArray[Any], y: NDArray[Any]
             ) -> NDArray[np.complex128]:
    """``f(x, y)`` for jets ``x, y`` without constant terms."""
    n = basis.degree
    px = [basis.constant(1.0, complex)]
    py = [basis.constant(1.0, complex)]
    for _ in range(n):
        px.append(basis.mul(px[-1], x))
        py.append(basis.mul(py[-1], y))
    out = np.zeros(basis.size, complex)
    for k, (i, j) in enumerate(basis.powers):
        if f[k] != 0.0:
            out = out + f[k] * basis.mul(px[i], py[j])
    return out


def _normal_form(jet: SectionJet, x_star: NDArray[np.float64]) -> dict[str, Any]:
    """(P2)-(P5) on the jets of ``P^n`` about the fixed point."""
    basis = jet.basis
    N = basis.degree
    A = jet.matrix()
    tr, det = float(np.trace(A)), float(np.linalg.det(A))
    if not abs(tr) < 2.0:
        raise ValueError(f"seed: the fixed point is not elliptic (trace of the linear map "
                         f"{tr:.6g}, |trace| >= 2)")
    vals, vecs = np.linalg.eig(A)
    k = int(np.argmax(vals.imag))
    lam = complex(vals[k])
    lam /= abs(lam)
    v = vecs[:, k]
    cross = float(v.real[0] * v.imag[1] - v.real[1] * v.imag[0])
    v = v / math.sqrt(2.0 * abs(cross))
    V = np.array([[v[0], np.conj(v[0])], [v[1], np.conj(v[1])]])
    ell = np.linalg.inv(V)[0]
    # F(w, wbar): the map in w, the displacement x = v w + conj(v w)
    X1 = np.zeros(basis.size, complex)
    X2 = np.zeros(basis.size, complex)
    X1[1], X1[2] = v[0], np.conj(v[0])
    X2[1], X2[2] = v[1], np.conj(v[1])
    pl, pL = jet.l.astype(complex), jet.L.astype(complex)
    pl[0] = pL[0] = 0.0
    F = ell[0] * _compose(basis, pl, X1, X2) + ell[1] * _compose(basis, pL, X1, X2)
    phi = np.zeros(basis.size, complex)
    phi[1] = 1.0
    g = np.zeros(basis.size, complex)
    g[1] = lam
    small = math.inf
    for d in range(2, N + 1):
        R = _compose(basis, F, phi, _conj(basis, phi)) - _compose(basis, phi, g,
                                                                   _conj(basis, g))
        for kk, (i, j) in enumerate(basis.powers):
            if i + j != d:
                continue
            if i - j == 1:
                g[kk] = R[kk]
            else:
                div = lam - lam ** (i - j)
                small = min(small, abs(div))
                phi[kk] = -R[kk] / div
    if small < MIN_DIVISOR:
        turns = np.angle(lam) / (2 * np.pi)
        raise ValueError(f"seed: the fixed point's rotation number {turns:.6g} is within"
                         f" {small:.1e} of a resonance of order <= {N} (the "
                         "normal form's divisors vanish); lower degree")
    K = (N - 1) // 2
    a = np.zeros(K + 1, complex)           # G(z) = z (a0 + a1 |z|^2 + ...)
    a[0] = lam
    for kk in range(1, K + 1):
        a[kk] = g[basis.index[(kk + 1, kk)]]
    s = a / lam
    s[0] = 0.0
    logs = np.zeros(K + 1, complex)         # log(1 + s) as a series in I' = |z|^2
    power = np.zeros(K + 1, complex)
    power[0] = 1.0
    for n in range(1, K + 1):
        power = np.convolve(power, s)[: K + 1]
        logs += (-1.0) ** (n + 1) * power / n
    omega0 = float(np.angle(lam) / (2 * math.pi))
    rho_z = logs.imag / (2 * math.pi)
    rho_z[0] = omega0
    # (P5) the action of |z| = r: I = sum_m m |W_m(r)|^2, a series in r
    area = np.zeros(2 * N + 1)
    for m in range(-N, N + 1):
        if m == 0:
            continue
        Wm = np.zeros(N + 1, complex)
        for kk, (i, j) in enumerate(basis.powers):
            if i - j == m:
                Wm[i + j] += phi[kk]
        area += m * np.convolve(Wm, np.conj(Wm)).real
    action_z = area[0: 2 * K + 3: 2][: K + 1]      # I(I') up to I'^K (exact to r^(N+1))
    # revert I(I') = I' + c2 I'^2 + ... and compose rho(I'(I))
    inv = np.zeros(K + 1)
    inv[1] = 1.0
    for _ in range(K + 1):
        comp = np.zeros(K + 1)
        power_r = np.zeros(K + 1)
        power_r[0] = 1.0
        for n in range(1, K + 1):
            power_r = np.convolve(power_r, inv)[: K + 1]
            comp += action_z[n] * power_r
        inv = inv - (comp - np.eye(K + 1)[1])
    tau = np.zeros(K + 1)
    power_r = np.zeros(K + 1)
    power_r[0] = 1.0
    tau[0] = omega0
    for n in range(1, K + 1):
        power_r = np.convolve(power_r, inv)[: K + 1]
        tau += rho_z[n] * power_r
    return {"lam": lam, "v": v, "ell": ell, "phi": phi, "g": g, "omega0": omega0,
            "rho_z": rho_z, "radial": logs.real, "action_z": action_z, "tau": tau,
            "trace": tr, "det": det, "small_divisor": small, "x_star": x_star}


def _to_normal(basis: JetBasis, nf: dict[str, Any], x: NDArray[np.float64]
               ) -> NDArray[np.complex128]:
    """``z = Phi^-1(w)`` of section points ``x`` (shape (n, 2)) by fixed-point iteration."""
    w = (x - nf["x_star"]) @ nf["ell"]
    phi = nf["phi"].copy()
    phi[1] = 0.0
    z = w.copy()
    for _ in range(60):
        z_new = w - basis.evaluate(phi, z, np.conj(z))
        if np.all(np.abs(z_new - z) <= 1e-16 * np.maximum(np.abs(z), 1e-300)):
            z = z_new
            break
        z = z_new
    return np.asarray(z)


_META = {
    "fixed_l": ("l^*", "l of the elliptic fixed point of P^n on the section", "rad", "(P1)"),
    "fixed_L": ("L^*", "L of the fixed point", "1", "(P1)"),
    "fixed_G": ("G^*", "|G| of the fixed point (the root of H = h above it)", "1", "(P1)"),
    "fixed_point_step": ("", "last Newton step of (P1): the fixed point's accuracy", "1",
                         "(P1)"),
    "return_time": ("T", "time of the n returns of the fixed point's orbit", "body time",
                    "(J3)"),
    "rotation": ("\\omega_0", "rotation number of the linear map, turns per iterate of P^n",
                 "1", "(P2)"),
    "trace": ("", "trace of the linear map (2 cos 2 pi omega0)", "1", "(P2)"),
    "residue": ("R", "Greene's residue (2 - trace) / 4", "1", "(R8)"),
    "determinant": ("", "determinant of the linear map (1: area preserved)", "1", "(P2)"),
    "twist": ("\\tau_k", "rho(I) = omega0 + sum_k tau_k I^k: the twist coefficients in the "
              "action I (area / 2 pi in the plane (l, L))", "1", "(P5)"),
    "rotation_z": ("", "rho as a series in |z|^2 of the normal form's coordinate (P4)", "1",
                   "(P4)"),
    "radial_defect": ("", "log|lambda + sum a_k |z|^2k| per power of |z|^2: zero for an "
                      "area-preserving map (a check)", "1", "(P4)"),
    "action_series": ("", "the action I of the curve |z| = r per power of r^2", "1", "(P5)"),
    "map_l": ("", "Taylor coefficients of l' - l* per monomial (dl)^i (dL)^j", "", "(J4)"),
    "map_L": ("", "Taylor coefficients of L' - L* per monomial", "", "(J4)"),
    "map_error": ("", "per degree, the largest change of a map coefficient between n_steps/2 "
                  "and n_steps Runge-Kutta steps (8th order: the error is ~1/256 of it)",
                  "", "(J2)"),
    "power_l": ("i", "power of dl of the monomial", "1", ""),
    "power_L": ("j", "power of dL of the monomial", "1", ""),
    "small_divisor": ("", "smallest |lambda - lambda^m| of the homological equations", "1",
                      "(P3)"),
}


@checks_body(ranges={"h": "energy", "M": "action", "G": "length", "tol": "tolerance"})
def periodic_orbit_normal_form(body: RigidBody, h: float, M: float, seed: ArrayLike, *,
                               period: int = 1, degree: int = 5, g_star: float = 0.0,
                               G: float | None = None, engine: str | None = None,
                               tol: float = 1e-13, n_steps: int | None = None
                               ) -> xr.Dataset:
    """The Birkhoff normal form of the section map at an elliptic periodic orbit.

    See the module's docstring, (P1)-(P5): the fixed point of ``P^period`` near ``seed``,
    the map's Taylor polynomial of degree ``degree`` by jet transport
    (:func:`andoyer.integrate.jet_transport.section_map_jet`), its Birkhoff normal form and
    the rotation number as a function of the action, ``rho(I) = omega0 + tau_1 I + ...``.

    Parameters
    ----------
    body : RigidBody
        Any heavy top (``mu >= 0``).
    h, M : float
        The energy level and the area constant.
    seed : array_like, shape (2,)
        ``(l, L)`` near the fixed point on the section ``g = g_star``.
    period : int
        Returns of the periodic orbit to the section (``q`` for a ``q:p`` chain's stable
        orbit; 1 for the moved centres of the free top).
    degree : int
        Degree ``N`` of the map's Taylor polynomial (3 to :data:`MAX_DEGREE`); the twist
        coefficients ``tau_1 .. tau_K``, ``K = (N - 1) // 2``.
    g_star : float
        The section ``g = g_star`` (crossed with ``dg/dt > 0``).
    G : float, optional
        ``|G|`` near the orbit's, to choose among several roots of ``H = h`` above the seed.
    engine : str, optional
        Engine (with crossings) of the return times and of the fixed point's orbit.
    tol : float
        Tolerance of the engine's integration.
    n_steps : int, optional
        Runge-Kutta steps of the jets over the ``period`` returns (even); default from the
        return time and the body's fastest rate (``~80`` steps per turn).

    Returns
    -------
    xarray.Dataset
        ``fixed_l``, ``fixed_L``, ``fixed_G``, ``fixed_point_step``, ``return_time``,
        ``rotation`` (``omega0``), ``trace``, ``residue``, ``determinant``,
        ``small_divisor``; on dim ``order`` (``k = 0 .. K``): ``twist`` (``tau_k``, ``tau_0 =
        omega0``), ``rotation_z``, ``radial_defect``, ``action_series``; on dim
        ``monomial``: ``map_l``, ``map_L`` with ``power_l``, ``power_L``; on dim ``degree``:
        ``map_error``. Attrs: ``period``, ``degree``, ``g_star``, ``n_steps``, the
        normalisation (``eigenvector``, ``dual``) and the conjugacy's coefficients
        (``conjugacy_real``, ``conjugacy_imag``) that :func:`orbit_rotation_numbers` reads.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-2)    # the rotation about y, moved
    >>> nf = periodic_orbit_normal_form(body, 1.0, 0.0, (0.0, 0.0), degree=3,
    ...                                 engine="numba")
    >>> round(float(nf.rotation), 6), round(float(nf.twist[1]), 4), round(float(nf.fixed_L), 5)
    (0.422749, 0.1766, -0.01531)
    """
    h, M = finite("h", h), finite("M", M)
    s = real_array("seed", seed)
    if s.shape != (2,):
        raise ValueError(f"seed must be one point (l, L) of the section, got shape {s.shape}")
    period = integer("period", period, 1, 1000)
    degree = integer("degree", degree, 3, MAX_DEGREE)
    g_star = finite("g_star", g_star)
    if G is not None:
        G = positive("G", G)
    tol = positive("tol", tol, maximum=1e-8)
    if n_steps is not None:
        n_steps = integer("n_steps", n_steps, 2, 10**7)
        if n_steps % 2:
            raise ValueError(f"n_steps must be even (the error estimate halves it), got "
                             f"{n_steps!r}")
    g_star = Section("g", g_star).value
    m = _Map(body, h, M, g_star, period, engine, tol, G)
    l_star, L_star, last = _fixed_point(m, float(s[0]), float(s[1]), n_steps)
    jet, G_star = m.jet(l_star, L_star, degree, n_steps)
    nf = _normal_form(jet, np.array([l_star, L_star]))
    basis = jet.basis
    ml, mL = jet.l.copy(), jet.L.copy()
    ml[0] -= l_star
    mL[0] -= L_star
    K = nf["tau"].size - 1
    ds = xr.Dataset(
        {"fixed_l": ((), l_star), "fixed_L": ((), L_star), "fixed_G": ((), G_star),
         "fixed_point_step": ((), last), "return_time": ((), jet.time),
         "rotation": ((), nf["omega0"]), "trace": ((), nf["trace"]),
         "residue": ((), (2.0 - nf["trace"]) / 4.0), "determinant": ((), nf["det"]),
         "small_divisor": ((), nf["small_divisor"]),
         "twist": ("order", nf["tau"]), "rotation_z": ("order", nf["rho_z"]),
         "radial_defect": ("order", nf["radial"]), "action_series": ("order", nf["action_z"]),
         "map_l": ("monomial", ml), "map_L": ("monomial", mL),
         "power_l": ("monomial", np.array([p[0] for p in basis.powers])),
         "power_L": ("monomial", np.array([p[1] for p in basis.powers])),
         "map_error": ("degree", jet.error)},
        coords={"order": np.arange(K + 1), "degree": np.arange(degree + 1)},
        attrs=provenance(body, h=h, M=M, period=period, degree=degree, g_star=g_star,
                         n_steps=jet.n_steps, tolerance=tol,
                         eigenvector_real=nf["v"].real.tolist(),
                         eigenvector_imag=nf["v"].imag.tolist(),
                         dual_real=nf["ell"].real.tolist(), dual_imag=nf["ell"].imag.tolist(),
                         conjugacy_real=nf["phi"].real.tolist(),
                         conjugacy_imag=nf["phi"].imag.tolist(),
                         normal_form_real=nf["g"].real.tolist(),
                         normal_form_imag=nf["g"].imag.tolist(),
                         method="jet transport of the section map (DOP853 steps on jets), "
                                "Birkhoff normal form of the map degree by degree",
                         derivation="andoyer.analysis.resonance.normal_form (P1)-(P5), "
                                    "andoyer.integrate.jet_transport (J1)-(J4)"))
    return describe_variables(ds, _META)


def _nf_of(ds: xr.Dataset) -> tuple[JetBasis, dict[str, Any]]:
    basis = JetBasis(int(ds.attrs["degree"]))
    a = ds.attrs
    nf = {"x_star": np.array([float(ds.fixed_l), float(ds.fixed_L)]),
          "ell": np.array(a["dual_real"]) + 1j * np.array(a["dual_imag"]),
          "phi": np.array(a["conjugacy_real"]) + 1j * np.array(a["conjugacy_imag"]),
          "g": np.array(a["normal_form_real"]) + 1j * np.array(a["normal_form_imag"])}
    return basis, nf


def _predicted(basis: JetBasis, nf: dict[str, Any], I_z: NDArray[np.float64]
               ) -> NDArray[np.float64]:
    """``rho(|z|^2)`` of the normal form to its degree (every resonant term, (P4))."""
    N = basis.degree
    lam = nf["g"][1]
    a = lam + sum(nf["g"][basis.index[(k + 1, k)]] * I_z**k for k in range(1, (N - 1) // 2 + 1))
    return np.asarray(np.angle(a / lam) / (2 * math.pi) + np.angle(lam) / (2 * math.pi))


@checks_body(ranges={"h": "energy", "M": "action", "tol": "tolerance"})
def orbit_rotation_numbers(body: RigidBody, h: float, M: float, normal_form: xr.Dataset,
                           amplitudes: ArrayLike, *, n_returns: int = 2048,
                           engine: str | None = None, tol: float = 1e-13) -> xr.Dataset:
    """Rotation numbers of orbits about the fixed point of ``normal_form``, by NAFF, beside
    the normal form's prediction.

    Orbits are seeded on the section at ``x* + a v`` (``v`` of (P2) scaled to amplitude
    ``a`` of ``|w|``), integrated through the engine seam
    (:func:`andoyer.integrate.poincare`, one batch), every ``period``-th crossing kept; the
    rotation number is NAFF's main line (:func:`andoyer.analysis.chaos.frequency.naff`) of
    ``w_n`` (the points in the linear normal coordinate, turns per iterate), the
    prediction ``rho(|z_0|^2)`` of (P4) at ``z_0 = Phi^-1(w_0)``.

    Parameters
    ----------
    body : RigidBody
        The body of ``normal_form``.
    h, M : float
        Its level and area constant.
    normal_form : xarray.Dataset
        A result of :func:`periodic_orbit_normal_form`.
    amplitudes : array_like
        Amplitudes ``|w_0|`` (> 0; the action is ``~ a^2``).
    n_returns : int
        Iterates of ``P^period`` per orbit (>= 64).
    engine : str, optional
        Engine with crossings.
    tol : float
        Tolerance of the integration.

    Returns
    -------
    xarray.Dataset
        On dim ``orbit``: ``amplitude``, ``action`` (``I`` of (P5) at ``|z_0|``),
        ``rotation_naff``, ``rotation_predicted``, ``rotation_error`` (their difference),
        ``rotation_linear`` (``omega0``: the error of degree 1).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3)
    >>> nf = periodic_orbit_normal_form(body, 1.0, 0.0, (math.pi / 2, 0.0), degree=5,
    ...                                 engine="numba")  # doctest: +SKIP
    >>> r = orbit_rotation_numbers(body, 1.0, 0.0, nf, [0.02, 0.04])  # doctest: +SKIP
    """
    from andoyer.analysis.chaos.frequency import naff

    if not isinstance(normal_form, xr.Dataset) or "conjugacy_real" not in normal_form.attrs:
        raise ValueError("normal_form must be a dataset of periodic_orbit_normal_form")
    a = real_array("amplitudes", amplitudes)
    if a.ndim > 1 or a.size == 0 or not np.all(np.isfinite(a)) or not np.all(a > 0.0):
        raise ValueError(f"amplitudes must be one or more finite numbers > 0 (a 1-D array), "
                         f"got shape {a.shape}")
    a = a.ravel()
    n_returns = integer("n_returns", n_returns, 64, 10**6)
    tol = positive("tol", tol, maximum=1e-8)
    basis, nf = _nf_of(normal_form)
    period = int(normal_form.attrs["period"])
    g_star = float(normal_form.attrs["g_star"])
    v = np.linalg.inv(np.array([nf["ell"], np.conj(nf["ell"])]))[:, 0]
    x0 = nf["x_star"][None, :] + 2.0 * np.real(a[:, None] * v[None, :])
    G = np.array([_root(body, h, M, g_star, float(p[0]), float(p[1]),
                        float(normal_form.fixed_G), "amplitudes") for p in x0])
    lo, Lo, _t = _section_points(body, h, M, g_star, x0[:, 0], x0[:, 1], G,
                                 n_returns * period, engine, tol)
    rot: list[float] = []
    act: list[float] = []
    z0 = _to_normal(basis, nf, x0)
    I_z = np.abs(z0) ** 2
    series = normal_form.action_series.values
    for i in range(a.size):
        pts = np.stack([lo[i, period - 1::period], Lo[i, period - 1::period]], -1)
        pts[:, 0] = nf["x_star"][0] + np.angle(np.exp(1j * (pts[:, 0] - nf["x_star"][0])))
        if not np.all(np.isfinite(pts)):
            rot.append(math.nan)
        else:
            pts = np.concatenate([x0[i][None, :], pts])
            w = (pts - nf["x_star"]) @ nf["ell"]
            f = float(naff(w, 1.0).frequency[0]) / (2 * math.pi)
            rot.append(f % 1.0)
        act.append(float(np.polyval(series[::-1], I_z[i])))
    pred = np.asarray(_predicted(basis, nf, I_z) % 1.0)
    rot_a = np.array(rot)
    ds = xr.Dataset(
        {"amplitude": ("orbit", a), "action": ("orbit", np.array(act)),
         "rotation_naff": ("orbit", rot_a), "rotation_predicted": ("orbit", pred),
         "rotation_error": ("orbit", pred - rot_a),
         "rotation_linear": ((), float(normal_form.rotation))},
        attrs=provenance(body, h=h, M=M, period=period, degree=int(normal_form.attrs["degree"]),
                         n_returns=n_returns, tolerance=tol,
                         method="NAFF main line of the section points in the linear normal "
                                "coordinate w (turns per iterate of P^period)"))
    return describe_variables(ds, {
        "amplitude": ("|w_0|", "amplitude of the seed in the linear normal coordinate", "1",
                      "(P2)"),
        "action": ("I", "action of the seed's invariant curve from the normal form", "1",
                   "(P5)"),
        "rotation_naff": ("\\rho", "rotation number measured by NAFF", "1", ""),
        "rotation_predicted": ("\\rho(I)", "rotation number of the normal form at the seed",
                               "1", "(P4)"),
        "rotation_error": ("", "predicted minus measured rotation number", "1", ""),
        "rotation_linear": ("\\omega_0", "rotation number of the linear map", "1", "(P2)")})
