"""Fixed points of the unperturbed system in the Andoyer-Deprit and Hess charts.

Two families, each found numerically and matched with its closed form:

* the fixed points of the unperturbed system (9) of [1]_ in ``(l, L)`` at fixed
  ``G = G0`` (:func:`andoyer_fixed_points`);
* the fixed points of its form in the Hess chart (14), ``(theta1, J1)`` at fixed
  ``J2`` and ``M = 0`` (the "unperturbed system" after Fig. 3; :func:`hess_fixed_points`).

Each point is tied to the permanent rotation(s) it stands for; those and the
equilibria ``G = 0, gamma = -+ r`` of the full Euler-Poisson equations (1) live in
:mod:`andoyer.analysis.unperturbed.equilibria`. Text tables: :func:`andoyer.io.tables.format_table`.

The reduced fields and their Jacobians are derived with SymPy from the chart
Hamiltonians of :mod:`andoyer.symbolic.hamiltonian` at ``mu = 0`` (nothing is typed
from the paper), lambdified once per process. The roots are found by
:func:`scipy.optimize.root` from the local minima of ``|field|`` on a grid that
includes the singular lines.

Closed forms (derived here, distinct moments ``a, b, c``)
---------------------------------------------------------
With ``s(l) = a sin^2 l + b cos^2 l``, (9) reads ``dl/dt = L (c - s(l))``,
``dL/dt = -(G0^2 - L^2)(a - b) sin 2l / 2``. Its zeros in ``l in [0, 2 pi)``,
``L in [-G0, G0]`` are

* ``(0, 0), (pi, 0)``: ``G = +-G0 e_y``, the permanent rotations about the y axis;
  ``(pi/2, 0), (3 pi/2, 0)``: ``G = +-G0 e_x``, about the x axis. Regular points of
  the chart; eigenvalues ``+-G0 sqrt(-(I_k - I_i)(I_k - I_j))`` -- centres about the
  major and minor axes, saddles about the middle one;
* when z is the middle axis (``c`` between ``a`` and ``b``; a Hess body): the points
  ``sin^2 l = (b - c)/(b - a)`` on each singular line ``L = +-G0`` -- ``l = +-phi0
  (mod pi)`` on a Hess body, 8 points. The whole line ``L = G0`` (or ``-G0``) is *one*
  state, the rotation about +z (or -z); the chart's points are only where the
  separatrices meet the line. The chart Jacobian there has eigenvalues
  ``+-2 sigma G0`` (``sigma = sqrt((b - c)(c - a))``), twice the physical exponent
  ``sigma G0`` of the rotation about z on the momentum sphere: near the pole the chart
  action ``G0 - |L|`` is quadratic in the distance. When z is an extreme axis the
  lines carry no chart fixed point at all (they are closed orbits of the chart field),
  though the rotation about z is then a (physical) centre.

In the Hess chart ``theta1 = 2 (l + phi0)``, ``J1 = (G0 + L)/2``: on ``[0, 2 pi)`` the
points ``l`` and ``l + pi`` coincide (the symmetry ``(G1, G2, gamma3) -> -(G1, G2,
gamma3)`` of ``M = 0``), so a Hess body has 6 fixed points: the centres
``(2 phi0, J2/2)`` (+-y) and ``(2 phi0 + pi, J2/2)`` (+-x), and the four points the
paper lists, ``(0, 0), (4 phi0, 0)`` on ``J1 = 0`` (-z) and ``(0, J2), (4 phi0, J2)`` on
``J1 = J2`` (+z). The double cover ``[0, 4 pi)`` separates the two senses of each
rotation: 12 points, one-to-one with those of ``(l, L)``.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import itertools
import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import Any, Literal

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer.analysis.unperturbed.equilibria import (
    PermanentRotation,
    classify,
    permanent_rotations,
    require_distinct_moments,
    sorted_eigenvalues,
)
from andoyer.body import RigidBody, checks_body
from andoyer.integrate.results import provenance
from andoyer.validation import MAX_ACTION, checks_arguments, integer
from andoyer.validation import positive as _positive

__all__ = ["FixedPoint", "FixedPointSet", "andoyer_fixed_points", "hess_fixed_points",
           "theta_text"]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

ReducedChart = Literal["andoyer", "hess"]


#: Relative residual of the field below which a Newton result is accepted as a root.
ROOT_RTOL = 1e-11
#: Two roots closer than this (relative to the domain) are the same point.
MERGE_RTOL = 1e-7


# ---------------------------------------------------------------------- derivations
@cache
def _reduced(chart: ReducedChart) -> tuple[Callable[..., Any], ...]:
    """H0, field and Jacobian of the mu = 0 reduced system, lambdified from SymPy.

    Arguments of the returned functions: ``(q, p, action, a, b, c, phi0)`` with
    ``(q, p) = (l, L)`` and ``action = G`` for ``"andoyer"``, ``(theta1, J1)`` and
    ``J2`` for ``"hess"`` (``phi0`` unused in ``"andoyer"``).
    """
    import sympy as sp

    from andoyer.symbolic.hamiltonian import H_andoyer, H_hess, S

    if chart == "andoyer":
        H, q, p, act = H_andoyer().subs(S.mu, 0), S.l, S.L, S.G
    else:
        H, q, p, act = H_hess().subs({S.mu: 0, S.J3: 0}), S.theta1, S.J1, S.J2
    field = sp.Matrix([sp.diff(H, p), -sp.diff(H, q)])
    jac = field.jacobian([q, p])
    args = (q, p, act, S.a, S.b, S.c, S.phi0)
    return (sp.lambdify(args, H, "numpy"), sp.lambdify(args, list(field), "numpy"),
            sp.lambdify(args, jac.tolist(), "numpy"))


# ---------------------------------------------------------------------- fixed points
@dataclass(frozen=True)
class FixedPoint:
    """A fixed point of the reduced unperturbed system in one chart.

    Attributes
    ----------
    chart : {"andoyer", "hess"}
        ``(q, p) = (l, L)`` at fixed ``G0``, or ``(theta1, J1)`` at fixed ``J2``.
    q, p : float
        The numerical root (``q`` reduced to the chart's angle range).
    q_closed, p_closed : float
        The matching closed form; ``closed_form`` its text, e.g. ``"(2 phi0, J2/2)"``.
    residual : float
        ``|field(q, p)|`` at the numerical root, relative to the field's scale.
    eigenvalues : tuple of 2 complex
        Of the chart Jacobian at the root; ``eigenvalues_closed`` their closed form.
    linear_type : str
        Of the chart Jacobian (``"centre"``, ``"saddle"``, ``"degenerate"``).
    motions : tuple of PermanentRotation
        The physical state(s) the point stands for (two senses when ``theta1`` is taken
        mod 2 pi); ``physical_type`` their linear type on the momentum sphere.
    real_equilibrium : bool
        ``False`` for a point of a singular line (``L = +-G``, ``J1 = 0, J2``): the
        whole line is one state and the point is an artefact of the chart (where the
        separatrices meet the line); its chart eigenvalues are not the physical ones.
    H0 : float
        The unperturbed energy at the point.
    closed_form : str
        Text of the closed form of ``(q, p)``, e.g. ``"(2 phi0, J2/2)"``.
    eigenvalues_closed : tuple of 2 complex
        Closed form of ``eigenvalues``.
    """

    chart: str
    q: float
    p: float
    q_closed: float
    p_closed: float
    closed_form: str
    residual: float
    eigenvalues: tuple[complex, complex]
    eigenvalues_closed: tuple[complex, complex]
    linear_type: str
    motions: tuple[PermanentRotation, ...]
    real_equilibrium: bool
    H0: float

    @property
    def physical_type(self) -> str:
        return self.motions[0].linear_type

    @property
    def label(self) -> int:
        """Digit of Fig. 2 (:data:`andoyer.analysis.unperturbed.equilibria.ROTATION_LABELS`)."""
        return self.motions[0].label

    @property
    def motion(self) -> str:
        """E.g. ``"+y, -y"``."""
        return ", ".join(m.name for m in self.motions)


@dataclass(frozen=True)
class FixedPointSet:
    """All fixed points of a reduced unperturbed system, with the permanent rotations.

    Attributes
    ----------
    chart : {"andoyer", "hess"}
    body : RigidBody
    action : float
        ``G0`` (``"andoyer"``) or ``J2`` (``"hess"``).
    period : float
        Range of the angle ``q``: ``[0, period)`` (``2 pi``; ``4 pi`` for the Hess
        double cover).
    points : tuple of FixedPoint
        Sorted by ``(p, q)``.
    rotations : tuple of PermanentRotation
        All six rotations (also those the chart shows as no fixed point).
    """

    chart: str
    body: RigidBody
    action: float
    period: float
    points: tuple[FixedPoint, ...]
    rotations: tuple[PermanentRotation, ...]

    @property
    def names(self) -> tuple[str, str, str]:
        """Storage names ``(q, p, action)``."""
        if self.chart == "andoyer":
            return ("l_angle", "L_action", "G_action")
        return ("theta1", "J1", "J2")

    def by_type(self, linear_type: str) -> tuple[FixedPoint, ...]:
        return tuple(fp for fp in self.points if fp.linear_type == linear_type)

    def to_dataset(self) -> xr.Dataset:
        """The set as a self-describing dataset (dims ``fixed_point``, ``eig``, ``rotation``).

        Examples
        --------
        >>> from andoyer import RigidBody
        >>> ds = hess_fixed_points(RigidBody.paper()).to_dataset()
        >>> ds.sizes["fixed_point"], sorted(set(ds.linear_type.values.tolist()))
        (6, ['centre', 'saddle'])
        """
        qn, pn, an = self.names
        pts = self.points
        ev = np.array([fp.eigenvalues for fp in pts], dtype=complex).reshape(len(pts), 2)
        evc = np.array([fp.eigenvalues_closed for fp in pts],
                       dtype=complex).reshape(len(pts), 2)
        rots = self.rotations
        rev = np.array([r.eigenvalues for r in rots], dtype=complex).reshape(len(rots), 2)
        fp_dim = ("fixed_point",)
        data: dict[str, Any] = {
            qn: (fp_dim, [fp.q for fp in pts]),
            pn: (fp_dim, [fp.p for fp in pts]),
            f"{qn}_closed": (fp_dim, [fp.q_closed for fp in pts]),
            f"{pn}_closed": (fp_dim, [fp.p_closed for fp in pts]),
            "closed_form": (fp_dim, np.array([fp.closed_form for fp in pts], dtype=str)),
            "residual": (fp_dim, [fp.residual for fp in pts]),
            "eig_real": (("fixed_point", "eig"), ev.real),
            "eig_imag": (("fixed_point", "eig"), ev.imag),
            "eig_closed_real": (("fixed_point", "eig"), evc.real),
            "eig_closed_imag": (("fixed_point", "eig"), evc.imag),
            "linear_type": (fp_dim, np.array([fp.linear_type for fp in pts], dtype=str)),
            "physical_type": (fp_dim, np.array([fp.physical_type for fp in pts], dtype=str)),
            "motion": (fp_dim, np.array([fp.motion for fp in pts], dtype=str)),
            "real_equilibrium": (fp_dim, np.array([fp.real_equilibrium for fp in pts])),
            "label": (fp_dim, np.array([fp.label for fp in pts], dtype=np.int64)),
            "H0": (fp_dim, [fp.H0 for fp in pts]),
            "rotation_name": (("rotation",), np.array([r.name for r in rots], dtype=str)),
            "rotation_moment": (("rotation",), np.array([r.moment for r in rots], dtype=str)),
            "rotation_rank": (("rotation",),
                              np.array([r.inertia_rank for r in rots], dtype=str)),
            "rotation_type": (("rotation",),
                              np.array([r.linear_type for r in rots], dtype=str)),
            "rotation_label": (("rotation",),
                               np.array([r.label for r in rots], dtype=np.int64)),
            "rotation_eig_real": (("rotation", "eig"), rev.real),
            "rotation_eig_imag": (("rotation", "eig"), rev.imag),
        }
        chart_eq = "(9)" if self.chart == "andoyer" else "(16) at mu = 0 (after Fig. 3)"
        ds = xr.Dataset(data, coords={"fixed_point": np.arange(len(pts)), "eig": [0, 1],
                                      "rotation": np.arange(len(rots))},
                        attrs=provenance(
                            self.body.with_mu(0.0), engine="scipy.optimize.root (hybr)",
                            equations=f"unperturbed reduced system {chart_eq} of Kyrychenko",
                            chart=self.chart, plane=f"({qn}, {pn})", **{an: self.action},
                            angle_period=self.period, body_mu_given=self.body.mu,
                            label_convention=_LABEL_TEXT))
        units = {"l_angle": "rad", "theta1": "rad"}
        long = {
            qn: f"angle of the fixed point ({'l' if qn == 'l_angle' else 'theta1'})",
            pn: f"action of the fixed point ({'L' if pn == 'L_action' else 'J1'})",
            "closed_form": "closed form of the fixed point",
            "residual": "|field| at the numerical root / field scale",
            "eig_real": "chart Jacobian eigenvalues, real part",
            "eig_imag": "chart Jacobian eigenvalues, imaginary part",
            "eig_closed_real": "closed-form chart eigenvalues, real part",
            "eig_closed_imag": "closed-form chart eigenvalues, imaginary part",
            "linear_type": "linear type from the chart Jacobian",
            "physical_type": "linear type of the physical motion (Euler eqs on |G| = G0)",
            "motion": "permanent rotation(s) the point stands for (G along the axis)",
            "real_equilibrium": "0: artefact of a singular line of the chart (whole line = "
                                "one state)",
            "label": "digit of the uniform rotation in Fig. 2",
            "H0": "unperturbed energy H0",
            "rotation_eig_real": "eigenvalues of the rotation on |G| = G0, real part",
            "rotation_eig_imag": "eigenvalues of the rotation on |G| = G0, imaginary part",
        }
        for name, text in long.items():
            ds[name].attrs.update(long_name=text, units=units.get(name, "1"))
        return ds


_LABEL_TEXT = ("1: rotation about +z (L = +G, J1 = J2), 2: about -z (L = -G, J1 = 0) -- the "
               "rotations the physical-pendulum motions approach; 3: about +-y (l = 0, pi; "
               "theta1 = 2 phi0); 4: about +-x (l = pi/2, 3 pi/2; theta1 = 2 phi0 + pi)")


def _l_closed_forms(body: RigidBody, G0: float
                    ) -> list[tuple[float, float, str, tuple[tuple[str, int], ...], bool]]:
    """Closed-form zeros of (9): ``(l, L, text, motions, on_singular_line)``."""
    pi = math.pi
    pts: list[tuple[float, float, str, tuple[tuple[str, int], ...], bool]] = [
        (0.0, 0.0, "(0, 0)", (("y", +1),), False),
        (pi, 0.0, "(pi, 0)", (("y", -1),), False),
        (pi / 2, 0.0, "(pi/2, 0)", (("x", +1),), False),
        (3 * pi / 2, 0.0, "(3 pi/2, 0)", (("x", -1),), False)]
    a, b, c = body.a, body.b, body.c
    if (b - c) * (c - a) > 0.0:
        lstar = math.asin(math.sqrt((b - c) / (b - a)))
        name = "|phi0|" if body.is_hess else "l*"
        for L, sense, Ltxt in ((G0, +1, "G0"), (-G0, -1, "-G0")):
            for val, txt in ((lstar, name), (pi - lstar, f"pi - {name}"),
                             (pi + lstar, f"pi + {name}"), (2 * pi - lstar, f"2 pi - {name}")):
                pts.append((val, L, f"({txt}, {Ltxt})", (("z", sense),), True))
    return pts


@checks_arguments(ranges={"value": "finite", "period": "time", "phi0": "angle"})
def theta_text(value: float, period: float, phi0: float, lstar: float | None) -> str:
    """Name ``value`` (mod ``period``) as ``k pi + m phi0 (+ n l*)``, simplest first.

    Parameters
    ----------
    value : float
        The angle (rad).
    period : float
        Its period (``2 pi`` or ``4 pi``): values are compared modulo it.
    phi0 : float
        The body's ``phi0`` (rad).
    lstar : float or None
        The angle ``l*`` of the separatrices where they are not ``+-phi0`` (None: not used).
    """
    terms = [("phi0", phi0)] + ([("l*", lstar)] if lstar is not None else [])
    best: tuple[int, str] | None = None
    coeffs = range(-4, 5)
    for k in range(-4, 5):
        for ms in itertools.product(coeffs, repeat=len(terms)):
            v = k * math.pi + sum(m * t for m, (_, t) in zip(ms, terms, strict=True))
            d = (value - v) % period
            if min(d, period - d) > 1e-9:
                continue
            parts = [f"{m} {n}" if m != 1 else n for m, (n, _) in zip(ms, terms, strict=True)
                     if m != 0]
            parts = [p.replace("-1 ", "-") for p in parts]
            if k:
                parts.append({1: "pi", -1: "-pi"}.get(k, f"{k} pi"))
            text = " + ".join(parts).replace("+ -", "- ") or "0"
            # Prefer an expression equal to the value itself, then few terms, k >= 0.
            cost = (100 * (abs(value - v) > 1e-9) + 10 * sum(m != 0 for m in ms) + abs(k)
                    + sum(abs(m) for m in ms) + 2 * (k < 0))
            if best is None or cost < best[0]:
                best = (cost, text)
    return best[1] if best else f"{value:.12g}"


def _closed_forms(body: RigidBody, chart: ReducedChart, action: float, period: float
                  ) -> list[tuple[float, float, str, tuple[tuple[str, int], ...], bool]]:
    """Closed-form fixed points of the chart, merged modulo ``period``."""
    base = _l_closed_forms(body, action)
    if chart == "andoyer":
        return base
    phi0 = body.phi0
    a, b, c = body.a, body.b, body.c
    lstar = None if body.is_hess or (b - c) * (c - a) <= 0 else math.asin(
        math.sqrt((b - c) / (b - a)))
    J2 = action
    merged: list[tuple[float, float, str, tuple[tuple[str, int], ...], bool]] = []
    for l, L, _, motions, line in base:
        theta1 = float(np.mod(2.0 * (l + phi0), period))
        theta1 = 0.0 if period - theta1 < 1e-12 else theta1
        J1 = 0.5 * (J2 + L)
        for i, (t, j, txt, mot, ln) in enumerate(merged):
            d = abs(t - theta1) % period
            if min(d, period - d) < 1e-9 and abs(j - J1) < 1e-12 * J2:
                merged[i] = (t, j, txt, mot + tuple(m for m in motions if m not in mot), ln)
                break
        else:
            jt = {0.0: "0", J2: "J2"}.get(J1, "J2/2")
            merged.append((theta1, J1, f"({theta_text(theta1, period, phi0, lstar)}, {jt})",
                           motions, line))
    return merged


def _roots(field: Callable[..., Any], jac: Callable[..., Any], args: tuple[float, ...],
           period: float, p_lo: float, p_hi: float, n_seed: tuple[int, int],
           scale: NDArray[np.float64]) -> list[tuple[float, float, float]]:
    """All zeros of a planar field on ``[0, period) x [p_lo, p_hi]``.

    Seeds: local minima of ``|field|`` on a grid (periodic in ``q``, the edges
    ``p = p_lo, p_hi`` included); each is polished by :func:`scipy.optimize.root`
    with the analytic Jacobian. Returns ``(q, p, relative residual)``.
    """
    from scipy.optimize import root

    nq, npp = n_seed
    q = np.linspace(0.0, period, nq, endpoint=False)
    p = np.linspace(p_lo, p_hi, npp)
    Q, P = np.meshgrid(q, p, indexing="ij")
    F = np.stack(np.broadcast_arrays(*field(Q, P, *args)), axis=-1) / scale
    norm = np.linalg.norm(F, axis=-1)
    padded = np.pad(norm, ((0, 0), (1, 1)), constant_values=np.inf)
    is_min = np.ones_like(norm, dtype=bool)
    for dq, dp in itertools.product((-1, 0, 1), repeat=2):
        if dq == dp == 0:
            continue
        nb = np.roll(padded, dq, axis=0)[:, 1 + dp: 1 + dp + npp]
        is_min &= norm <= nb

    def fun(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(field(z[0], z[1], *args), dtype=float) / scale

    def dfun(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(jac(z[0], z[1], *args), dtype=float) / scale[:, None]

    span = p_hi - p_lo
    found: list[tuple[float, float, float]] = []
    for q0, p0 in zip(Q[is_min], P[is_min], strict=True):
        sol = root(fun, np.array([q0, p0]), jac=dfun, method="hybr",
                   options={"xtol": 1e-15})
        qq, pp = float(sol.x[0]), float(sol.x[1])
        if not (p_lo - 1e-9 * span <= pp <= p_hi + 1e-9 * span):
            continue
        pp = min(max(pp, p_lo), p_hi)
        res = float(np.linalg.norm(fun(np.array([qq, pp]))))
        if res > ROOT_RTOL:
            continue
        qq = float(np.mod(qq, period))
        qq = 0.0 if period - qq < 1e-12 else qq
        dup = False
        for k, (qf, pf, rf) in enumerate(found):
            d = abs(qf - qq) % period
            if min(d, period - d) < MERGE_RTOL * period and abs(pf - pp) < MERGE_RTOL * span:
                if res < rf:
                    found[k] = (qq, pp, res)
                dup = True
                break
        if not dup:
            found.append((qq, pp, res))
    return found


def _fixed_points(body: RigidBody, chart: ReducedChart, action: float, period: float,
                  n_seed: tuple[int, int]) -> FixedPointSet:
    require_distinct_moments(body)
    H0, field, jac = _reduced(chart)
    phi0 = body.phi0 if chart == "hess" else 0.0
    args = (action, body.a, body.b, body.c, phi0)
    p_lo, p_hi = (-action, action) if chart == "andoyer" else (0.0, action)
    smax = max(body.a, body.b, body.c)
    # dq/dt ~ smax * action, dp/dt ~ smax * action^2 in both charts.
    scale = np.array([smax * action, smax * action**2])
    roots = _roots(field, jac, args, period, p_lo, p_hi, n_seed, scale)
    closed = _closed_forms(body, chart, action, period)
    rotations = permanent_rotations(body, action)
    by_key = {(r.axis, r.sense): r for r in rotations}
    span = p_hi - p_lo
    points = []
    unmatched = list(range(len(closed)))
    for qq, pp, res in roots:
        best = None
        for i in unmatched:
            qc, pc = closed[i][0], closed[i][1]
            d = abs(qq - qc) % period
            if min(d, period - d) < MERGE_RTOL * period and abs(pp - pc) < MERGE_RTOL * span:
                best = i
                break
        if best is None:
            raise RuntimeError(
                f"numerical fixed point ({qq:.12g}, {pp:.12g}) of the {chart} chart has no "
                "closed form: the derivation and the numerics disagree")
        unmatched.remove(best)
        qc, pc, text, motion_keys, line = closed[best]
        J = np.asarray(jac(qq, pp, *args), dtype=float)
        ev = np.linalg.eigvals(J)
        motions = tuple(by_key[k] for k in motion_keys)
        if line:
            lam = 2.0 * body.sigma * action
            ev_closed = (complex(-lam), complex(lam))
        else:
            ev_closed = motions[0].eigenvalues_closed
        points.append(FixedPoint(
            chart=chart, q=qq, p=pp, q_closed=qc, p_closed=pc, closed_form=text, residual=res,
            eigenvalues=sorted_eigenvalues(ev),  # type: ignore[arg-type]
            eigenvalues_closed=sorted_eigenvalues(np.array(ev_closed)),  # type: ignore[arg-type]
            linear_type=classify(ev, float(scale[0])), motions=motions,
            real_equilibrium=not line, H0=float(H0(qq, pp, *args))))
    if unmatched:
        missing = ", ".join(closed[i][2] for i in unmatched)
        raise RuntimeError(f"closed-form fixed points {missing} of the {chart} chart were not "
                           "found numerically; refine n_seed")
    points.sort(key=lambda fp: (round(fp.p / action, 9), fp.q))
    return FixedPointSet(chart=chart, body=body, action=action, period=period,
                         points=tuple(points), rotations=rotations)


def _n_seed(n_seed: Any) -> tuple[int, int]:
    if isinstance(n_seed, numbers.Real) and not isinstance(n_seed, bool):
        k = integer("n_seed", n_seed, 1, 100_000)
        nq, npp = k, k // 2 + 1
    elif isinstance(n_seed, tuple | list) and len(n_seed) == 2:
        nq = integer("n_seed[0] (n_angle)", n_seed[0], 1, 100_000)
        npp = integer("n_seed[1] (n_action)", n_seed[1], 1, 100_000)
    else:
        raise ValueError(f"n_seed must be an int or a pair (n_angle, n_action), got "
                         f"{n_seed!r}")
    if nq < 8 or npp < 3:
        raise ValueError(f"n_seed = {n_seed!r} is too coarse: use at least (8, 3)")
    return nq, npp


@checks_body(ranges={"G0": "length"}, closed_form=CLOSED_FORM)
def andoyer_fixed_points(body: RigidBody, G0: float = 1.0, *,
                         n_seed: int | tuple[int, int] = (64, 33)) -> FixedPointSet:
    """All fixed points of the unperturbed system (9) in ``(l, L)`` at fixed ``G = G0``.

    Parameters
    ----------
    body : RigidBody
        Three distinct moments (``mu``, ``r`` ignored: ``mu = 0``).
    G0 : float
        Length of the angular momentum (> 0).
    n_seed : int or (int, int)
        Seed grid ``(n_l, n_L)`` for the root search (``L = +-G0`` included).

    Returns
    -------
    FixedPointSet
        Points in ``l in [0, 2 pi)``, ``L in [-G0, G0]``, each matched with its closed
        form (module notes); raises ``RuntimeError`` if numerics and closed forms
        disagree.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> fps = andoyer_fixed_points(RigidBody.paper())
    >>> len(fps.points), len(fps.by_type("centre")), sum(fp.real_equilibrium
    ...                                                  for fp in fps.points)
    (12, 4, 4)
    """
    G0 = _positive("G0", G0, maximum=MAX_ACTION)
    return _fixed_points(body, "andoyer", G0, math.tau, _n_seed(n_seed))


@checks_body(ranges={"J2": "action"}, closed_form=CLOSED_FORM)
def hess_fixed_points(body: RigidBody, J2: float = 1.0, *, double_cover: bool = False,
                      n_seed: int | tuple[int, int] = (64, 33)) -> FixedPointSet:
    """All fixed points of the unperturbed Hess-chart system in ``(theta1, J1)``, ``M = 0``.

    Parameters
    ----------
    body : RigidBody
        Three distinct moments and ``e3 = 0`` (for ``phi0``); ``mu`` ignored.
    J2 : float
        ``J2 = G > 0``.
    double_cover : bool
        ``theta1 in [0, 4 pi)`` (every physical state once) instead of the paper's
        ``[0, 2 pi)`` (where ``l`` and ``l + pi`` coincide).
    n_seed : int or (int, int)
        Seed grid ``(n_theta1, n_J1)``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> fps = hess_fixed_points(RigidBody.paper())
    >>> [(fp.closed_form, fp.linear_type, fp.motion) for fp in fps.points][:2]
    [('(0, 0)', 'saddle', '-z'), ('(4 phi0, 0)', 'saddle', '-z')]
    """
    J2 = _positive("J2", J2, maximum=MAX_ACTION)
    period = 2.0 * math.tau if double_cover else math.tau
    nq, npp = _n_seed(n_seed)
    return _fixed_points(body, "hess", J2, period, (nq * (2 if double_cover else 1), npp))
