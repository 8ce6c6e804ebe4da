"""The heavy rigid body about a fixed point.

A body is given by its principal moments of inertia ``A, B, C`` about the fixed
point, by ``mu`` -- the product of its weight and the distance from the fixed point
to the centre of mass -- and by the unit vector ``r = (e1, e2, e3)`` pointing from
the fixed point to the centre of mass in the principal axes (Eq. (1) of [1]_).

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import functools
import inspect
import math
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, ParamSpec, TypeVar, overload

import numpy as np

from andoyer.errors import ArgumentTypeError
from andoyer.validation import checks_arguments, real_array
from andoyer.validation import finite as _finite

__all__ = ["RigidBody", "PAPER_BODY", "PAPER", "Preset", "PRESETS", "make_body", "checks_body"]

#: The paper's body (Fig. 3 of Kyrychenko): a Hess body, its moments and mu -- the one
#: place these numbers are written (``RigidBody.paper``, the scan configs' defaults).
PAPER = {"A": 2.5, "B": 2.0, "C": 2.2, "mu": 0.01}

#: Relative tolerance used to decide whether a body satisfies the Hess conditions (2).
HESS_RTOL = 1e-12


def _finite_positive(name: str, value: float) -> float:
    if isinstance(value, bool | str | bytes):  # float(True), float("2") hide a wrong argument
        raise ValueError(f"{name} must be a real number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite positive moment of inertia, got {v!r}")
    return v


@dataclass(frozen=True)
class RigidBody:
    """A heavy rigid body with a fixed point.

    Parameters
    ----------
    A, B, C : float
        Principal moments of inertia about the fixed point (positive, finite, obeying
        the triangle inequalities ``A <= B + C`` etc.).
    mu : float, default 0
        Weight times the distance from the fixed point to the centre of mass
        (``mu >= 0``). ``mu = 0`` is the Euler-Poinsot case.
    r : sequence of 3 floats, default (1, 0, 0)
        Direction of the centre of mass in the principal axes. It is normalised:
        its length is discarded, the distance is already inside ``mu``.
    name : str, optional
        A label carried into the provenance of results.

    Notes
    -----
    The Hamiltonian is :math:`H = \\tfrac12 (\\mathbf G, \\mathbf I^{-1}\\mathbf G) + \\mu
    (\\mathbf r, \\boldsymbol\\gamma)` with :math:`\\mathbf I^{-1} = \\mathrm{diag}(a, b, c)
    = \\mathrm{diag}(1/A, 1/B, 1/C)`, Eq. (1) of the paper.

    Examples
    --------
    >>> body = RigidBody.hess(2.5, 2.0, 2.2, mu=0.01)
    >>> body.is_hess
    True
    >>> round(body.kappa, 6)
    -0.1
    """

    A: float
    B: float
    C: float
    mu: float = 0.0
    r: tuple[float, float, float] = (1.0, 0.0, 0.0)
    name: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        A = _finite_positive("A", self.A)
        B = _finite_positive("B", self.B)
        C = _finite_positive("C", self.C)
        # Triangle inequalities of a real mass distribution (equality: a flat body).
        tol = 1e-12 * (A + B + C)
        for x, y, z, nx in ((A, B, C, "A <= B + C"), (B, C, A, "B <= C + A"),
                            (C, A, B, "C <= A + B")):
            if x > y + z + tol:
                raise ValueError(
                    f"moments A={A}, B={B}, C={C} violate the triangle inequality {nx}: "
                    "no mass distribution has them")
        if isinstance(self.mu, bool):  # float(True) = 1.0 would hide a wrong argument
            raise ValueError(f"mu must be a real number, got {self.mu!r}")
        try:
            mu = float(self.mu)
        except (TypeError, ValueError):
            raise ValueError(f"mu must be a real number, got {self.mu!r}") from None
        if not math.isfinite(mu) or mu < 0.0:
            raise ValueError(
                f"mu (weight x distance to the centre of mass) must be finite and >= 0, "
                f"got {mu!r}")
        if not isinstance(self.name, str):
            raise ValueError(f"name must be a string, got {self.name!r}")
        r = real_array("r", self.r)
        if r.shape != (3,) or not np.all(np.isfinite(r)):
            raise ValueError(f"r must be 3 finite numbers (e1, e2, e3), got {self.r!r}")
        norm = float(np.linalg.norm(r))
        if norm == 0.0:
            if mu > 0.0:
                raise ValueError("r = (0, 0, 0) with mu > 0: the centre of mass direction "
                                 "is undefined; give a non-zero r or mu = 0")
            r = np.array([1.0, 0.0, 0.0])
            norm = 1.0
        r = r / norm
        object.__setattr__(self, "A", A)
        object.__setattr__(self, "B", B)
        object.__setattr__(self, "C", C)
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "r", (float(r[0]), float(r[1]), float(r[2])))

    # ------------------------------------------------------------------ properties
    @property
    def a(self) -> float:
        """Inverse moment ``1/A`` (the paper's a)."""
        return 1.0 / self.A

    @property
    def b(self) -> float:
        """Inverse moment ``1/B`` (the paper's b)."""
        return 1.0 / self.B

    @property
    def c(self) -> float:
        """Inverse moment ``1/C`` (the paper's c)."""
        return 1.0 / self.C

    @property
    def e1(self) -> float:
        return self.r[0]

    @property
    def e2(self) -> float:
        return self.r[1]

    @property
    def e3(self) -> float:
        return self.r[2]

    @property
    def is_hess(self) -> bool:
        """Whether the body satisfies the Hess conditions (2) (paper's axis order).

        ``A > C > B``, ``e3 = 0`` and ``(c - b) e1^2 = (a - c) e2^2`` (Eq. (8)),
        to relative tolerance ``HESS_RTOL``.
        """
        if not (self.A > self.C > self.B):
            return False
        if abs(self.e3) > HESS_RTOL:
            return False
        lhs = (self.c - self.b) * self.e1**2
        rhs = (self.a - self.c) * self.e2**2
        return abs(lhs - rhs) <= HESS_RTOL * (abs(lhs) + abs(rhs) + 1e-300)

    @property
    def phi0(self) -> float:
        """Angle of the centre of mass in the G1-G2 plane, ``e1 = cos phi0, e2 = sin phi0``.

        Eq. (11). For a Hess body ``tan^2 phi0 = (c - b)/(a - c)``; the paper's branch
        gives ``phi0`` in (0, pi/2), the other branch (``branch=-1``) in (-pi/2, 0).
        Defined for any body with ``e3 = 0`` (it is the parameter of the Hess chart (14)).
        """
        self.require_planar("phi0")
        return math.atan2(self.e2, self.e1)

    @property
    def kappa(self) -> float:
        """``kappa = (a - c)/e1^2``, equal to ``a - b`` on a Hess body (after Eq. (13))."""
        return self.a - self.b

    @property
    def sigma(self) -> float:
        """``sigma = sqrt((b - c)(c - a))``: the exponent of the permanent rotation about z
        is ``sigma G`` when z is the middle axis of inertia; NaN when it is not.

        >>> round(RigidBody.paper().sigma, 12)
        0.049792959773
        """
        prod = (self.b - self.c) * (self.c - self.a)
        return math.sqrt(prod) if prod > 0.0 else math.nan

    def require_planar(self, what: str) -> None:
        """``ValueError`` naming ``what`` unless the centre of mass is in the G1-G2 plane."""
        if abs(self.e3) > HESS_RTOL:
            raise ValueError(
                f"{what} needs the centre of mass in the G1-G2 principal plane (e3 = 0), "
                f"but e3 = {self.e3!r}; build the body with RigidBody.hess(...) or r=(e1, e2, 0)")

    def require_hess(self, what: str) -> None:
        """``ValueError`` naming ``what`` unless the body satisfies the Hess conditions (2).

        >>> body = RigidBody(2.5, 2.0, 2.2, 0.01, (1.0, 0.0, 0.0))
        >>> body.require_hess("the demo")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        ValueError: the demo needs a Hess body: the Hess conditions (2) ...
        """
        if not self.is_hess:
            raise ValueError(
                f"{what} needs a Hess body: the Hess conditions (2) A > C > B, e3 = 0 and "
                "(c - b) e1^2 = (a - c) e2^2 must hold (then the heteroclinic lines are "
                "theta1 = 0 and theta1 = 4 phi0); build it with RigidBody.hess(A, B, C, mu); "
                f"got A={self.A}, B={self.B}, C={self.C}, r={self.r}")

    def require_middle_axis(self, what: str) -> float:
        """:attr:`sigma`, or ``ValueError`` naming ``what`` unless C is the middle moment
        (the rotation about Oz a saddle, ``(b - c)(c - a) > 0``)."""
        if not self.sigma > 0.0:
            prod = (self.b - self.c) * (self.c - self.a)
            raise ValueError(
                f"{what} needs Oz to be the middle axis of inertia (C the middle moment of "
                f"inertia, the rotation about Oz a saddle); got A={self.A}, B={self.B}, "
                f"C={self.C} ((b - c)(c - a) = {prod:.3g} <= 0)")
        return self.sigma

    def with_mu(self, mu: float) -> RigidBody:
        """The same body with another ``mu`` (useful for mu -> 0 continuation)."""
        return RigidBody(self.A, self.B, self.C, mu, self.r, self.name)

    @property
    def params(self) -> tuple[float, float, float, float, float, float, float]:
        """``(a, b, c, mu, e1, e2, e3)``: the body as the plain floats kernels take."""
        return (self.a, self.b, self.c, self.mu, self.e1, self.e2, self.e3)

    @property
    def engine_params(self) -> tuple[float, float, float, float, float, float, float, float]:
        """``(a, b, c, mu, e1, e2, e3, phi0)``: what the integration engines take.

        ``phi0`` (11) enters only the Hess-chart section functions; it is 0.0 for a body
        whose centre of mass is off the G1-G2 plane (there the Hess chart does not apply).
        """
        phi0 = self.phi0 if abs(self.e3) <= 1e-12 else 0.0
        return (*self.params, phi0)

    def attrs(self) -> dict[str, float | str]:
        """The body as flat attributes for self-describing datasets."""
        return {"body_name": self.name, "A": self.A, "B": self.B, "C": self.C,
                "mu": self.mu, "e1": self.e1, "e2": self.e2, "e3": self.e3,
                "is_hess": int(self.is_hess)}

    # ------------------------------------------------------------------ presets
    @classmethod
    def hess(cls, A: float, B: float, C: float, mu: float = 0.0, branch: int = 1,
             name: str = "hess") -> RigidBody:
        """A body of Hess conditions (2): ``A > C > B``, ``e3 = 0``.

        ``e1 = cos phi0``, ``e2 = branch * sin phi0`` with
        ``tan^2 phi0 = (c - b)/(a - c) = A (C - B) / (B (A - C))``.

        Parameters
        ----------
        A, B, C : float
            Principal moments with ``A > C > B``.
        mu : float, default 0
            Weight times distance to the centre of mass (``mu >= 0``).
        branch : {+1, -1}
            Sign choice in (2); +1 gives the paper's ``phi0`` in (0, pi/2).
        name : str, default "hess"
            A label carried into the provenance of results.

        Examples
        --------
        >>> round(RigidBody.hess(A=2.5, B=2.0, C=2.2, mu=0.01).phi0, 6)
        0.739881
        """
        A = _finite_positive("A", A)
        B = _finite_positive("B", B)
        C = _finite_positive("C", C)
        if not (A > C > B):
            raise ValueError(
                f"the Hess conditions (2) need A > C > B, got A={A}, B={B}, C={C}; "
                "order the principal axes so that C is the middle moment")
        if isinstance(branch, bool) or not isinstance(branch, numbers.Real) \
                or branch not in (1, -1):  # True == 1 would pass for a branch
            raise ValueError(f"branch must be +1 or -1, got {branch!r}")
        branch = int(branch)
        phi0 = math.atan(math.sqrt(A * (C - B) / (B * (A - C))))
        return cls(A, B, C, mu, (math.cos(phi0), branch * math.sin(phi0), 0.0), name)

    @classmethod
    def near_hess(cls, A: float, B: float, C: float, mu: float = 0.0, epsilon: float = 0.0,
                  e3: float = 0.0, branch: int = 1, name: str = "near-hess") -> RigidBody:
        """A Hess body whose centre of mass is turned by ``epsilon`` in the (e1, e2) plane
        off the Hess direction ``phi0`` and lifted by ``e3``.

        ``r = (sqrt(1 - e3^2) cos(phi), sqrt(1 - e3^2) sin(phi), e3)`` with
        ``phi = branch * phi0 + epsilon``; ``epsilon = e3 = 0`` is :meth:`hess`.

        What becomes of the Hess relation (3): for any centre of mass in the (e1, e2)
        plane, with ``n = (-e2, e1, 0)``, Euler's equations give exactly

            d(G, r)/dt = G3 [ (a - b) e1 e2 (G, r) + kappa_H (G, n) ],
            kappa_H = (c - b) e1^2 - (a - c) e2^2 = :attr:`hess_defect`

        (the potential does not enter: ``r . (gamma x r) = 0``). On a Hess body
        ``kappa_H = 0`` and (3) is invariant; off it, ``(G, r)`` is driven by ``(G, n)`` at
        a rate ``kappa_H = -(a - b) sin(2 phi0) epsilon + O(epsilon^2) = 2 sigma epsilon +
        O(epsilon^2)`` (branch +1, ``sin 2 phi0 = 2 sigma / (b - a)``), so an orbit
        started on ``(G, r) = 0`` leaves it linearly in time (``e3 != 0`` adds
        ``e3 (b - a) G1 G2``).

        Parameters
        ----------
        A, B, C : float
            Principal moments with ``A > C > B`` (those of the Hess body turned).
        mu : float, default 0
            Weight times distance to the centre of mass (``mu >= 0``).
        epsilon : float, default 0
            Turn of the centre of mass off the Hess direction in the (e1, e2) plane
            (radians).
        e3 : float, default 0
            Component of the unit vector ``r`` along the third axis, in (-1, 1).
        branch : {+1, -1}
            Sign choice in (2) of the Hess body turned (:meth:`hess`).
        name : str, default "near-hess"
            A label carried into the provenance of results.

        Examples
        --------
        >>> body = RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.01, epsilon=0.0)
        >>> body.is_hess, abs(body.hess_defect) < 1e-15
        (True, True)
        >>> round(RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.01, epsilon=1e-3).hess_defect, 9)
        9.9595e-05
        """
        base = cls.hess(A, B, C, mu, branch)
        eps = _finite("epsilon", epsilon)
        z = _finite("e3", e3)
        if not abs(z) < 1.0:
            raise ValueError(f"e3 must lie in (-1, 1) (a unit vector r), got {e3!r}")
        phi = math.atan2(base.e2, base.e1) + eps
        rho = math.sqrt(1.0 - z * z)
        return cls(base.A, base.B, base.C, base.mu,
                   (rho * math.cos(phi), rho * math.sin(phi), z), name)

    @property
    def hess_defect(self) -> float:
        """``kappa_H = (c - b) e1^2 - (a - c) e2^2``: zero exactly when the centre of mass
        satisfies the Hess condition (8); the rate at which ``(G, n)`` drives ``(G, r)``
        (see :meth:`near_hess`)."""
        return (self.c - self.b) * self.e1**2 - (self.a - self.c) * self.e2**2

    def nearest_hess(self) -> RigidBody:
        """The Hess body of the same moments and ``mu`` whose centre of mass is nearest
        this one's (the branch of (2) with ``phi0`` nearer :attr:`phi0`); ``self`` if the
        body is Hess.

        Its chart (14) and its heteroclinic lines ``theta1 = 0``, ``4 phi0`` describe the
        unperturbed (``mu = 0``) motion of every body with these moments, since the
        Euler-Poinsot flow does not see ``r``. ``ValueError`` unless the centre of mass is
        in the (e1, e2) plane and ``A > C > B``.

        >>> b = RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.01, epsilon=0.05)
        >>> b.nearest_hess().is_hess, round(b.hess_epsilon, 12)
        (True, 0.05)
        """
        if self.is_hess:
            return self
        self.require_planar("the nearest Hess body")
        twins = [RigidBody.hess(self.A, self.B, self.C, self.mu, branch=s, name=self.name)
                 for s in (1, -1)]
        return min(twins, key=lambda t: abs(math.remainder(self.phi0 - t.phi0, math.tau)))

    @property
    def hess_epsilon(self) -> float:
        """The turn ``epsilon`` in ``(-pi, pi]`` of the centre of mass off the nearest Hess
        direction (:meth:`nearest_hess`): ``phi0 - phi0_H``; 0 on a Hess body. In the Hess
        chart of this body the former Hess separatrix ``l = -phi0_H`` sits at
        ``theta1 = 2 epsilon``."""
        return float(math.remainder(self.phi0 - self.nearest_hess().phi0, math.tau))

    @classmethod
    def paper(cls, mu: float = PAPER["mu"]) -> RigidBody:
        """The paper's body: Hess, A = 2.5, B = 2.0, C = 2.2, mu = 0.01 (Fig. 3).

        Parameters
        ----------
        mu : float, default 0.01
            Weight times distance to the centre of mass (``mu >= 0``; the paper's 0.01).

        Examples
        --------
        >>> RigidBody.paper(mu=0.05).mu
        0.05
        """
        return cls.hess(PAPER["A"], PAPER["B"], PAPER["C"], mu, name="paper")

    @classmethod
    def euler_poinsot(cls, A: float, B: float, C: float) -> RigidBody:
        """Free rigid body (``mu = 0``): the Euler-Poinsot case.

        Parameters
        ----------
        A, B, C : float
            Principal moments of inertia (positive).

        Examples
        --------
        >>> RigidBody.euler_poinsot(A=2.5, B=2.0, C=2.2).mu
        0.0
        """
        return cls(A, B, C, 0.0, (1.0, 0.0, 0.0), "euler_poinsot")

    @classmethod
    def lagrange(cls, A: float, C: float, mu: float) -> RigidBody:
        """Lagrange top: ``A = B``, centre of mass on the symmetry axis 3.

        Parameters
        ----------
        A : float
            Equatorial moment of inertia (``A = B``, positive).
        C : float
            Moment about the symmetry axis 3 (positive).
        mu : float
            Weight times the distance of the centre of mass from the fixed point, along
            the symmetry axis (``mu >= 0``).

        Examples
        --------
        >>> top = RigidBody.lagrange(A=1.0, C=0.6, mu=1.0)
        >>> (top.A, top.B, top.C, top.r)
        (1.0, 1.0, 0.6, (0.0, 0.0, 1.0))
        """
        return cls(A, A, C, mu, (0.0, 0.0, 1.0), "lagrange")

    @classmethod
    def kovalevskaya(cls, C: float = 1.0, mu: float = 1.0) -> RigidBody:
        """Kovalevskaya top: ``A = B = 2C``, centre of mass in the equatorial plane.

        Parameters
        ----------
        C : float, default 1
            Moment about the symmetry axis 3 (positive); ``A = B = 2C``.
        mu : float, default 1
            Weight times the distance of the centre of mass from the fixed point
            (``mu >= 0``).
        """
        return cls(2.0 * C, 2.0 * C, C, mu, (1.0, 0.0, 0.0), "kovalevskaya")

    @classmethod
    def goryachev_chaplygin(cls, C: float = 1.0, mu: float = 1.0) -> RigidBody:
        """Goryachev-Chaplygin top: ``A = B = 4C``, equatorial centre of mass (integrable
        on the zero level of the area integral, M = 0).

        Parameters
        ----------
        C : float, default 1
            Moment about the symmetry axis 3 (positive); ``A = B = 4C``.
        mu : float, default 1
            Weight times the distance of the centre of mass from the fixed point
            (``mu >= 0``).
        """
        return cls(4.0 * C, 4.0 * C, C, mu, (1.0, 0.0, 0.0), "goryachev_chaplygin")


#: The body of the paper's computations (Fig. 3).
PAPER_BODY = RigidBody.paper()


@dataclass(frozen=True)
class Preset:
    """A kind of body users name (``--body``, a scan's ``[body] kind``, the explorer).

    Parameters
    ----------
    name : str
        Its name in the CLI, scan configs and the explorer.
    factory : callable
        ``factory(**values) -> RigidBody`` from the values of its flags (each given,
        or its default).
    flags : tuple of str
        The body flags it takes (``A``, ``B``, ``C``, ``mu``, ``r``, ``epsilon``); others
        are refused.
    help : str
        What it is, for ``--help``.
    required : tuple of str, optional
        The flags that have no default.
    defaults : dict, optional
        The defaults of the others.
    integrals : tuple of str, optional
        The first integrals it brings beside ``H``, ``(G, gamma)``, ``|gamma|^2`` (rows
        of :data:`andoyer.charts.integrals.INTEGRALS`; the datasets, drifts and the
        explorer then carry them).
    """

    name: str
    factory: Callable[..., RigidBody]
    flags: tuple[str, ...]
    help: str
    required: tuple[str, ...] = ()
    defaults: dict[str, float] = field(default_factory=dict)
    integrals: tuple[str, ...] = ()

    def make(self, **values: object) -> RigidBody:
        """The body from ``values`` (None: the flag's default); ``ValueError`` naming a
        flag it does not take or a required flag missing.

        Parameters
        ----------
        **values : object
            Flag name -> value (None for not given).

        Examples
        --------
        >>> PRESETS["kovalevskaya"].make(C=0.5).A
        1.0
        """
        given = {k: v for k, v in values.items() if v is not None}
        extra = sorted(set(given) - set(self.flags), key=list(_FLAG_ORDER).index)
        if extra:
            raise ValueError(f"the {self.name} body does not take {', '.join(extra)} (it "
                             f"takes {', '.join(self.flags)})")
        missing = [k for k in self.required if k not in given]
        if missing:
            raise ValueError(f"the {self.name} body needs {', '.join(missing)}")
        return self.factory(**{**self.defaults, **given})


_FLAG_ORDER = ("A", "B", "C", "mu", "epsilon", "r")
_MU = {"mu": PAPER["mu"]}


def _turned(body: RigidBody, epsilon: float) -> RigidBody:
    """``body`` with its centre of mass turned by ``epsilon`` off the Hess direction."""
    if epsilon == 0.0:
        return body
    return RigidBody.near_hess(body.A, body.B, body.C, body.mu, epsilon,
                               branch=1 if body.e2 >= 0.0 else -1,
                               name=f"{body.name} turned by {epsilon:g}")


#: The body presets, by name: ``--body`` choices, their flags and help, scan configs'
#: kinds and the explorer's body menu are derived from this table.
PRESETS: dict[str, Preset] = {p.name: p for p in (
    Preset("paper", lambda mu, epsilon: _turned(RigidBody.paper(mu), epsilon),
           ("mu", "epsilon"),
           f"Hess body A={PAPER['A']:g}, B={PAPER['B']:g}, C={PAPER['C']:g}, "
           f"mu={PAPER['mu']:g} (the paper's; default)", defaults={**_MU, "epsilon": 0.0}),
    Preset("hess", lambda A, B, C, mu, epsilon: _turned(RigidBody.hess(A, B, C, mu), epsilon),
           ("A", "B", "C", "mu", "epsilon"), "Hess body from A > C > B and mu",
           ("A", "B", "C"), {**_MU, "epsilon": 0.0}),
    Preset("general", lambda A, B, C, mu, r: RigidBody(A, B, C, mu, tuple(r), "general"),
           ("A", "B", "C", "mu", "r"), "any body: A, B, C, mu and the direction r of the "
           "centre of mass", ("A", "B", "C", "r"), dict(_MU)),
    Preset("lagrange", lambda A, C, mu: RigidBody.lagrange(A, C, mu), ("A", "C", "mu"),
           "Lagrange top: A = B, centre of mass on the axis 3", ("A", "C"), dict(_MU)),
    Preset("kovalevskaya", lambda C, mu: RigidBody.kovalevskaya(C, mu), ("C", "mu"),
           "Kovalevskaya top: A = B = 2C, equatorial centre of mass (its integral K)",
           defaults={"C": 1.0, "mu": 1.0}, integrals=("K",)),
    Preset("goryachev-chaplygin", lambda C, mu: RigidBody.goryachev_chaplygin(C, mu),
           ("C", "mu"), "Goryachev-Chaplygin top: A = B = 4C, equatorial centre of mass",
           defaults={"C": 1.0, "mu": 1.0}),
)}


def make_body(kind: str, **values: object) -> RigidBody:
    """The body of preset ``kind`` (:data:`PRESETS`) from its flags' values.

    Parameters
    ----------
    kind : str
        A key of :data:`PRESETS`.
    **values : object
        Flag name -> value (None for not given).

    Examples
    --------
    >>> make_body("paper").A, make_body("hess", A=2.5, B=1.0, C=1.6).is_hess
    (2.5, True)
    """
    if kind not in PRESETS:
        raise ValueError(f"body kind must be one of {', '.join(PRESETS)}, got {kind!r}")
    return PRESETS[kind].make(**values)


_P = ParamSpec("_P")
_R = TypeVar("_R")


@overload
def checks_body(func: Callable[_P, _R], /) -> Callable[_P, _R]: ...


@overload
def checks_body(func: None = None, /, *, ranges: Mapping[str, str] | None = ...,
                labels: Mapping[str, str] | None = ..., closed_form: bool = ...
                ) -> Callable[[Callable[_P, _R]], Callable[_P, _R]]: ...


def checks_body(func: Callable[_P, _R] | None = None, /, *,
                ranges: Mapping[str, str] | None = None,
                labels: Mapping[str, str] | None = None, closed_form: bool = False) -> Any:
    """Decorator of the public functions whose first argument is a body: anything but a
    :class:`RigidBody` there raises one clear ``TypeError`` naming the function; the other
    arguments are checked by :func:`andoyer.validation.checks_arguments` with the ranges
    given here (an ``energy`` held to a level of that body).

    Parameters
    ----------
    func : callable, optional
        The public function to wrap (first argument: the body); bare ``@checks_body``
        checks the body and the annotated types only.
    ranges, labels, closed_form :
        As in :func:`andoyer.validation.checks_arguments`
        (``@checks_body(ranges={"h": "energy"}, closed_form=True)``).

    Returns
    -------
    callable
        The wrapped function, or the decorator when ``func`` is not given.

    Examples
    --------
    >>> from andoyer import energy
    >>> energy("paper", [0, 0, 1, 0, 0, 1])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    andoyer.errors.ArgumentTypeError: energy: body must be a RigidBody (...), got str 'paper'
    """
    options: dict[str, Any] = {"ranges": ranges, "labels": labels, "closed_form": closed_form}
    if func is None:
        return functools.partial(_checks_body, options=options)
    return _checks_body(func, options)


def _checks_body(func: Callable[_P, _R], options: dict[str, Any]) -> Callable[_P, _R]:
    first = next(iter(inspect.signature(func).parameters), "body")
    checked = checks_arguments(**options, body=first)(func)

    @functools.wraps(func)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        body = args[0] if args else kwargs.get(first)
        if not isinstance(body, RigidBody):
            raise ArgumentTypeError(
                f"{func.__name__}: body must be a RigidBody (e.g. RigidBody.paper() or "
                f"RigidBody.hess(A, B, C, mu)), got {type(body).__name__} {repr(body)[:60]}")
        return checked(*args, **kwargs)

    wrapper.__checks__ = checked.__checks__  # type: ignore[attr-defined]
    return wrapper
