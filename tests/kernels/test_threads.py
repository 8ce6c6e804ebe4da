"""Blocks of orbits in threads give the very numbers of one block on one thread."""

from __future__ import annotations

import numpy as np
import pytest

from andoyer import RigidBody, from_andoyer
from andoyer.kernels import common
from andoyer.kernels.dop853 import flow as dop
from andoyer.kernels.dop853 import tangent as kt
from andoyer.kernels.threads import block_starts

BODY = RigidBody(1.3, 1.7, 2.1, mu=0.7, r=(0.3, -0.5, 0.8))
P = np.array(BODY.engine_params)
Y0 = from_andoyer(np.column_stack([np.linspace(0.1, 3.0, 7), np.full(7, 0.4),
                                   np.linspace(-0.5, 0.6, 7), np.ones(7), np.zeros(7)]))


@pytest.mark.parametrize("threads, block", [(2, 1), (2, 3), (2, 0), (3, 2)])
def test_threads_change_nothing(threads: int, block: int) -> None:
    t = np.linspace(0.0, 20.0, 5)
    ref = dop.propagate(Y0, t, P, 1e-12, 1e-12, 10**6, threads=1)
    got = dop.propagate(Y0, t, P, 1e-12, 1e-12, 10**6, threads=threads, block=block)
    for a, b in zip(ref, got, strict=True):
        np.testing.assert_array_equal(a, b)
    ref = dop.locate_crossings(Y0, P, 2, 0.0, 1, 4, 200.0, 1e-12, 1e-12, 10**6, threads=1)
    got = dop.locate_crossings(Y0, P, 2, 0.0, 1, 4, 200.0, 1e-12, 1e-12, 10**6,
                               threads=threads, block=block)
    for a, b in zip(ref, got, strict=True):
        np.testing.assert_array_equal(a, b)
    assert got[2].sum() >= 8  # crossings were found (the comparison is not vacuous)


def test_tangent_kernels_in_threads() -> None:
    k = 2
    L = common.layout(k)
    z0 = np.zeros((Y0.shape[0], common.dimension(k)))
    z0[:, L["y"]] = Y0
    z0[:, L["u"]] = np.tile(np.eye(6)[:2].ravel(), (Y0.shape[0], 1))
    t = np.linspace(0.0, 10.0, 3)
    ref = kt.propagate(z0, t, P, 1e-12, 1e-12, 10**6, threads=1)
    got = kt.propagate(z0, t, P, 1e-12, 1e-12, 10**6, threads=2, block=2)
    for a, b in zip(ref, got, strict=True):
        np.testing.assert_array_equal(a, b)


def test_blocks_cover_every_orbit_once() -> None:
    for n in (1, 2, 7, 50):
        for threads in (1, 2, 4):
            for block in (0, 1, 3):
                starts = block_starts(n, threads, block)
                assert starts[0] == 0 and all(np.diff(starts) > 0) and starts[-1] < n
                if block == 0:
                    assert len(starts) <= threads
