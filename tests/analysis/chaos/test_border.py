"""The chaotic fraction and the layer around the former Hess separatrix.

Routes: by construction the free top (mu = 0, integrable) has no chaotic cell (its own
grid is the reference); a heavy Hess body has a wide chaotic layer (as the FLI maps of
tests/analysis/chaos/test_indicators.py show); the layer measure on synthetic masks; the Hess line
of a turned body at 2 epsilon in its chart.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.chaos.border import chaos_border, hess_line, layer_width

HEAVY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)


def test_the_free_top_has_no_chaos_and_a_heavy_top_has_much() -> None:
    free = RigidBody(3.0, 1.0, 2.0, 0.0, HEAVY.r)
    assert float(chaos_border(free, 1.0, n=12, t_end=150.0).chaotic_fraction) == 0.0
    ds = chaos_border(HEAVY, 1.0, n=12, t_end=150.0)
    f = float(ds.chaotic_fraction)
    assert 0.2 < f < 0.9
    # the sensitivity band brackets the value: a lower threshold finds more chaos
    assert float(ds.chaotic_fraction_high) <= f <= float(ds.chaotic_fraction_low)
    assert float(ds.threshold) == pytest.approx(float(ds.reference_max) + 1.0)
    assert ds.chaotic.dims == ds.megno.dims and ds.chaotic_fraction.attrs["long_name"]


def test_hess_line_of_a_turned_body() -> None:
    assert hess_line(RigidBody.hess(3.0, 1.0, 2.0, mu=0.1)) == pytest.approx(0.0, abs=1e-12)
    for eps in (0.05, 0.3, -0.2):
        b = RigidBody.near_hess(3.0, 1.0, 2.0, mu=0.1, epsilon=eps)
        assert hess_line(b) == pytest.approx(np.mod(2 * eps, 2 * math.pi), abs=1e-12)
    assert math.isnan(hess_line(RigidBody(2.0, 2.5, 3.0, 0.1, (1.0, 0.0, 0.0))))


def test_layer_width_follows_the_line_across_the_wrap() -> None:
    nx = 12
    th = (np.arange(nx) + 0.5) * 2 * math.pi / nx
    cell = 2 * math.pi / nx
    c = np.zeros((3, nx), dtype=bool)
    c[0, [0, 1, nx - 1]] = True        # through 0, across the wrap: 3 cells
    c[1, [3, 4]] = True                # away from 0: none through the line 0
    acc = np.ones_like(c)
    acc[2] = False                     # a row off the level is left out
    w, med = layer_width(c, acc, th)
    assert w[0] == pytest.approx(3 * cell) and w[1] == 0.0 and math.isnan(w[2])
    assert med == pytest.approx(1.5 * cell)
    w, _ = layer_width(c, acc, th, line=4 * cell)       # the line between cells 3 and 4
    assert w[1] == pytest.approx(2 * cell) and w[0] == 0.0


def test_bad_input_is_refused() -> None:
    with pytest.raises(ValueError, match="margin"):
        chaos_border(HEAVY, 1.0, n=8, t_end=50.0, margin=0.0)
    with pytest.raises(ValueError, match="section"):
        chaos_border(HEAVY, 1.0, section=("G3", 0.0), n=8, t_end=50.0)
