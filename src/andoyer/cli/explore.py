"""``andoyer explore``: the interactive section explorer in the browser (a local web app)."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    add_level_args,
    add_term,
    body_from_args,
    count,
)

NAME = "explore"
ORDER = 45


def run(args: argparse.Namespace) -> int:
    from andoyer.explore.server import serve
    from andoyer.integrate import Section

    body = body_from_args(args)
    section = Section.parse(args.section)

    def started(url: str) -> None:
        print(f"andoyer explore: serving on {url}", flush=True)
        print("press Ctrl-C to stop", flush=True)

    serve(body, port=args.port, show=not args.no_browser, on_start=started, h=args.h,
          M=args.M, section=section, n_crossings=args.n_crossings, engine=args.engine,
          rtol=args.rtol, atol=args.atol, max_sessions=args.max_sessions)
    print("andoyer explore: stopped")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="interactive Poincare-section explorer in the browser",
                       description="Serve the explorer on http://127.0.0.1:PORT/ and block "
                                   "until Ctrl-C: click on the section plane to seed orbits.")
    add_body_args(p)
    add_level_args(p)
    add_term(p, "n_crossings", type=count(1), default=500,
             help="crossings per orbit (default 500)")
    add_engine_args(p)
    p.add_argument("--port", type=count(0, 65535), default=0,
                   help="port (default 0: a free port; the address is printed at start)")
    p.add_argument("--max-sessions", type=count(1), default=8,
                   help="pages open at once; a page past it says so (default 8)")
    p.add_argument("--no-browser", action="store_true",
                   help="do not open the page in a web browser")
    # a server: Ctrl-C, SIGTERM and SIGHUP are its normal stop (exit 0, "stopped")
    p.set_defaults(func=run, serves=True)
