"""The benchmark harness itself (nothing is timed here).

* the peers' hand-written equations and section functions are andoyer's derived ones
  (else the side-by-side would compare different problems);
* the peers find the crossings andoyer finds;
* the harness runs end to end on a tiny problem and writes a JSON file and a
  markdown table with the errors against the reference, the ratios and the targets.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

pytest.importorskip("heyoka")

from benchmarks.__main__ import main  # noqa: E402
from benchmarks.peers import heyoka_scripts as hs  # noqa: E402
from benchmarks.peers import model  # noqa: E402
from benchmarks.peers import scipy_scripts as ss  # noqa: E402

from andoyer import RigidBody, from_andoyer, to_hess  # noqa: E402
from andoyer.integrate import Section, poincare  # noqa: E402
from andoyer.kernels.generated.equations import ep_field  # noqa: E402
from benchmarks import harness, workloads  # noqa: E402
from benchmarks import reference as R  # noqa: E402

BODY = RigidBody.paper()
P = workloads.params(BODY)
RNG = np.random.default_rng(5)


def states(n: int) -> np.ndarray:
    G = RNG.uniform(0.8, 1.2, n)
    x = np.column_stack([RNG.uniform(0, 2 * np.pi, n), RNG.uniform(0, 2 * np.pi, n),
                         G * RNG.uniform(-0.9, 0.9, n), G, G * RNG.uniform(-0.5, 0.5, n)])
    return from_andoyer(x)


@pytest.mark.parametrize("body", [BODY, RigidBody(2.4, 1.9, 1.4, mu=0.5, r=(0.4, -0.3, 0.85))])
def test_peer_equations_are_andoyers_field(body: RigidBody) -> None:
    import heyoka as hy

    p = {**dict(zip(("a", "b", "c", "mu", "e1", "e2", "e3"), body.params, strict=True)),
         "phi0": 0.0}  # phi0 only enters the theta2 section
    y = states(20)
    G1, G2, G3, g1, g2, g3 = y.T
    want = np.array(ep_field(G1, G2, G3, g1, g2, g3, *body.params)).T
    np.testing.assert_allclose(np.array([model.rhs(p)(0.0, s) for s in y]), want,
                               rtol=1e-14, atol=1e-15)
    sys_ = model.heyoka_system(p, hy)
    cf = hy.cfunc([rhs for _, rhs in sys_], [v for v, _ in sys_])
    np.testing.assert_allclose(cf(np.ascontiguousarray(y.T)).T, want, rtol=1e-14, atol=1e-15)


def test_peer_theta2_section_is_the_hess_angle() -> None:
    y = states(50)
    for value in (0.0, 1.0, 5.5):
        f, w = model.numpy_section(P, "theta2", value)(y)
        theta2 = to_hess(BODY, y)[:, 1]
        d = np.angle(np.exp(1j * (np.arctan2(f, w) - (theta2 - value))))
        assert np.abs(d).max() < 1e-12


def test_peers_find_andoyers_crossings() -> None:
    y0 = workloads.initial_states(3)
    for name in ("G3", "theta2"):
        ds = poincare(BODY, y0, Section(name, 0.0, 1), 4, progress=False)
        for T, _ in (hs.plain_section(P, y0, name, 0.0, 4, 1e-12),
                     hs.ensemble_section(P, y0, name, 0.0, 4, 1e-12),
                     hs.tuned_section(P, y0, name, 0.0, 4, 1e-12, t_pilot=30.0),
                     ss.section(P, y0[:1], name, 0.0, 2, 1e-12, 1e-12)):
            np.testing.assert_allclose(T, ds.t.values[:len(T), :T.shape[1]], rtol=0, atol=1e-8)


@pytest.fixture
def heyoka_defaults(monkeypatch):
    """Orbits and component sections on heyoka, the defaults the rows of these tests were
    written for: the harness reads the defaults from MEASURED_DEFAULTS at each call."""
    from andoyer.integrate import engines

    monkeypatch.setattr(engines, "MEASURED_DEFAULTS", {
        k: v for k, v in engines.MEASURED_DEFAULTS.items()
        if k not in ("orbit", "component_section")})


def test_harness_end_to_end_on_a_tiny_problem(tmp_path, monkeypatch, heyoka_defaults) -> None:
    monkeypatch.setattr(R, "CACHE", tmp_path / "reference")
    sizes = workloads.Sizes(w1_t_end=20.0, w1_points=5, w2_orbits=4, w2_crossings=3,
                            scipy_orbits=1, repeat=1)
    out = harness.run(workloads=("W1", "W2"), sizes=sizes, sections=(("G3", 0.0),),
                      runners={"andoyer heyoka", "heyoka plain", "heyoka hand-tuned",
                               "scipy DOP853 serial"}, out_dir=tmp_path)
    data = json.loads((tmp_path / "results.json").read_text())
    assert data == json.loads(json.dumps(out, default=float))
    rows = {(r["workload"], r["runner"]): r for r in data["rows"]}
    assert set(rows) == {("W1", "andoyer heyoka"), ("W1", "heyoka plain"),
                         ("W2", "andoyer heyoka"), ("W2", "heyoka plain"),
                         ("W2", "heyoka hand-tuned"), ("W2", "scipy DOP853 serial")}
    for r in data["rows"]:
        assert r["wall_s"] > 0
        assert r["error_max"] < 1e-9  # measured against the reference, not assumed
    scipy = rows[("W2", "scipy DOP853 serial")]
    assert scipy["extra"]["orbits_run"] == 1 and "extrapolated" in scipy["note"]
    assert scipy["extra"]["scale"] > 1.0  # 4 orbits from 1, by integrated time
    assert math.isclose(scipy["wall_s"], scipy["extra"]["measured_wall_s"]
                        * scipy["extra"]["scale"])
    assert len(data["load_before"]) == 3 and data["meta"]["mode"] == "full"
    text = (tmp_path / "RESULTS.md").read_text()
    assert "| andoyer heyoka |" in text and "## Targets" in text
    names = [t["target"] for t in data["targets"]]
    assert any(n.startswith("W2 G3: andoyer default / hand-tuned") for n in names)
    # the machine limit of the default engine, from heyoka's step counter
    limit = rows[("W2", "andoyer heyoka")]["extra"]["limit"]
    assert limit["steps"] > 0 and 0 < limit["limit_s"] and limit["engine"] == "heyoka"
    assert "## Machine limits" in text and "x limit" in text
    assert len(list((tmp_path / "reference").glob("crossing-G3-*.json"))) == 1


def test_interleaved_timing_calls_the_runners_in_turn() -> None:
    """One warm-up call each, then rounds of one call each in turn; every runner gets its
    own walls (``repeat`` of them) and its last result."""
    calls: list[str] = []

    def runner(name: str):
        return lambda: calls.append(name) or len(calls)

    out = harness.timed_interleaved({"a": runner("a"), "b": runner("b")}, 3)
    assert calls == ["a", "b"] * 4
    assert [len(out[k][2]) for k in "ab"] == [3, 3]
    assert (out["a"][3], out["b"][3]) == (7, 8)
    assert all(out[k][0] >= 0.0 and out[k][0] in out[k][2] for k in "ab")


def test_reference_is_cached_and_extended_precision(tmp_path, monkeypatch) -> None:
    monkeypatch.setattr(R, "CACHE", tmp_path)
    y0 = workloads.initial_states(1)[0]
    a = R.orbit_end(P, y0, 10.0)
    assert len(list(tmp_path.glob("orbit-*.json"))) == 1
    stored = json.loads(next(tmp_path.glob("orbit-*.json")).read_text())
    assert np.finfo(np.longdouble).eps < 1e-18 and float(stored["tol"]) < 1e-18
    np.testing.assert_array_equal(R.orbit_end(P, y0, 10.0), a)  # from the cache
    double = hs.plain_orbit(P, y0, np.array([0.0, 10.0]), 1e-15)[-1]
    assert np.abs(double - a).max() < 1e-13


def test_targets_and_table_from_rows(heyoka_defaults) -> None:
    def row(wl: str, case: str, runner: str, wall: float, err: float = 1e-10
            ) -> harness.Row:
        return harness.Row(wl, case, runner, wall, wall, [wall], err, err)

    case = "50 orbits x 1000 crossings of G3 = 0 (upward)"
    rows = [row("W2", case, "andoyer heyoka", 1.0), row("W2", case, "heyoka hand-tuned", 1.2),
            row("W2", case, "heyoka plain", 3.5), row("W2", case, "andoyer numba", 4.0),
            row("W1", "1 orbit", "andoyer heyoka", 0.01),
            row("W1", "1 orbit", "heyoka plain", 0.005)]
    t = {x["target"]: x for x in harness.targets(rows)}
    assert t["W2 G3: andoyer default / hand-tuned heyoka <= 1.0"]["met"]
    assert math.isclose(t["W2 G3: plain heyoka loop / andoyer default >= 3"]["value"], 3.5)
    assert not t["W2 G3: andoyer numba / hand-tuned heyoka <= 3"]["met"]
    assert not t["W1: andoyer default / plain heyoka <= 1.2"]["met"]
    # the default (heyoka) is the fastest andoyer engine here: ratio 1
    assert t["W2 G3: andoyer default / fastest andoyer engine <= 1.1"]["value"] == 1.0
    text = harness.markdown({"meta": harness.meta("test", {}), "load_before": [0, 0, 0],
                             "load_after": [0, 0, 0], "targets": harness.targets(rows),
                             "rows": [harness.asdict(r) for r in rows]})
    assert "| heyoka hand-tuned | 1.20 s | 1.20 s | 1.20 |" in text
    assert "| W1: andoyer default / plain heyoka <= 1.2 | 2.00 | 1.2 | **no** |" in text


def test_issue_26_targets_and_the_engine_advice_from_rows(heyoka_defaults) -> None:
    """The taylor rows' targets (speed, error, cold start) and the generated "which engine
    for what" table: the fastest engine with heyoka and without it."""
    def row(wl: str, case: str, runner: str, wall: float, err: float = 1e-10,
            **extra: object) -> harness.Row:
        return harness.Row(wl, case, runner, wall, wall, [wall], err, err, extra=extra)

    g3 = "50 orbits x 1000 crossings of G3 = 0 (upward)"
    th = "50 orbits x 1000 crossings of theta2 = 0 (upward)"
    fli = "FLI map 64 x 64, t = 1000"
    rows = [row("W2", g3, "andoyer heyoka", 1.0, limit={"limit_s": 0.4}),
            row("W2", g3, "andoyer taylor", 1.5, 2e-10),
            row("W2", g3, "andoyer numba", 4.0),
            row("W2", th, "andoyer heyoka", 0.4), row("W2", th, "andoyer taylor", 0.2),
            row("W3", fli, "andoyer heyoka", 2.0), row("W3", fli, "andoyer taylor", 2.2),
            row("W4", "fresh process, cold on-disk caches", "andoyer taylor", 6.0,
                first_s=6.0, second_s=0.5, caches="cold")]
    t = {x["target"]: x for x in harness.targets(rows)}
    assert not t["W2 G3: andoyer taylor / andoyer heyoka <= 1.2"]["met"]
    assert t["W3 FLI map: andoyer taylor / andoyer heyoka <= 1.2"]["met"]
    assert math.isclose(t["W2 G3: andoyer heyoka within 2x its machine limit"]["value"], 2.5)
    assert not t[f"W2 {g3}: taylor's error within 1.5x of heyoka's (median, max)"]["met"]
    assert t[f"W2 {th}: taylor's error within 1.5x of heyoka's (median, max)"]["met"]
    half = next(x for x in t.values() if x["target"].startswith("W2 theta2: fastest"))
    assert "andoyer taylor" in half["target"] and half["met"]  # 0.2 s <= 0.5 x 0.432 s
    assert not t["W4: andoyer taylor, cold first call <= 5 s"]["met"]
    advice = "\n".join(harness.engine_advice(rows))
    # the defaults come from MEASURED_DEFAULTS (fli_map: taylor), not from these rows
    assert (f"| W2: {g3} | heyoka | heyoka (taylor takes 1.50x) | taylor | "
            "taylor (numba takes 2.67x) |") in advice
    assert (f"| W2: {th} | taylor | taylor (heyoka takes 2.00x) | taylor | "
            "taylor (only one measured) |") in advice
    assert (f"| W3: {fli} | taylor | heyoka (taylor takes 1.10x) | taylor | "
            "taylor (only one measured) |") in advice


def test_tables_are_rewritten_from_results_json(tmp_path) -> None:
    """``python -m benchmarks --tables``: RESULTS.md and SUMMARY.md from results.json
    alone (nothing runs), the same text as the run wrote."""
    row = harness.Row("W1", "1 orbit to t = 10000, 1001 outputs", "andoyer heyoka", 0.01,
                      0.01, [0.01])
    result = {"meta": {**harness.meta("quick", {}), "date": "2026-01-01T00:00:00+00:00"},
              "load_before": [0, 0, 0], "load_after": [0, 0, 0], "targets": [],
              "rows": [harness.asdict(row)], "scaling": []}
    (tmp_path / "results.json").write_text(json.dumps(result))
    assert main(["--tables", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "SUMMARY.md").read_text() == harness.summary(result)
    assert (tmp_path / "RESULTS.md").read_text() == harness.markdown(result)


@pytest.mark.parametrize("engine", ["heyoka", "numba"])
def test_machine_limit_counts_the_engines_steps(engine) -> None:
    from benchmarks import limits

    b = workloads.body()
    y0 = workloads.initial_states(2)
    fn = limits.heyoka_limit if engine == "heyoka" else limits.numba_limit
    one, two = (fn(b, y0, np.array([t, t]), 1e-12) for t in (50.0, 100.0))
    # steps grow in proportion to the span (a quasi-periodic orbit steps at a steady rate)
    assert 1.8 < two.steps / one.steps < 2.2
    assert one.step_s > 0 and math.isclose(one.limit_s, one.steps * one.step_s)
    single = fn(b, y0[:1], np.array([100.0]), 1e-12, single_orbit=True)
    assert single.steps < two.steps and "one orbit" in single.note


def test_command_line_rejects_unknown_names() -> None:
    with pytest.raises(SystemExit):
        main(["--workloads", "W9"])
    with pytest.raises(SystemExit):
        main(["--runners", "fortran"])


def test_summary_table_goes_between_the_readme_markers(tmp_path, heyoka_defaults) -> None:
    row = harness.Row("W1", "1 orbit", "andoyer heyoka", 0.01, 0.01, [0.01],
                      extra={"limit": {"limit_s": 0.004}})
    paper = harness.Row("W5", "andoyer paper", "andoyer heyoka", 17.5, math.nan, [17.5])
    result = {"meta": harness.meta("full", {}), "rows": [harness.asdict(row),
                                                         harness.asdict(paper)]}
    text = harness.summary(result)
    assert "| W1: 1 orbit | 10.0 ms | – |" in text and "| 2.5x |" in text
    assert "17.50 s" in text
    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n{harness.README_START}\nold\n{harness.README_END}\nend\n")
    assert harness.update_readme(text, readme)
    new = readme.read_text()
    assert "old" not in new and text in new and new.endswith(f"{harness.README_END}\nend\n")
    (tmp_path / "plain.md").write_text("no markers")
    assert not harness.update_readme(text, tmp_path / "plain.md")


def test_issue_36_targets_tables_and_the_megno_advice_from_rows(heyoka_defaults) -> None:
    """Issue 36's targets from rows (nothing timed): section / bare flow, theta2 against
    the fastest engine before the issue, G3 at two sizes, the MEGNO map and the 256^2 FLI
    map on their defaults, the lane widths, the main job; W6's and W7's tables; the MEGNO
    map's row of "which engine for what" is the ``megno_map`` workload's."""
    def row(wl: str, case: str, runner: str, wall: float, note: str = "",
            **extra: object) -> harness.Row:
        return harness.Row(wl, case, runner, wall, wall, [wall], note=note, extra=extra)

    load = [[1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]
    cost = "16 orbits over the span of 300 theta2 = 0 crossings"
    w6 = [row("W6", cost, label, cpu, steps=1000, ns_per_step=cpu, over_bare=cpu / 0.1,
              over_limit=cpu / 0.1, load=load)
          for label, cpu in (("bare flow (lanes)", 0.1), ("G3 = 0 lanes", 0.12),
                             ("theta2 = 0 lanes", 0.3), ("g = 0 lanes", 0.14))]

    def lanes(k: int, flow: float, diff: float, runner: str = "") -> harness.Row:
        return row("W7", "lane kernels", runner or f"{k} lanes", 1.0, lanes=k,
                   ns_per_orbit_step={"flow": flow, "G3": 300.0}, steps={"flow": 5, "G3": 5},
                   steps_equal=True, diff_from_8={"flow_end": diff, "crossing_t": 0.0},
                   load=[1.0, 1.0])

    g3, g3s = ("50 orbits x 1000 crossings of G3 = 0 (upward)",
               "20 orbits x 400 crossings of G3 = 0 (upward)")
    th = "50 orbits x 1000 crossings of theta2 = 0 (upward)"
    megno, big = "MEGNO map 64 x 64, t = 1000", "FLI map 256 x 256, t = 1000"
    rows = [*w6, lanes(4, 250.0, 3e-15), lanes(4, 210.0, 0.0, "4 lanes, AVX2"),
            lanes(8, 200.0, 0.0),
            row("W2", g3, "andoyer heyoka", 1.0), row("W2", g3, "andoyer taylor", 0.9),
            row("W2", g3s, "andoyer heyoka", 0.2), row("W2", g3s, "andoyer taylor", 0.28),
            row("W2", th, "andoyer heyoka", 0.4), row("W2", th, "andoyer taylor", 0.15),
            row("W3", megno, "andoyer heyoka", 5.0), row("W3", megno, "andoyer taylor", 3.0),
            row("W3", big, "andoyer taylor", 30.0, note="timed once"),
            row("W3", big, "heyoka hand-tuned", 50.0, note="timed once"),
            row("W5", "andoyer paper", "andoyer heyoka", 17.0)]
    t = {x["target"]: x for x in harness.targets(rows)}
    assert t["W6 G3 = 0: section on lanes / bare lane flow <= 1.5"]["met"]
    assert not t["W6 theta2 = 0: section on lanes / bare lane flow <= 1.5"]["met"]
    assert t["W6 g = 0: section on lanes within 2x its machine limit"]["met"]
    third = next(x for x in t.values() if x["target"].startswith("W2 theta2: fastest andoyer "
                                                                  "engine (andoyer taylor)"))
    assert "481.5 ms" in third["target"] and third["met"]  # 150 ms <= 481.5 / 3
    assert t["W2 G3 50 orbits x 1000: andoyer taylor / andoyer heyoka <= 1.0"]["met"]
    assert not t["W2 G3 20 orbits x 400: andoyer taylor / andoyer heyoka <= 1.0"]["met"]
    # the issue-26 targets of W2 G3 read the 50 x 1000 case alone
    assert math.isclose(t["W2 G3: andoyer default / fastest andoyer engine <= 1.1"]["value"],
                        1.0 / 0.9)
    assert math.isclose(t["W2 G3: andoyer taylor / andoyer heyoka <= 1.2"]["value"], 0.9)
    assert t[f"W3 {megno}: default (andoyer taylor) / andoyer heyoka <= 1.0"]["met"]
    assert math.isclose(t[f"W3 {big}: default (andoyer taylor) / hand-written heyoka "
                          "ensemble <= 0.7"]["value"], 0.6)
    flow = t["W7 flow: ns per orbit-step, 4 lanes / 8 lanes within 10 % (max(x, 1/x))"]
    assert math.isclose(flow["value"], 1.25) and not flow["met"]
    assert t["W7 flow: ns per orbit-step, 4 lanes, AVX2 / 8 lanes within 10 % (max(x, 1/x))"][
        "met"]
    assert t["W7 G3: ns per orbit-step, 4 lanes / 8 lanes within 10 % (max(x, 1/x))"]["met"]
    same = next(x for x in t.values() if x["target"].startswith("W7: results"))
    assert same["met"] and same["value"] == 3e-15
    assert not t["W5: andoyer paper, warm caches, <= 15 s (issue 36)"]["met"]
    text = harness.markdown({"meta": harness.meta("test", {}), "load_before": [0, 0, 0],
                             "load_after": [0, 0, 0], "targets": harness.targets(rows),
                             "rows": [harness.asdict(r) for r in rows]})
    assert "## W6: section / bare flow" in text and "| theta2 = 0 lanes | 300.0 ms |" in text
    assert "## W7: lane widths" in text and "| 4 lanes | 250 | 300 | True |" in text
    advice = "\n".join(harness.engine_advice(rows))
    assert (f"| W3: {megno} | taylor | taylor (heyoka takes 1.67x) | taylor | "
            "taylor (only one measured) |") in advice


@pytest.mark.parametrize("moved", [{}, {"angle_section": "taylor"}])
def test_the_default_of_a_target_is_the_workloads_default(
        monkeypatch: pytest.MonkeyPatch, moved: dict[str, str]) -> None:
    """"andoyer default" in a target is the engine ``engine=None`` runs for that workload
    (MEASURED_DEFAULTS), not heyoka's row: a moved default moves the ratios, and
    ``--tables`` recomputes them from the rows."""
    from andoyer.integrate import engines

    monkeypatch.setattr(engines, "MEASURED_DEFAULTS", moved)
    th = "50 orbits x 1000 crossings of theta2 = 0 (upward)"
    rows = [harness.Row("W2", th, runner, wall, wall, [wall], 1e-11, 1e-11)
            for runner, wall in (("andoyer heyoka", 0.4), ("andoyer taylor", 0.2),
                                 ("heyoka plain", 1.0))]
    t = {x["target"]: x["value"] for x in harness.targets(rows)}
    taylor = moved.get("angle_section") == "taylor"
    assert t["W2 theta2: andoyer default / fastest andoyer engine <= 1.1"] == \
        (1.0 if taylor else 2.0)
    assert math.isclose(t["W2 theta2: plain heyoka loop / andoyer default >= 3"],
                        5.0 if taylor else 2.5)
    assert harness.default_runner("W2", th) == ("andoyer taylor" if taylor else
                                                "andoyer heyoka")
