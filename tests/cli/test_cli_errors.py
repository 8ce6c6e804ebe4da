"""One error boundary for the command line: one line on stderr, a distinct exit code per
class of expected failure, no traceback; outputs checked before any computation."""

import os
import subprocess
import sys

import pytest

from andoyer import cli
from andoyer.cli import EXIT_CODES, main
from andoyer.errors import CostLimitError, IntegrationError

ORBIT = ["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "1", "--n-out", "3"]


def run(argv, capsys):
    with pytest.raises(SystemExit) as info:
        main(argv)
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return info.value.code, err


@pytest.mark.parametrize("exc, kind", [
    (ValueError("bad value"), "bad input"),
    (TypeError("bad type"), "bad input"),
    (CostLimitError("too much"), "cost limit"),
    (PermissionError(13, "Permission denied", "/x/y.nc"), "file system"),
    (MemoryError(), "out of memory"),
    (IntegrationError("step size underflow"), "integration failed"),
    (ModuleNotFoundError("No module named 'heyoka'"), "missing dependency"),
    (RuntimeError("a bug"), "internal error"),
    (KeyboardInterrupt(), "interrupted"),
])
def test_each_failure_class_has_its_exit_code(monkeypatch, capsys, tmp_path, exc, kind):
    def boom(args):
        raise exc

    parser = cli.build_parser()
    monkeypatch.setattr(cli, "build_parser", lambda: parser)
    parser._subparsers._group_actions[0].choices["orbit"].set_defaults(func=boom)
    code, err = run([*ORBIT, "--out", str(tmp_path / "o.nc")], capsys)
    assert code == EXIT_CODES[kind]
    assert err.startswith("andoyer orbit: error:") and err.count("\n") == 1
    assert len(set(EXIT_CODES.values())) == len(EXIT_CODES)
    # --debug shows the traceback instead
    if not isinstance(exc, KeyboardInterrupt):
        with pytest.raises(type(exc)):
            main(["--debug", *ORBIT, "--out", str(tmp_path / "o.nc")])


@pytest.mark.parametrize("out, match", [
    ("sec.png", "must name a .nc file"),
    ("{tmp}", "must name a .nc file"),
    ("{tmp}/missing/o.nc", "does not exist"),
    ("{file}/o.nc", "is a file, not a folder"),
])
def test_outputs_are_checked_before_computing(capsys, tmp_path, monkeypatch, out, match):
    (tmp_path / "f").write_text("x")
    out = out.format(tmp=tmp_path, file=tmp_path / "f")
    calls = []
    monkeypatch.setattr("andoyer.integrate.api.propagate", lambda *a, **k: calls.append(1))
    code, err = run([*ORBIT, "--out", out], capsys)
    assert code == 2 and match in err and not calls
    assert list(tmp_path.iterdir()) == [tmp_path / "f"]  # nothing half-written


def test_read_only_folder_is_refused_before_computing(capsys, tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        code, err = run([*ORBIT, "--out", str(ro / "o.nc")], capsys)
    finally:
        ro.chmod(0o755)
    assert code == 2 and "not writable" in err and not list(ro.iterdir())


def test_section_out_must_be_netcdf_so_the_figure_cannot_overwrite_it(capsys):
    code, err = run(["section", "--out", "sec.png"], capsys)
    assert code == 2 and ".nc" in err


@pytest.mark.parametrize("argv, match", [
    (["--A", "3", "--B", "1", "--C", "2"], "--body paper does not take --A, --B, --C"),
    (["--body", "kovalevskaya", "--A", "2"], "does not take --A"),
    (["--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--r", "1", "0", "0"],
     "does not take --r"),
])
def test_flags_that_do_not_apply_are_refused(capsys, tmp_path, argv, match):
    code, err = run([*ORBIT, *argv, "--out", str(tmp_path / "o.nc")], capsys)
    assert code == 2 and match in err


def test_a_given_zero_is_not_replaced_by_a_default(capsys, tmp_path):
    code, err = run([*ORBIT, "--body", "kovalevskaya", "--C", "0",
                     "--out", str(tmp_path / "o.nc")], capsys)
    assert code == 2 and "argument --C: must be finite and > 0" in err


def test_cost_limit_from_the_command_line(capsys, tmp_path):
    code, err = run(["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "1e13",
                     "--out", str(tmp_path / "o.nc")], capsys)
    assert code == EXIT_CODES["cost limit"] and "--no-limits" in err


def test_real_process_prints_one_line_and_no_traceback(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "andoyer", *ORBIT, "--out",
                           str(tmp_path / "missing" / "o.nc")],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().startswith("andoyer orbit: error:")


def test_level_flags_have_the_api_names():
    parser = cli.build_parser()
    new = parser.parse_args(["section", "--energy", "0.25", "--M", "0.1"])
    assert (new.h, new.M) == (0.25, 0.1)


@pytest.mark.parametrize("argv, flag, want", [
    (["section", "--n-crossings", "0"], "--n-crossings", "an integer >= 1"),
    (["section", "--n-crossings", "2.5"], "--n-crossings", "an integer >= 1"),
    (["section", "--n-orbits", "abc"], "--n-orbits", "an integer >= 1"),
    (["orbit", "--andoyer", "0.3,1,0.2,1,0", "--n-out", "1"], "--n-out", "an integer >= 2"),
    (["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "nan"], "--t-end", "finite and > 0"),
    (["orbit", "--andoyer", "0.3,1,0.2,1,0", "--rtol", "-1"], "--rtol", "finite and > 0"),
    (["chaos-map", "--t-end", "-1"], "--t-end", "finite and > 0"),
    (["chaos-map", "--chunk", "0"], "--chunk", "an integer >= 1"),
    (["section", "--energy", "inf"], "--energy", "finite"),
    (["section", "--body", "hess", "--A", "-1"], "--A", "finite and > 0"),
    (["explore", "--port", "70000"], "--port", "an integer in [0, 65535]"),
    (["paper", "--jobs", "0"], "--jobs", "an integer >= 1"),
    (["scan", "x.toml", "--retries", "-1"], "--retries", "an integer >= 0"),
    (["manifolds", "--delta", "0"], "--delta", "finite and > 0"),
])
def test_number_flags_fail_at_parsing_naming_the_flag(capsys, tmp_path, monkeypatch, argv,
                                                      flag, want):
    """A bad count or real fails before any work, and the message names the flag the user
    typed (not the Python argument it becomes)."""
    monkeypatch.chdir(tmp_path)
    code, err = run(argv, capsys)
    assert code == EXIT_CODES["bad input"]
    assert f"argument {flag}: must be {want}, got " in err
    assert not any(tmp_path.iterdir())  # nothing written


def test_chaos_map_grid_is_checked_before_compiling(capsys, tmp_path):
    with pytest.raises(SystemExit) as info:
        main(["chaos-map", "--n", "8,1", "--out", str(tmp_path / "c.nc")])
    out, err = capsys.readouterr()
    assert info.value.code == EXIT_CODES["bad input"]
    assert "--n must be an integer >= 2, got 1" in err
    assert "compiled" not in out and not any(tmp_path.iterdir())


def test_matplotlibs_logged_warnings_are_the_warning_line(tmp_path):
    """Matplotlib logs its warnings (findfont: a font family not found, once per text
    drawn; building the font cache): they reached the command's stderr as raw lines
    (hundreds of ``findfont: ...``); now each distinct one is the CLI's warning line."""
    config = tmp_path / "mpl"
    config.mkdir()
    (config / "matplotlibrc").write_text("font.family: NoSuchFontAndoyer\n")
    proc = subprocess.run([sys.executable, "-m", "andoyer", "section", "--energy", "0.25",
                           "--n-orbits", "2", "--n-crossings", "2", "--engine", "scipy",
                           "--out", str(tmp_path / "s.nc")],
                          capture_output=True, text=True, timeout=120,
                          env={**os.environ, "MPLCONFIGDIR": str(config)})
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "s.png").exists()
    lines = [line for line in proc.stderr.replace("\r", "\n").splitlines()
             if line.strip() and "poincare (scipy)" not in line]  # progress bars aside
    assert lines, "no warning shown"
    assert all(line.startswith("andoyer section: warning: matplotlib: findfont: Font family")
               for line in lines), lines
    assert len(lines) == len(set(lines)) <= 2, lines


@pytest.mark.timeout(180)
def test_a_section_at_a_degenerate_level_returns(capsys, tmp_path):
    """andoyer section just above the minimum of H on theta2 = 3 pi/2 (h = -mu (1 - 1e-7),
    five orbits): no result after 300 s before; now the section in seconds (measured 14 s
    with the integration of the crossings), no traceback."""
    import time

    t0 = time.perf_counter()
    out = tmp_path / "s.nc"
    try:
        code = main(["section", "--energy=-0.009999999", "--section",
                     "theta2=4.71238898038469", "--n-orbits", "5", "--n-crossings", "5",
                     "--engine", "numba", "--out", str(out)])
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert code in (0, None) and "Traceback" not in err, err
    assert out.exists()
    assert time.perf_counter() - t0 < 120.0
