"""``andoyer animate``: the gyroscope moving in space, written as an animated GIF or MP4."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    add_state_args,
    add_term,
    body_from_args,
    count,
    output_file,
    real,
    state_from_args,
)

#: The frame's side by default (andoyer.plot.space.ANIMATION_SIZE; the CLI imports no
#: matplotlib before it runs).
ANIMATION_SIZE = 480

NAME = "animate"
ORDER = 35
#: Most frames of one animation (each is a rendered image kept until the file is written).
MAX_FRAMES = 2000


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from andoyer.integrate.orientation import attitude
    from andoyer.plot.space import (
        ANIMATION_FORMATS,
        animation_writer_available,
        gyroscope_animation,
        save_animation,
    )

    suffix = Path(args.out).suffix.lower()
    if suffix not in ANIMATION_FORMATS:
        raise ValueError(f"--out {args.out!r} must name a .gif or .mp4 file")
    if not animation_writer_available(suffix):
        raise ValueError(f"--out {args.out!r}: no MP4 encoder here (the ffmpeg program is "
                         "not installed); write a .gif")
    out_path = output_file(args.out, suffix)
    body = body_from_args(args)
    state, chart = state_from_args(args, body)  # type: ignore[misc]
    if args.frames > MAX_FRAMES:
        raise ValueError(f"--frames {args.frames}: at most {MAX_FRAMES} frames")
    t = np.linspace(0.0, args.t_end, args.frames)
    ds = attitude(body, state, t, chart=chart, engine=args.engine, rtol=args.rtol,
                  atol=args.atol, precession0=args.precession0, progress=True)
    anim = gyroscope_animation(ds, fps=args.fps, size=args.size)
    out = save_animation(anim, out_path, fps=args.fps, progress=True)
    print(f"wrote {out}: {args.frames} frames of {args.size} x {args.size} px to "
          f"t = {args.t_end:g} at {args.fps} frames/s "
          f"(engine {ds.attrs['engine']})")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="the gyroscope moving in space; write GIF or MP4")
    add_body_args(p)
    add_state_args(p)
    p.add_argument("--t-end", type=real(positive=True), default=20.0,
                   help="final time (default 20)")
    p.add_argument("--frames", type=count(2), default=200,
                   help=f"frames, evenly spaced in time (default 200, at most {MAX_FRAMES})")
    p.add_argument("--fps", type=count(1, 60), default=20, help="frames per second (default 20)")
    p.add_argument("--size", type=count(64, 4096), default=ANIMATION_SIZE,
                   help=f"side of the square frame in pixels (default {ANIMATION_SIZE})")
    add_term(p, "precession0", type=real(), default=0.0)
    add_engine_args(p)
    p.add_argument("--out", default="gyroscope.gif",
                   help="output file: .gif (Pillow) or .mp4 (needs ffmpeg)")
    p.set_defaults(func=run)
