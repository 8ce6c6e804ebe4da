"""``andoyer animate`` (issue 27, item 4): an animated GIF through Pillow, written
atomically through ``cli._common.output_file``; bad outputs refused before any work;
an interrupted write leaves nothing behind."""

from __future__ import annotations

import pytest
from PIL import Image

from andoyer.cli import EXIT_CODES, main
from andoyer.plot import space

STATE = ["--andoyer", "0.3,1.1,0.2,1.0,-0.4", "--mu", "0.5", "--engine", "numba"]


def run(argv, capsys):
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code or 0, err


def test_animate_writes_a_gif_with_one_frame_per_time(tmp_path, capsys):
    out = tmp_path / "top.gif"
    code, _ = run(["animate", *STATE, "--frames", "12", "--t-end", "3", "--out", str(out)],
                  capsys)
    assert code == 0
    with Image.open(out) as im:
        assert im.format == "GIF" and im.n_frames == 12
    # nothing else but the manifest that records top.gif as andoyer's (andoyer.outputs)
    assert sorted(p.name for p in tmp_path.iterdir() if not p.name.endswith(".lock")) == [
        ".andoyer-manifest.json", "top.gif"]


@pytest.mark.parametrize("name, message", [("top.png", "must name a .gif or .mp4"),
                                           ("missing/top.gif", "does not exist")])
def test_bad_outputs_are_refused_before_any_work(tmp_path, capsys, name, message):
    code, err = run(["animate", *STATE, "--out", str(tmp_path / name)], capsys)
    assert code == EXIT_CODES["bad input"] and message in err


def test_mp4_without_ffmpeg_is_refused_naming_the_flag(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(space.writers, "is_available", lambda name: False)
    code, err = run(["animate", *STATE, "--out", str(tmp_path / "top.mp4")], capsys)
    assert code == EXIT_CODES["bad input"] and "--out" in err and "ffmpeg" in err


def test_an_interrupted_write_leaves_nothing_behind(tmp_path, capsys, monkeypatch):
    def interrupted(self):  # half the file written, then Ctrl-C
        with open(self.outfile, "wb") as f:
            f.write(b"GIF89a")
        raise KeyboardInterrupt

    monkeypatch.setattr(space._GifWriter, "finish", interrupted)
    out = tmp_path / "top.gif"
    code, _ = run(["animate", *STATE, "--frames", "6", "--t-end", "1", "--out", str(out)],
                  capsys)
    assert code == EXIT_CODES["interrupted"]
    assert [p for p in tmp_path.iterdir() if not p.name.endswith(".lock")] == []


def test_a_failing_encoder_gives_one_line_and_no_file(tmp_path, capsys, monkeypatch):
    """An encoder that fails (a fake ffmpeg exiting 3): one line naming it, its exit status
    and the last line of its stderr; exit code 'encoder failed'; no partial file. Before:
    exit 70 (internal error) with the raw CalledProcessError."""
    fake = tmp_path / "bin"
    fake.mkdir()
    exe = fake / "ffmpeg"
    exe.write_text("#!/bin/sh\necho 'ffmpeg version fake' >&2\n"
                   "echo 'Unknown encoder h264' >&2\nexit 3\n")
    exe.chmod(0o755)
    import os

    monkeypatch.setenv("PATH", f"{fake}:{os.environ['PATH']}")
    out = tmp_path / "films" / "top.mp4"
    out.parent.mkdir()
    code, err = run(["animate", *STATE, "--frames", "4", "--t-end", "1", "--out", str(out)],
                    capsys)
    assert code == EXIT_CODES["encoder failed"]
    lines = [line for line in err.splitlines() if line.strip() and "%" not in line]
    assert lines == [f"andoyer animate: error: the encoder ffmpeg failed with exit status 3: "
                     f"Unknown encoder h264; nothing was written to {str(out)!r}"], err
    assert not [p for p in out.parent.iterdir()
                if not p.name.endswith(".lock") and p.name != ".andoyer-manifest.json"]

def test_size_option_and_a_frame_without_a_blank_band(tmp_path, capsys):
    """``--size`` sets the square frame's side in pixels; the sphere fills the frame
    (its lowest and highest fifths are drawn on, not left blank)."""
    import numpy as np

    from andoyer.cli import animate

    assert animate.ANIMATION_SIZE == space.ANIMATION_SIZE
    out = tmp_path / "top.gif"
    code, _ = run(["animate", *STATE, "--frames", "3", "--t-end", "1", "--size", "300",
                   "--out", str(out)], capsys)
    assert code == 0
    with Image.open(out) as im:
        assert im.size == (300, 300)
        pixels = np.asarray(im.convert("L"), dtype=float)
    rows = (pixels < 250).mean(axis=1)  # the share of drawn (not white) pixels per row
    assert rows[-60:].max() > 0.2 and rows[:60].max() > 0.2, rows[::20]
    code, err = run(["animate", *STATE, "--size", "10", "--out", str(tmp_path / "x.gif")],
                    capsys)
    assert code != 0 and "--size" in err


def test_animate_in_a_pipe_prints_plain_progress_lines(tmp_path, capsys):
    """stderr no terminal (captured): the integration and the frames each end with a
    plain ``[n/n] label: 100 %, t s`` line, no bar redraws."""
    out = tmp_path / "top.gif"
    code, err = run(["animate", *STATE, "--frames", "6", "--t-end", "1", "--out", str(out)],
                    capsys)
    assert code == 0 and "\r" not in err
    assert "[6/6] frames of top.gif: 100 %" in err, err


def test_help_names_each_body_with_its_flags(capsys):
    """``animate --help`` lists ``--body lagrange`` with the flags it takes."""
    from andoyer.cli._common import BODY_FLAGS

    with pytest.raises(SystemExit):
        main(["animate", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for name, flags in BODY_FLAGS.items():
        assert f"{name}: " + " ".join(f"--{f}" for f in flags) in text, name
