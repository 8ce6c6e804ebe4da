"""The island chains to orders 1-3 in mu against the sections (benchmarks.resonance_orders).

The laws, as fitted slopes of log |error| against log mu, on the measured table
``benchmarks/resonance_orders.json`` (which the tutorial shows) and, re-measured, on
Hess(3, 1, 2) (slow) and the paper's body (slow). For p = 1 chains (docstring of
``andoyer.analysis.resonance.second_order``): the half-width's relative error is O(mu) for
the pendulum R6, O(mu^2) at order 2 (the mu^3 resonant harmonic is missing: odd orders
only bring it), O(mu^3) at order 3; the stable point misses by O(mu^2) (R10) and O(mu^3)
(order 2)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from benchmarks import resonance_orders as ro

RECORDS = json.loads(ro.RESULTS.read_text())


def _chain(body, label):
    return [r for r in RECORDS if r["case"]["body"] == body and r["case"]["label"] == label]


def _record(body, label, mu):
    return next(r for r in _chain(body, label) if r["case"]["mu"] == mu)


def test_the_tables_are_the_rendering_of_the_measurements():
    assert ro.TABLES.read_text() == ro.render(RECORDS), \
        "RESONANCE_ORDERS.md differs: python -m benchmarks.resonance_orders"
    assert "```{include} ../../benchmarks/RESONANCE_ORDERS.md" in (
        ro.HERE.parent / "docs/tutorials/resonances.md").read_text()
    assert {(r["case"]["body"], r["case"]["label"]) for r in RECORDS} == {
        ("hess", "3:1"), ("hess", "2:1"), ("paper", "7:1"), ("paper", "8:1")}


@pytest.mark.parametrize("label", ["3:1", "2:1"])
def test_hess_widths_fall_from_order_mu_to_mu2(label):
    """Hess(3, 1, 2), mu = 1e-4 .. 1e-3: R6's relative error has slope 1 +- 0.2 (measured
    1.03, 1.01); order 2's falls at least like mu^2 over the points the measurement
    resolves (slope > 1.8; measured 3.0 and 2.0: at mu = 1e-3 the 3:1 island measures
    5.9e-5 narrower than orders 2 and 3 alike); at mu = 1e-3 order 2 errs < 5 % of R6
    (measured 0.4 %, 0.05 %)."""
    row = ro.slopes(RECORDS)[f"hess {label}"]
    assert abs(row["width R6"] - 1.0) < 0.2, row
    assert row["width order 2"] > 1.8, row
    e = ro.width_errors(_record("hess", label, 1e-3))
    assert abs(e["order 2"]) < 0.05 * abs(e["R6"]), e


@pytest.mark.parametrize("label", ["7:1", "8:1"])
def test_paper_widths_second_order_mu2_third_order_better(label):
    """The paper's body, mu = 0.0025 .. 0.01: order 2's relative error has slope 2 +- 0.3
    (measured 2.02), and is the mu^3 resonant harmonic: order 3 removes nine tenths of it
    at mu >= 0.005 (measured 0.038 % against 4.0 % at 0.01 on 7:1)."""
    row = ro.slopes(RECORDS)[f"paper {label}"]
    assert abs(row["width order 2"] - 2.0) < 0.3, row
    for r in _chain("paper", label):
        if r["case"]["mu"] >= 5e-3:
            e = ro.width_errors(r)
            assert abs(e["order 3"]) < 0.1 * abs(e["order 2"]), (r["case"], e)


@pytest.mark.parametrize("body, label", [("hess", "3:1"), ("hess", "2:1"), ("paper", "7:1"),
                                         ("paper", "8:1")])
def test_stable_point_misses_like_mu2_then_mu3(body, label):
    """R10 misses the measured stable point by O(mu^2) (slope 2 +- 0.3; measured 2.00,
    2.15, 2.00, 2.00); on the paper's body order 2 by O(mu^3) (slope > 2.6; measured 3.4)
    and order 3 by O(mu^4) (slope > 3.5; measured 4.0), and at mu = 0.01 the order-2
    stable point lies inside the measured island, R10's outside; on Hess(3, 1, 2) order 2
    is at the stable search's resolution (~5e-6 half-widths) but at mu = 1e-3, where it
    misses by less than a quarter of R10's miss."""
    row = ro.slopes(RECORDS)[f"{body} {label}"]
    assert abs(row["position R10"] - 2.0) < 0.3, row
    if body == "paper":
        assert row["position order 2"] > 2.6 and row["position order 3"] > 3.5, row
        r = _record(body, label, 1e-2)
        assert r["s_inner"] < r["predicted"]["stable_s"][1] < r["s_outer"]
        assert not r["s_inner"] < r["predicted_stable_s"] < r["s_outer"]
    else:
        miss = ro.position_misses(_record(body, label, 1e-3))
        assert abs(miss["order 2"]) < 0.25 * abs(miss["R10"]), miss


def test_second_order_against_the_measured_hess_chain_cheap():
    """Cheap (no integration): island_prediction on Hess(3, 1, 2), 3:1, mu = 1e-3, against
    the measured half-width and libration frequency of the table: order 2 within 2e-4 and
    5e-4 (measured 8.5e-5 and 2.7e-4), order 1's frequency 9.5e-3 off. It fails with K2 = 0
    (frequency 1.2e-3 off) or with the order-2 brackets of the triangle dropped."""
    from andoyer.analysis.resonance import island_prediction

    r = _record("hess", "3:1", 1e-3)
    ds = island_prediction(ro.make_body(ro.Case(**r["case"])), 1.0, 0.0, "3:1", axis=1)
    w1, w2 = ds.half_width.values / r["measured_half_width"] - 1.0
    o1, o2 = ds.libration_frequency.values / r["measured_libration_frequency"] - 1.0
    assert abs(w2) < 2e-4 and abs(o2) < 5e-4, (w2, o2)
    assert abs(o1) > 5e-3 and abs(w1) > 2 * abs(w2), (w1, o1)
    assert abs(ds.stable_s.values[1] - r["stable_s"]) < 0.25 * abs(
        r["stable_s"] - r["predicted_stable_s"])


@pytest.mark.slow
def test_hess_3_1_remeasured():
    """Re-measured (numba, 3 seeds, 10 rounds, no stable search; about 2 minutes): the
    half-widths agree with the table's to the edge resolution, R6's error has slope
    1 +- 0.2 (measured 1.04), order 2's falls at least like mu^2 (slope > 1.8; measured 3.7
    over mu = 2e-4 .. 1e-3, steepened by the island's edge at 1e-3)."""
    from andoyer.analysis.resonance.measure import measure_island

    mus, r6, o2 = [], [], []
    for r in _chain("hess", "3:1"):
        case = ro.Case(**r["case"])
        if case.mu < 2e-4:
            continue        # order 2 is at the edge resolution there
        m = measure_island(ro.make_body(case), 1.0, 0.0, "3:1", axis=1, n_seeds=3,
                           n_rounds=10, stable=False, engine="numba")
        w = float(m.measured_half_width)
        assert abs(w - r["measured_half_width"]) < 2 * float(m.edge_uncertainty) \
            + 2 * r["edge_uncertainty"]
        mus.append(case.mu)
        r6.append(abs(float(m.predicted_half_width) / w - 1))
        o2.append(abs(ro.predict(case)["half_width"][1] / w - 1))
    fit = [np.polyfit(np.log(mus), np.log(e), 1)[0] for e in (r6, o2)]
    assert abs(fit[0] - 1.0) < 0.2 and fit[1] > 1.8, fit


@pytest.mark.slow
def test_paper_7_1_remeasured_at_two_mu():
    """The paper's 7:1 chain at mu = 0.005 and 0.01, re-measured (some 10 minutes): order
    2's relative width error grows 4x when mu doubles (3 to 5.5x), order 3's stays below a
    tenth of it."""
    from andoyer.analysis.resonance.measure import measure_island

    err2, err3 = [], []
    for mu in (5e-3, 1e-2):
        case = ro.Case("paper", "7:1", mu, 6)
        m = measure_island(ro.make_body(case), ro.LEVELS["paper"], 0.0, "7:1", axis=1,
                           n_seeds=3, n_rounds=6, stable=False, engine="numba")
        w = float(m.measured_half_width)
        pred = ro.predict(case)["half_width"]
        err2.append(abs(pred[1] / w - 1))
        err3.append(abs(pred[2] / w - 1))
    assert 3.0 < err2[1] / err2[0] < 5.5, err2
    assert err3[1] < 0.1 * err2[1] and err3[0] < 0.1 * err2[0], (err2, err3)
