"""``andoyer verify CERTIFICATE``: re-check a certificate of ``andoyer prove``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

NAME = "verify"
ORDER = 93


def run(args: argparse.Namespace) -> int:
    from andoyer.analysis.splitting.certificate import verify_certificate

    path = Path(args.certificate)
    if not path.is_file():
        raise ValueError(f"CERTIFICATE {args.certificate!r}: no such file")
    result = verify_certificate(path)
    if "zeros" not in result:
        print(f"verified {path}: every box recomputed in {result['seconds']:.0f} s "
              f"({result['bits']} bits)\n{result['statement']}")
        return 0
    print(f"verified {path}: {result['zeros']} simple zeros, Melnikov coefficient to "
          f"{result['digits']:.1f} digits ({result['bits']} bits)\n{result['statement']}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="re-check a certificate written by andoyer prove")
    p.add_argument("certificate", metavar="CERTIFICATE", help="the certificate (JSON)")
    p.set_defaults(func=run)
