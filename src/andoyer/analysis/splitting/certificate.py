"""Certificates of the first-order transversal splitting, written and verified.

A certificate (JSON) states, for a body given by decimals (a Hess body or one whose centre
of mass is turned by ``epsilon``, :class:`~andoyer.integrate.validated.arithmetic.BodySpec`),
a separatrix line and a level ``J2 = G``:

    the Melnikov function ``M(theta2_0) = Re(Z e^{i theta2_0})`` of (16) has exactly two
    zeros on ``[0, 2 pi)``, each simple, in the boxes listed; hence (Melnikov) the stable
    and unstable manifolds of the rotations ``P-`` and ``P+`` intersect transversally near
    the unperturbed heteroclinic orbit for every ``mu`` in ``(0, mu*)``, some ``mu* > 0``.

It records the ball of ``Z`` (the certified integral,
:func:`~andoyer.analysis.splitting.certified.melnikov_coefficient`), every box,
the precision, the libraries' versions and a SHA-256 digest of its content.
:func:`verify_certificate` re-checks it without the search that produced it: the
digest; the arithmetic (same python-flint); ``Z`` recomputed from the body and compared
with the recorded ball; the Krawczyk test on each recorded box with the recomputed ``Z``;
the two boxes distinct modulo ``2 pi`` (a nonzero trigonometric polynomial of degree 1 has
exactly two zeros per period). Any altered parameter or box is rejected.

The ``mu`` interval of that kind is ``(0, mu*)`` with ``mu*`` not bounded. The second kind,
``heteroclinic-transversality`` (:func:`prove_transversal_certificate`), states the theorem
of :mod:`andoyer.analysis.splitting.transversal` at a given decimal ``mu``: it records the
local manifold's frame, box and cone slope, the piece carried and every ball the proof
produced; :func:`verify_certificate` re-runs the proof from those (no search) and requires
each recomputed ball to be the recorded one.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from pathlib import Path
from typing import Any

from flint import acb, arb

from andoyer.analysis.splitting.certified import (
    certified_melnikov,
    melnikov_coefficient,
)
from andoyer.analysis.unperturbed.separatrix import DEFAULT_BRANCH
from andoyer.errors import ArgumentTypeError, CertificateError
from andoyer.integrate.validated.arithmetic import (
    FLINT_VERSION,
    BodySpec,
    spec_of,
    working_precision,
)

__all__ = ["FORMAT", "KIND", "KIND_TRANSVERSAL", "prove_certificate",
           "prove_transversal_certificate", "write_certificate", "read_certificate",
           "verify_certificate"]

#: The ``format`` field of every andoyer certificate.
FORMAT = "andoyer-certificate"
#: The kind of statement this module writes and verifies.
KIND = "melnikov-first-order-transversality"
#: The kind of the finite-``mu`` theorem (:mod:`andoyer.analysis.splitting.transversal`).
KIND_TRANSVERSAL = "heteroclinic-transversality"
#: The fields a finite-``mu`` certificate must have.
FIELDS_TRANSVERSAL = ("format", "version", "kind", "statement", "body", "mu_interval",
                      "level", "precision_bits", "order", "libraries", "local_manifold",
                      "piece", "boxes", "run_seconds", "digest")
#: The recorded balls a verification recomputes and compares, as text.
TRANSVERSAL_BOXES = ("multiplier", "expansion", "cone_derivative", "ends_gamma3",
                     "point_box", "crossing_time", "slope", "angle")
#: The fields a certificate must have.
FIELDS = ("format", "version", "kind", "statement", "body", "mu_interval", "level",
          "branch", "sheet", "precision_bits", "libraries", "heteroclinic_line",
          "coefficient", "zeros", "digest")


def _line_balls(spec: BodySpec, branch: str, sheet: int, J2: str, bits: int
                ) -> dict[str, str]:
    """The line ``theta1`` and the rate ``lambda = 2 sigma J2`` of the heteroclinic orbit
    (the orbit the integral runs along), as balls."""
    from andoyer.analysis.splitting.certified import heteroclinic_orbit_balls

    theta1, lam = heteroclinic_orbit_balls(spec, branch, sheet, J2, bits)
    return {"theta1": theta1.str(30, radius=True, more=True),
            "lambda": lam.str(30, radius=True, more=True)}


def _digest(cert: dict[str, Any]) -> str:
    content = {k: v for k, v in cert.items() if k != "digest"}
    text = json.dumps(content, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def prove_certificate(body: Any, *, branch: str = DEFAULT_BRANCH, sheet: int = 1,
                      J2: str = "1", digits: int = 30) -> dict[str, Any]:
    """Prove the first-order statement and return its certificate (a JSON-ready dict).

    Parameters
    ----------
    body : RigidBody or BodySpec
        A Hess or near-Hess body.
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        The separatrix line. The default is every analysis' default, the Hess
        separatrix; on a Hess body that line does not split (M = 0).
    sheet : {+1, -1}, default 1
        Which of its orbits.
    J2 : str, default "1"
        The level ``J2 = G`` (a decimal).
    digits : int, default 30
        Correct digits asked of ``|Z|``.

    Raises
    ------
    ValueError
        When ``M`` vanishes identically (the Hess branch of a Hess body: nothing splits)
        or the zeros are not all proved simple.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> cert = prove_certificate(RigidBody.paper(), branch="theta1=4phi0", digits=20)
    >>> verify_certificate(cert)["zeros"]
    2
    """
    from andoyer._version import __version__

    body = spec_of(body)
    res = certified_melnikov(body, branch=branch, sheet=sheet, J2=J2, digits=digits,
                             phases=[])
    if not res.complete or len(res.zeros) != 2:
        raise ValueError(f"nothing to certify on branch {branch!r} of this body: the "
                         "Melnikov function vanishes identically (no splitting at first "
                         "order) or its zeros were not all proved simple")
    with working_precision(res.bits):
        Z, _, _ = melnikov_coefficient(res.body, branch=branch, sheet=sheet, J2=J2,
                                       bits=res.bits)
        coefficient = {"real": Z.real.str(digits + 8, radius=True, more=True),
                       "imag": Z.imag.str(digits + 8, radius=True, more=True)}
        line = _line_balls(res.body, branch, sheet, J2, res.bits)
    zeros = [{"box": z.box, "zero": z.zero, "derivative": z.derivative} for z in res.zeros]
    spec = res.body.as_dict()
    spec.pop("mu")
    cert: dict[str, Any] = {
        "format": FORMAT, "version": 1, "kind": KIND,
        "statement": (
            f"For the body A={spec['A']}, B={spec['B']}, C={spec['C']} (branch "
            f"{spec['branch']} of the Hess condition (2), centre of mass turned by epsilon="
            f"{spec['epsilon']}) on the level J2=G={J2}, the Melnikov function of the "
            f"heteroclinic line {branch} (sheet {sheet}) has exactly two zeros in [0, 2 pi), "
            "both simple, in the boxes below; so for every mu in (0, mu*), some mu* > 0, "
            "the stable and unstable manifolds of the rotations intersect transversally "
            "near the unperturbed heteroclinic orbit."),
        "body": spec,
        "mu_interval": {"lower": "0", "upper": None, "open": True,
                        "note": "first order in mu: mu* exists, no bound is proved"},
        "level": {"J2": J2}, "branch": branch, "sheet": sheet,
        "precision_bits": res.bits,
        "libraries": {"python-flint": FLINT_VERSION, "andoyer": __version__},
        "heteroclinic_line": line, "coefficient": coefficient, "zeros": zeros,
    }
    cert["digest"] = _digest(cert)
    return cert


def write_certificate(cert: dict[str, Any], path: str | os.PathLike[str]) -> Path:
    """Write ``cert`` as JSON atomically (:func:`andoyer.atomic.atomic_path`).

    Parameters
    ----------
    cert : dict
        From :func:`prove_certificate`.
    path : str or os.PathLike
        The file (``.json``).
    """
    from andoyer.atomic import atomic_path

    if not isinstance(cert, dict):
        raise ArgumentTypeError(f"cert must be a certificate (a dict), got "
                                f"{type(cert).__name__}")
    out = _path("path", path)
    if out.suffix.lower() != ".json":
        raise ValueError(f"path {str(out)!r} must name a .json file")
    try:
        text = json.dumps(cert, indent=1, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"cert is not JSON: {exc}") from None
    with atomic_path(out) as tmp:
        tmp.write_text(text + "\n")
    return out


def _path(name: str, value: Any) -> Path:
    if isinstance(value, bool) or not isinstance(value, str | os.PathLike) or not str(value):
        raise ArgumentTypeError(f"{name} must be a file path, got {value!r:.60}")
    return Path(value)


def read_certificate(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Read a certificate file; :class:`~andoyer.errors.CertificateError` if not JSON.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    """
    p = _path("path", path)
    if not p.is_file():
        raise ValueError(f"path {str(p)!r}: no such file")
    try:
        text = p.read_text()
    except UnicodeDecodeError:
        raise CertificateError(f"{str(p)!r} is not a certificate (not text)") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise CertificateError(f"{str(p)!r} is not a certificate (not JSON: {exc.msg} at "
                               f"line {exc.lineno})") from None
    if not isinstance(data, dict):
        raise CertificateError(f"{str(p)!r} is not a certificate (JSON {type(data).__name__},"
                               " not an object)")
    return data


def _ball(text: Any, what: str) -> arb:
    if not isinstance(text, str):
        raise CertificateError(f"{what} must be a ball written as a string, got {text!r}")
    try:
        return arb(text)
    except (ValueError, TypeError):
        raise CertificateError(f"{what} is not a ball: {text!r}") from None


def _check_envelope(data: dict[str, Any], fields: tuple[str, ...], kind: str) -> None:
    """The checks every kind of certificate passes before its boxes are recomputed: its
    fields, kind and version, the python-flint that computed it, its digest."""
    missing = [k for k in fields if k not in data]
    if missing:
        raise CertificateError(f"the certificate lacks the field(s) {', '.join(missing)}")
    if data["kind"] != kind or data["version"] != 1:
        raise CertificateError(f"unknown certificate kind {data['kind']!r} version "
                               f"{data['version']!r} (this andoyer verifies {kind!r} 1)")
    libs = data["libraries"]
    theirs = libs.get("python-flint") if isinstance(libs, dict) else None
    if theirs != FLINT_VERSION:
        raise CertificateError(f"the certificate's balls were computed by python-flint "
                               f"{theirs}; this is python-flint {FLINT_VERSION}: verify it "
                               "with the same version (pip install python-flint==" +
                               f"{theirs})")
    if data["digest"] != _digest(data):
        raise CertificateError("the certificate was altered: its SHA-256 digest does not "
                               "match its content")


def verify_certificate(cert: dict[str, Any] | str | os.PathLike[str]) -> dict[str, Any]:
    """Re-check a certificate independently of the search that wrote it.

    Parameters
    ----------
    cert : dict, str or os.PathLike
        The certificate or its file.

    Returns
    -------
    dict
        ``statement``, ``zeros`` (their number), ``digits`` (of ``|Z|``), ``bits``.

    Raises
    ------
    CertificateError
        Foreign JSON, a missing field, another python-flint, an altered content, or a
        box the Krawczyk test does not prove (one line naming what failed).
    """
    if isinstance(cert, dict):
        data = cert
    else:
        if isinstance(cert, bool) or not isinstance(cert, str | os.PathLike):
            raise ArgumentTypeError(f"cert must be a certificate (a dict) or its file, got "
                                    f"{cert!r:.60}")
        if not Path(cert).is_file():
            raise ValueError(f"cert {str(cert)!r}: no such file")
        data = read_certificate(cert)
    if data.get("format") != FORMAT:
        raise CertificateError(f"not an andoyer certificate (format {data.get('format')!r}, "
                               f"expected {FORMAT!r})")
    if data.get("kind") == KIND_TRANSVERSAL:
        return _verify_transversal(data)
    _check_envelope(data, FIELDS, KIND)
    mu = data["mu_interval"]
    if mu != {"lower": "0", "upper": None, "open": True,
              "note": "first order in mu: mu* exists, no bound is proved"}:
        raise CertificateError("the mu interval of a first-order certificate is (0, mu*) "
                               "with no bound on mu*; this one claims "
                               f"{mu!r}")
    try:
        b = data["body"]
        spec = BodySpec(b["A"], b["B"], b["C"], b["branch"], b["epsilon"], "0")
        J2 = str(data["level"]["J2"])
        bits = int(data["precision_bits"])
    except (KeyError, TypeError) as exc:
        raise CertificateError(f"the certificate's body or level lacks {exc}") from None
    except ValueError as exc:
        raise CertificateError(f"the certificate's body is not valid: {exc}") from None
    if not 64 <= bits <= 4096:
        raise CertificateError(f"precision_bits {bits} out of [64, 4096]")
    zeros = data["zeros"]
    if not isinstance(zeros, list) or len(zeros) != 2:
        raise CertificateError("a first-order certificate lists exactly two zeros")
    try:
        Z, _, _ = melnikov_coefficient(spec, branch=data["branch"], sheet=data["sheet"],
                                       J2=J2, bits=bits)
    except ValueError as exc:
        raise CertificateError(f"the certificate's branch, sheet or level: {exc}") from None
    with working_precision(bits):
        line = _line_balls(spec, data["branch"], data["sheet"], J2, bits)
        rec_line = data["heteroclinic_line"]
        for key in ("theta1", "lambda"):
            got = rec_line.get(key) if isinstance(rec_line, dict) else None
            if not _ball(got, f"heteroclinic_line.{key}").overlaps(arb(line[key])):
                raise CertificateError(f"the recorded heteroclinic line's {key} does not "
                                       "match the body, line, sheet and level")
        rec = acb(_ball(data["coefficient"]["real"], "coefficient.real"),
                  _ball(data["coefficient"]["imag"], "coefficient.imag"))
        if not (rec.real.overlaps(Z.real) and rec.imag.overlaps(Z.imag)):
            raise CertificateError("the recorded coefficient Z does not match the body, "
                                   f"line and level: recomputed {Z.str(20, radius=True)}")
        if abs(Z).contains(0):
            raise CertificateError("the Melnikov function is not proved nonzero")
        mids, rads = [], []
        for k, z in enumerate(zeros):
            X = _ball(z.get("box") if isinstance(z, dict) else None, f"zeros[{k}].box")
            K = _ball(z.get("zero"), f"zeros[{k}].zero")
            m = arb(X.mid())
            dX = -Z.real * X.sin() - Z.imag * X.cos()
            if dX.contains(0):
                raise CertificateError(f"zeros[{k}]: M' is not bounded away from 0 on its box")
            Y = 1 / arb(dX.mid())
            Kx = m - Y * (Z.real * m.cos() - Z.imag * m.sin()) + (1 - Y * dX) * (X - m)
            if not (Kx.lower() > X.lower() and Kx.upper() < X.upper()):
                raise CertificateError(f"zeros[{k}]: the Krawczyk test fails on its box "
                                       f"{z.get('box')}")
            if not K.overlaps(Kx):
                raise CertificateError(f"zeros[{k}]: the recorded zero is not where "
                                       "K(box) puts it")
            mids.append(float(m))
            rads.append(float(X.rad()))
        gap = abs(math.remainder(mids[0] - mids[1], math.tau))
        if not gap > 2 * (rads[0] + rads[1]):
            raise CertificateError("the two zero boxes are the same zero modulo 2 pi")
        digits = -math.log10(float(abs(Z).rad()) / float(abs(Z).mid()))
    return {"statement": data["statement"], "zeros": len(zeros), "digits": digits,
            "bits": bits}


# ----------------------------------------------------------------------------- finite mu
def _transversal_boxes(proof: Any) -> dict[str, Any]:
    lm = proof.manifold
    return {"multiplier": lm.multiplier, "expansion": lm.expansion,
            "cone_derivative": list(lm.derivative), "ends_gamma3": list(proof.ends_gamma3),
            "point_box": list(proof.point_box), "crossing_time": proof.crossing_time,
            "slope": proof.slope, "angle": proof.angle}


def prove_transversal_certificate(body: Any, *, G: str = "1", rotation: int = 1,
                                  radius: float = 3e-5, mu_radius: str = "0",
                                  side: int = 1, which: int = 0,
                                  half_width: float = 1e-9,
                                  bits: int = 128, order: int = 24) -> dict[str, Any]:
    """Prove the finite-``mu`` theorem and return its certificate.

    The theorem is that of
    :func:`~andoyer.analysis.splitting.transversal.prove_transversal`.

    Parameters
    ----------
    body : RigidBody or BodySpec
        A body with ``mu > 0`` and its centre of mass in the (e1, e2) plane.
    G : str, default "1"
        The level ``h = c G^2 / 2``.
    rotation, radius, mu_radius, side, which, half_width, bits, order
        As in :func:`~andoyer.analysis.splitting.transversal.prove_transversal`.

    Raises
    ------
    ValueError
        When the proof does not close; the message names the step and its widths.
    """
    from andoyer._version import __version__
    from andoyer.analysis.splitting.transversal import mu_interval, prove_transversal

    spec = spec_of(body)
    try:
        proof = prove_transversal(spec, G=G, rotation=rotation, radius=radius, side=side,
                                  mu_radius=mu_radius, which=which,
                                  half_width=half_width, bits=bits, order=order)
    except ArithmeticError as exc:
        raise ValueError(f"the finite-mu proof does not close: {exc}") from None
    if not proof.proved:
        raise ValueError("the finite-mu proof does not close: " + _failure(proof.widths))
    lm = proof.manifold
    cert: dict[str, Any] = {
        "format": FORMAT, "version": 1, "kind": KIND_TRANSVERSAL,
        "statement": proof.statement,
        "body": proof.body,
        "mu_interval": _mu_claim(mu_interval(proof.body)),
        "level": {"G": proof.G, "area": "0"},
        "precision_bits": proof.bits, "order": proof.order,
        "libraries": {"python-flint": FLINT_VERSION, "andoyer": __version__},
        "local_manifold": {"rotation": lm.rotation, "frame": [list(r) for r in lm.frame],
                           "radius": lm.radius, "kappa": lm.kappa},
        "piece": {"side": proof.side, "u": list(proof.piece)},
        "boxes": _transversal_boxes(proof),
        "run_seconds": round(proof.seconds, 1),
    }
    cert["digest"] = _digest(cert)
    return cert


def _mu_claim(bounds: tuple[str, str]) -> dict[str, Any]:
    lo, hi = bounds
    return {"lower": lo, "upper": hi, "open": False,
            "note": "the decimal mu itself" if lo == hi else "every mu of the closed "
            "interval at once (the field's coefficients are balls)"}


def _failure(widths: dict[str, float]) -> str:
    return ("the ends' gamma3 " + f"{widths['end_gamma3_a_mid']:.3g} +/- "
            f"{widths['end_gamma3_a']:.2g} and {widths['end_gamma3_b_mid']:.3g} +/- "
            f"{widths['end_gamma3_b']:.2g} (need opposite signs); the tangent's gamma3 "
            f"{widths['tangent_gamma3_mid']:.3g} +/- {widths['tangent_gamma3']:.2g} and "
            f"the slope {widths['slope_mid']:.3g} +/- {widths['slope']:.2g} (need != 0); "
            f"the piece's image {widths['piece_image']:.2g} wide")


def _verify_transversal(data: dict[str, Any]) -> dict[str, Any]:
    from andoyer.analysis.splitting.transversal import (
        local_unstable_manifold,
        mu_interval,
        prove_transversal,
    )

    _check_envelope(data, FIELDS_TRANSVERSAL, KIND_TRANSVERSAL)
    try:
        b = data["body"]
        spec = BodySpec(b["A"], b["B"], b["C"], b["branch"], b["epsilon"], b["mu"])
        mu_radius = str(b.get("mu_radius", "0"))
        G = str(data["level"]["G"])
        bits = int(data["precision_bits"])
        order = int(data["order"])
        lmd = data["local_manifold"]
        frame = tuple(tuple(float(x) for x in row) for row in lmd["frame"])
        radius, kappa = float(lmd["radius"]), float(lmd["kappa"])
        rotation = int(lmd["rotation"])
        side = int(data["piece"]["side"])
        u_a, u_b = (float(x) for x in data["piece"]["u"])
        boxes = data["boxes"]
        if not isinstance(boxes, dict):
            raise TypeError("boxes")
    except (KeyError, TypeError) as exc:
        raise CertificateError(f"the certificate's body, level, manifold or piece lacks "
                               f"{exc}") from None
    except ValueError as exc:
        raise CertificateError(f"the certificate's body is not valid: {exc}") from None
    try:
        claim = _mu_claim(mu_interval({"mu": spec.mu, "mu_radius": mu_radius}))
    except ArithmeticError:
        raise CertificateError(f"the body's mu_radius {mu_radius!r} is not a decimal") from None
    if data["mu_interval"] != claim:
        raise CertificateError(f"the mu interval must be {claim['lower']}..{claim['upper']} "
                               f"(the body's mu and mu_radius); this one claims "
                               f"{data['mu_interval']!r}")
    if not 64 <= bits <= 4096 or not 8 <= order <= 60:
        raise CertificateError(f"precision_bits {bits} or order {order} out of range")
    if len(frame) != 2 or any(len(r) != 2 for r in frame):
        raise CertificateError("local_manifold.frame must be a 2 x 2 matrix")
    try:
        lm = local_unstable_manifold(spec, G=G, rotation=rotation, radius=radius, bits=bits,
                                     order=order, frame=frame, kappa=kappa,
                                     mu_radius=mu_radius)
        if not lm.holds:
            raise CertificateError(f"the cone condition fails on the recorded box N "
                                   f"(radius {radius}, kappa {kappa})")
        proof = prove_transversal(spec, G=G, side=side, piece=(u_a, u_b), manifold=lm,
                                  bits=bits, order=order, mu_radius=mu_radius)
    except (ValueError, ArithmeticError, ZeroDivisionError) as exc:
        if isinstance(exc, CertificateError):
            raise
        raise CertificateError(f"the recorded manifold or piece does not prove the "
                               f"theorem: {exc}") from None
    if not proof.proved:
        raise CertificateError("the recorded piece does not prove the theorem: "
                               + _failure(proof.widths))
    again = _transversal_boxes(proof)
    for key in TRANSVERSAL_BOXES:
        if boxes.get(key) != again[key]:
            raise CertificateError(f"the recorded box {key!r} is not what the recorded "
                                   f"manifold and piece give: recomputed {again[key]!r}")
    if data["statement"] != proof.statement:
        raise CertificateError("the statement does not match the recomputed theorem")
    return {"statement": proof.statement, "angle": proof.angle, "bits": bits,
            "seconds": proof.seconds, "kind": KIND_TRANSVERSAL}
