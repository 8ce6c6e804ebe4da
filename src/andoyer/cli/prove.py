"""``andoyer prove``: certify the first-order transversal splitting (``--kind melnikov``)
or the transversal splitting at a finite ``mu`` (``--kind transversal``); write the
certificate."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import add_term, count, output_file

NAME = "prove"
ORDER = 92


def run(args: argparse.Namespace) -> int:
    from andoyer.analysis.splitting.certificate import (
        prove_certificate,
        prove_transversal_certificate,
        write_certificate,
    )
    from andoyer.integrate.validated.arithmetic import BodySpec

    out = output_file(args.out, ".json")
    if args.kind == "transversal":
        if args.mu is None:
            raise ValueError("--kind transversal needs --mu (a decimal > 0), e.g. --mu 0.05")
        spec = BodySpec(args.A, args.B, args.C, 1, args.epsilon, args.mu)
        cert = prove_transversal_certificate(spec, G=args.G, rotation=args.rotation,
                                             mu_radius=args.mu_radius,
                                             half_width=args.half_width)
        write_certificate(cert, out)
        print(f"wrote {out} in {cert['run_seconds']:.0f} s: {cert['statement']}\n"
              f"check it with andoyer verify {out}")
        return 0
    if not 5 <= args.digits <= 200:
        raise ValueError(f"--digits must lie in [5, 200], got {args.digits}")
    if args.mu is not None or args.mu_radius != "0":
        raise ValueError("--mu and --mu-radius belong to --kind transversal (the "
                         "first-order statement holds for mu in (0, mu*))")
    spec = BodySpec(args.A, args.B, args.C, 1, args.epsilon)
    cert = prove_certificate(spec, branch=args.branch, sheet=args.sheet, J2=args.G,
                             digits=args.digits)
    write_certificate(cert, out)
    zeros = ", ".join(z["zero"][:24] + "...]" for z in cert["zeros"])
    print(f"wrote {out}: two simple zeros of the Melnikov function on {args.branch} "
          f"({zeros}); {cert['precision_bits']} bits; check it with andoyer verify {out}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="prove the transversal splitting of a (near-)Hess body in "
                                  "ball arithmetic (first order, or at a finite mu); write "
                                  "a certificate")
    add_term(p, "kind", choices=("melnikov", "transversal"), default="melnikov",
             help="melnikov: simple zeros of the Melnikov function (mu in (0, mu*)); "
                  "transversal: W^u and W^s proved to cross at the given --mu (default "
                  "melnikov)")
    g = p.add_argument_group("body (decimals, read exactly: 2.2 is the decimal 2.2)")
    for name, default in (("A", "2.5"), ("B", "2.0"), ("C", "2.2")):
        add_term(g, name, default=default, help=f"principal moment {name} (a decimal; "
                                               f"default {default}, the paper's)")
    add_term(g, "epsilon", default="0",
             help="turn of the centre of mass off the Hess direction (rad, a decimal; "
                  "default 0: the Hess body, branch +1 of (2))")
    add_term(g, "mu", default=None,
             help="--kind transversal: weight times distance of the centre of mass (a "
                  "decimal > 0; e.g. 0.05 with --B 1.0 --C 1.6 --epsilon 0.1)")
    add_term(p, "branch", choices=("theta1=4phi0", "theta1=0"), default="theta1=4phi0",
             help="the heteroclinic line (default theta1=4phi0; theta1=0 splits only for "
                  "epsilon != 0)")
    add_term(p, "sheet", type=int, choices=(1, -1), default=1,
             help="which orbit of the line (default 1; -1: theta1 + 2 pi)")
    add_term(p, "mu_radius", default="0",
             help="--kind transversal: prove it for every mu in [mu - r, mu + r] (a decimal; "
                  "default 0; e.g. 5e-8 with --half-width 1e-4)")
    add_term(p, "half_width", type=float, default=1e-9,
             help="--kind transversal: relative half-width of the piece of W^u carried "
                  "(default 1e-9; larger for a mu interval)")
    add_term(p, "rotation", type=int, choices=(1, -1), default=1,
             help="--kind transversal: whose unstable manifold, P+ (1, default) or P- (-1)")
    add_term(p, "G", default="1", help="the level h = c G^2/2, G = J2 (a decimal; default 1)")
    add_term(p, "digits", type=count(5), default=30,
             help="correct digits of the Melnikov coefficient (default 30)")
    p.add_argument("--out", default="certificate.json", help="the certificate (JSON)")
    p.set_defaults(func=run)
