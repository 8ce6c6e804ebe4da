"""Bad sizes and levels are refused before any work, naming the argument or the flag.

Each example comes from the issue's list "left from last round"; each class has a hunt:
huge counts on the command line end in the cost guard naming the flag (never "out of
memory"), levels and states beyond what the integrators take are refused naming the
argument (never "integration failed" or a division by zero inside a kernel).
"""

from __future__ import annotations

import pytest

from andoyer import RigidBody, propagate
from andoyer.cli import EXIT_CODES, main
from andoyer.integrate import budget, fill_section
from andoyer.scan import config as scan_config
from andoyer.scan import load_config
from andoyer.scan.cost import estimate_cost

BODY = RigidBody.paper()


def _fails(argv: list[str], capsys) -> tuple[int, str]:
    with pytest.raises(SystemExit) as exc:
        main(argv)
    return int(exc.value.code), capsys.readouterr().err


# ---------------------------------------------------------------------- the examples
@pytest.mark.parametrize("tol", [-1, 0.0, float("nan"), float("inf"), "x", True])
def test_fill_section_tol_is_validated(tol):
    """Before: tol = -1 ended in "please report this"."""
    with pytest.raises(ValueError, match="tol"):
        fill_section(BODY, 0.3, 0.0, ("g", 0.0), n_orbits=4, tol=tol)


def test_an_unreachable_tol_names_tol_not_a_bug():
    with pytest.raises(ValueError, match=r"above tol = 1e-300.*raise tol") as exc:
        fill_section(BODY, 0.3, 0.0, ("g", 0.0), n_orbits=4, tol=1e-300)
    assert "report" not in str(exc.value)


def test_section_at_a_huge_energy_names_the_flag(capsys):
    """Before: "integration failed" naming nothing (then a ZeroDivisionError in the
    kernel)."""
    code, err = _fails(["section", "--energy", "1e300", "--engine", "numba"], capsys)
    assert code == EXIT_CODES["bad input"]
    assert "--energy = 1e+300: the energy level reaches |G|" in err


@pytest.mark.parametrize("h", [1e201, 1e300, 1.7e308])
def test_fill_section_refuses_levels_beyond_the_integrators(h):
    with pytest.raises(ValueError, match=r"^h = .*beyond the 1e\+100"):
        fill_section(BODY, h, 0.0, ("g", 0.0), n_orbits=4)


@pytest.mark.parametrize("G", [1e101, 1e150, 1e300])
def test_states_beyond_the_integrators_are_refused(G):
    with pytest.raises(ValueError, match=r"^y0: \|G\| = .*beyond the 1e\+100"):
        propagate(BODY, [G, 0.0, 0.0, 0.0, 0.0, 1.0], [0.0, 1.0], engine="numba")


def test_orbit_n_out_1e9_is_the_cost_guard_naming_the_flag(capsys):
    """Before: "out of memory" (the 8 GB of output times were allocated first)."""
    code, err = _fails(["orbit", "--andoyer", "0.3,1,0.2,1,0", "--n-out", "1e9",
                        "--engine", "numba"], capsys)
    assert code == EXIT_CODES["cost limit"]
    assert "--n-out 1000000000: the results would take about 224 GiB" in err


def test_scan_num_1e12_is_refused_naming_the_key(tmp_path, capsys):
    """Before: "out of memory" (np.linspace of 1e12 values)."""
    cfg = tmp_path / "huge.toml"
    cfg.write_text('[parameters]\nmu = {start = 0.01, stop = 0.3, num = 1e12}\nh = 0.3\n'
                   '[task]\nkind = "section"\n')
    code, err = _fails(["scan", str(cfg), "--dry-run"], capsys)
    assert code == EXIT_CODES["bad input"]
    assert "[parameters] mu.num = 1000000000000 values: more than the 1000000" in err


def test_a_large_grid_loads_without_a_body_per_point(monkeypatch):
    """Before: an 810 000-point configuration took over 20 s to load (a body per
    point). Counted, not timed: the bodies built grow with the shapes, not the grid."""
    built = []
    real = scan_config.ScanConfig.body_at

    def counting(self, values):
        built.append(1)
        return real(self, values)

    monkeypatch.setattr(scan_config.ScanConfig, "body_at", counting)
    cfg = load_config({"parameters": {"mu": {"start": 0.01, "stop": 0.3, "num": 900},
                                      "A": {"start": 2.3, "stop": 2.6, "num": 900},
                                      "h": 0.3},
                       "task": {"kind": "section"}})
    assert cfg.n_points == 810_000
    assert len(built) <= 900 + 900
    assert estimate_cost(cfg).tasks == 810_000


def test_levels_out_of_reach_still_name_the_point():
    with pytest.raises(ValueError, match=r"M = 2 is out of reach on the level h = 0.1 "
                                         r"\(mu = 0.01"):
        load_config({"parameters": {"mu": [0.01, 0.3], "h": [0.1, 0.5], "M": [0.0, 2.0]},
                     "task": {"kind": "section"}})


# ---------------------------------------------------------------------- hunts
HUGE = ["1e9", "1e12", "1e15", "1e300"]


@pytest.mark.parametrize("value", HUGE)
@pytest.mark.parametrize("argv, flag", [
    (["orbit", "--andoyer", "0.3,1,0.2,1,0", "--n-out", "{}"], "--n-out"),
    (["section", "--n-orbits", "{}"], "--n-orbits"),
    (["section", "--n-crossings", "{}"], "--n-crossings"),
])
def test_hunt_huge_counts_end_in_the_guard_naming_the_flag(argv, flag, value, capsys):
    code, err = _fails([a.format(value) for a in argv] + ["--engine", "numba"], capsys)
    assert code in (EXIT_CODES["cost limit"], EXIT_CODES["bad input"]), err
    assert flag in err and "out of memory" not in err, err


# |G| beyond 1e100: states from 1e101, levels (h ~ G^2) from about 1e201.
@pytest.mark.parametrize("argv, flag, values", [
    (["orbit", "--y0", "{},0,0,0,0,1"], "--y0", ["1e101", "1e150", "1e300", "-1e300"]),
    (["orbit", "--andoyer", "0.3,1,0,{},0"], "--andoyer", ["1e101", "1e150", "1e300"]),
    (["section", "--energy", "{}"], "--energy", ["1e201", "1e250", "1e300", "1.7e308"]),
])
def test_hunt_huge_levels_and_states_are_refused_naming_the_flag(argv, flag, values,
                                                                capsys):
    for value in values:
        code, err = _fails([a.format(value) for a in argv] + ["--engine", "numba"], capsys)
        assert code == EXIT_CODES["bad input"], err
        assert flag in err and "integration failed" not in err and "internal" not in err


def test_the_momentum_limit_keeps_the_field_finite():
    """The bound is not arbitrary: at MAX_MOMENTUM the field and its error control are
    finite; at 1e150 they are not (what the refusal prevents)."""
    import numpy as np

    from andoyer import vector_field

    for G, finite in ((budget.MAX_MOMENTUM, True), (1e160, False)):
        f = vector_field(BODY, [G, 0.3 * G, 0.2 * G, 0.0, 0.6, 0.8])
        scaled = np.asarray(f) * G  # the step control multiplies once more
        assert bool(np.all(np.isfinite(scaled))) is finite, G
