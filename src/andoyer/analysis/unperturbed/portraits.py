"""Phase portraits of the unperturbed system: level sets of H0 in (l, L) (Eq. (9), Fig. 1)
and in the Hess chart (theta1, J1) (Fig. 2), with the separatrices of
:mod:`andoyer.analysis.unperturbed.separatrix` and the fixed points.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from andoyer.analysis.unperturbed.separatrix import (
    FIG2_CAPTION,
    SEPARATRIX_LEVEL,
    check_grid_size,
    separatrix_curves,
    separatrix_energy,
)
from andoyer.body import RigidBody, checks_body
from andoyer.integrate.results import provenance, values_from_attrs
from andoyer.validation import MAX_ACTION
from andoyer.validation import positive as _positive

__all__ = ["portrait_andoyer", "portrait_hess"]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True


# ---------------------------------------------------------------------- portraits
def _grid_n(n: Any) -> tuple[int, int]:
    if np.ndim(n) == 0:
        k = check_grid_size(n, "n")
        return k, k // 2 + 1
    try:
        nq, npp = n
    except (TypeError, ValueError):
        raise ValueError(f"n must be an int or a pair (n_angle, n_action), got {n!r}") from None
    return check_grid_size(nq, "n[0]"), check_grid_size(npp, "n[1]", 3)


def _portrait(body: RigidBody, chart: str, action: float, n: Any, n_levels: int,
              n_curve: int, double_cover: bool) -> xr.Dataset:
    from andoyer.analysis.unperturbed.equilibria import ROTATION_LABELS
    from andoyer.analysis.unperturbed.fixed_points import andoyer_fixed_points, hess_fixed_points
    from andoyer.dynamics import hamiltonian

    nq, npp = _grid_n(n)
    n_levels = check_grid_size(n_levels, "n_levels", 2)
    body0 = body.with_mu(0.0)
    if chart == "hess":
        body.require_planar("the Hess chart")
        period = 2.0 * math.tau if double_cover else math.tau
        qn, pn, an = "theta1", "J1", "J2"
        p_lo, p_hi = 0.0, action
        fps = hess_fixed_points(body, action, double_cover=double_cover)
    else:
        period = math.tau
        qn, pn, an = "l_angle", "L_action", "G_action"
        p_lo, p_hi = -action, action
        fps = andoyer_fixed_points(body, action)
    q = np.linspace(0.0, period, nq)
    p = np.linspace(p_lo, p_hi, npp)
    Q, P = np.meshgrid(q, p)  # (p, q): rows are actions
    zeros = np.zeros_like(Q)
    act = np.full_like(Q, action)
    x = np.stack([Q, zeros, P, act, zeros], axis=-1)
    H0 = hamiltonian(body0, x, "hess" if chart == "hess" else "andoyer")

    h_sep = separatrix_energy(body, action)
    lo, hi = float(H0.min()), float(H0.max())
    regular = lo + (hi - lo) * (np.arange(n_levels) + 0.5) / n_levels
    regular = regular[np.abs(regular - h_sep) > 0.02 * (hi - lo)]
    # The saddles' energies (equal to h_sep to round-off; kept if ever they are not).
    tol = 1e-12 * max(abs(hi), 1.0)
    saddle_H = [fp.H0 for fp in fps.points
                if fp.linear_type == "saddle" and abs(fp.H0 - h_sep) > tol]
    levels = np.unique(np.concatenate([regular, [h_sep], saddle_H]))
    is_sep = np.isclose(levels, h_sep, rtol=0.0, atol=tol)

    curves = separatrix_curves(body, chart, action, period, n_curve)
    pts = fps.points
    ds = curves.copy()
    ds = ds.assign_coords({qn: q, pn: p, "level": np.arange(len(levels)),
                           "fixed_point": np.arange(len(pts))})
    ds["H0"] = ((pn, qn), H0)
    ds["levels"] = (("level",), levels)
    ds["level_is_separatrix"] = (("level",), is_sep)
    ev = np.array([fp.eigenvalues for fp in pts], dtype=complex).reshape(len(pts), 2)
    ds[f"fp_{qn}"] = (("fixed_point",), np.array([fp.q for fp in pts]))
    ds[f"fp_{pn}"] = (("fixed_point",), np.array([fp.p for fp in pts]))
    ds["fp_type"] = (("fixed_point",), np.array([fp.linear_type for fp in pts], dtype=str))
    ds["fp_physical_type"] = (("fixed_point",),
                              np.array([fp.physical_type for fp in pts], dtype=str))
    ds["fp_motion"] = (("fixed_point",), np.array([fp.motion for fp in pts], dtype=str))
    ds["fp_real"] = (("fixed_point",), np.array([fp.real_equilibrium for fp in pts]))
    ds["fp_label"] = (("fixed_point",), np.array([fp.label for fp in pts], dtype=np.int64))
    ds["fp_H0"] = (("fixed_point",), np.array([fp.H0 for fp in pts]))
    ds["fp_closed_form"] = (("fixed_point",), np.array([fp.closed_form for fp in pts],
                                                        dtype=str))
    ds["fp_eig_real"] = (("fixed_point", "eig"), ev.real)
    ds["fp_eig_imag"] = (("fixed_point", "eig"), ev.imag)
    ds[f"singular_{pn}"] = (("singular_line",), np.array([p_lo, p_hi]))

    # Where the digits 1-4 go: 1, 2 on the singular lines (+z at the top, -z at the
    # bottom) above/below the last regular point (off the separatrices), 3, 4 just above
    # each regular fixed point.
    span = p_hi - p_lo
    regular_q = [fp.q for fp in pts if fp.real_equilibrium]
    q12 = regular_q[-1] if regular_q else period / 2.0
    ann_q: list[float] = [q12, q12]
    ann_p: list[float] = [p_hi - 0.02 * span, p_lo + 0.02 * span]
    ann_t: list[str] = [str(ROTATION_LABELS[("z", +1)]), str(ROTATION_LABELS[("z", -1)])]
    ann_va: list[str] = ["top", "bottom"]
    for fp in pts:
        if fp.real_equilibrium:
            ann_q.append(fp.q)
            ann_p.append(fp.p + 0.03 * span)
            ann_t.append(str(fp.label))
            ann_va.append("bottom")
    ds[f"annotation_{qn}"] = (("annotation",), np.array(ann_q))
    ds[f"annotation_{pn}"] = (("annotation",), np.array(ann_p))
    ds["annotation_text"] = (("annotation",), np.array(ann_t, dtype=str))
    ds["annotation_va"] = (("annotation",), np.array(ann_va, dtype=str))

    sym = {"l_angle": "$l$", "L_action": "$L$", "theta1": r"$\theta_1$", "J1": "$J_1$"}
    ds[qn].attrs.update(long_name=f"angle {qn}", units="rad", symbol=sym[qn],
                        equation="(5)-(6)" if chart == "andoyer" else "(14)")
    ds[pn].attrs.update(long_name=f"action {pn}", units="1", symbol=sym[pn],
                        equation="(5)" if chart == "andoyer" else "(14)")
    ds["H0"].attrs.update(long_name="unperturbed Hamiltonian H0 (mu = 0)", units="1",
                          symbol="H_0", equation="(12)-(13)" if chart == "andoyer" else
                          "(16) at mu = 0")
    ds["levels"].attrs.update(long_name="contour levels of H0 (the separatrix level "
                                        "included)", units="1")
    ds["fp_type"].attrs.update(long_name="linear type from the chart Jacobian")
    ds["fp_real"].attrs.update(long_name="0: point of a singular line (chart artefact)")
    ds["fp_label"].attrs.update(long_name="digit of the uniform rotation (Fig. 2)")
    eq = "(9)" if chart == "andoyer" else "unperturbed system after Fig. 3"
    ds.attrs = provenance(
        body0, engine="closed form + scipy.optimize.root", chart=chart,
        equations=f"unperturbed reduced system {eq} of Kyrychenko",
        plane_x=qn, plane_y=pn, x_label=sym[qn], y_label=sym[pn], **{an: action},
        angle_period=period, separatrix_H0=h_sep, body_mu_given=body.mu,
        is_hess=int(body.is_hess), caption=FIG2_CAPTION,
        label_convention=("1: rotation about +z (L = G, J1 = J2); 2: about -z (L = -G, "
                          "J1 = 0) -- the rotations the pendulum motions approach; 3: about "
                          "+-y; 4: about +-x"))
    return values_from_attrs(ds, SEPARATRIX_LEVEL)


@checks_body(ranges={"G0": "length", "n_levels": "count", "n_curve": "count"},
             closed_form=CLOSED_FORM)
def portrait_andoyer(body: RigidBody, G0: float = 1.0, n: int | tuple[int, int] = (241, 121),
                     *, n_levels: int = 14, n_curve: int = 201) -> xr.Dataset:
    """Everything Fig. 1 / Fig. 2(a) need: the unperturbed portrait of (9) in ``(l, L)``.

    Parameters
    ----------
    body : RigidBody
        Three distinct moments (``mu`` ignored: ``mu = 0``).
    G0 : float
        Length of the angular momentum.
    n : int or (int, int)
        Grid ``(n_l, n_L)`` for H0 over ``[0, 2 pi] x [-G0, G0]``.
    n_levels : int
        Number of ordinary contour levels (the separatrix level is added).
    n_curve : int
        Points per separatrix curve.

    Returns
    -------
    xarray.Dataset
        ``H0`` (L_action, l_angle); ``levels``, ``level_is_separatrix``; the separatrix
        curves (:func:`separatrix_andoyer`); the fixed points ``fp_*`` with their chart
        and physical types and Fig. 2 digits; ``singular_L_action``; the digit
        positions ``annotation_*``; attrs ``caption``, ``label_convention``,
        ``plane_x``/``plane_y``, axis labels and provenance.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = portrait_andoyer(RigidBody.paper(), n=(33, 17), n_curve=11)
    >>> bool(ds.level_is_separatrix.any()), int(ds.sizes["fixed_point"])
    (True, 12)
    """
    G0 = _positive("G0", G0, maximum=MAX_ACTION)
    return _portrait(body, "andoyer", G0, n, n_levels, check_grid_size(n_curve, "n_curve"), False)


@checks_body(ranges={"J2": "action", "n_levels": "count", "n_curve": "count"},
             closed_form=CLOSED_FORM)
def portrait_hess(body: RigidBody, J2: float = 1.0, n: int | tuple[int, int] = (241, 81), *,
                  n_levels: int = 14, n_curve: int = 201,
                  double_cover: bool = False) -> xr.Dataset:
    """Everything Fig. 2(b) needs: the unperturbed portrait in ``(theta1, J1)``, ``M = 0``.

    As :func:`portrait_andoyer` with ``theta1 in [0, 2 pi]`` (``[0, 4 pi]`` with
    ``double_cover``), ``J1 in [0, J2]``.

    Parameters
    ----------
    body : RigidBody
        Three distinct moments with Oz the middle axis (``mu`` ignored: ``mu = 0``).
    J2 : float, default 1.0
        ``J2 = |G|`` of the level.
    n : int or (int, int), default (241, 81)
        Grid ``(n_theta1, n_J1)`` for H0 over the plane.
    n_levels : int, default 14
        Number of ordinary contour levels (the separatrix level is added).
    n_curve : int, default 201
        Points per separatrix curve.
    double_cover : bool, default False
        ``theta1`` over ``[0, 4 pi]`` (both sheets) instead of ``[0, 2 pi]``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = portrait_hess(RigidBody.paper(), n=(33, 9), n_curve=11)
    >>> sorted(ds.fp_closed_form.values.tolist())[:3]
    ['(0, 0)', '(0, J2)', '(2 phi0 + pi, J2/2)']
    """
    J2 = _positive("J2", J2, maximum=MAX_ACTION)
    return _portrait(body, "hess", J2, n, n_levels, check_grid_size(n_curve, "n_curve"),
                     double_cover)
