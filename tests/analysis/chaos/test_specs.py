"""chaos_map's options grouped (issue 25, item 6): MapGrid (where the orbits start),
IndicatorRun (what is integrated), engine options on the engine; the flat keywords that
came before them are unknown keywords (nothing was released)."""

from __future__ import annotations

import dataclasses

import pytest

from andoyer import IndicatorRun, MapGrid, RigidBody
from andoyer.analysis.chaos.lyapunov import chaos_map
from andoyer.integrate.engines import resolve_engine
from andoyer.integrate.engines.base import Capability

PAPER = RigidBody.paper(0.5)
H = 0.3733  # two sheets over some points of theta2 = 0: root matters


def test_specs_normalise_and_are_frozen() -> None:
    assert MapGrid(8).n == (8, 8) and MapGrid((8, 4)).shape == (4, 8)
    assert MapGrid(4, plane_bounds=[(0, 1), (0.1, 0.5)]).plane_bounds == ((0.0, 1.0),
                                                                           (0.1, 0.5))
    assert IndicatorRun(t_end=5).t_end == 5.0 and isinstance(IndicatorRun(t_end=5).t_end,
                                                             float)
    assert not IndicatorRun().renormalised and IndicatorRun("megno").renormalised
    with pytest.raises(dataclasses.FrozenInstanceError):
        MapGrid().n = (3, 3)  # type: ignore[misc]
    assert MapGrid.of(MapGrid(5)) == MapGrid(5) == MapGrid.of((5, 5))


@pytest.mark.parametrize(("make", "name"), [
    (lambda: MapGrid(1), "n"), (lambda: MapGrid((4,)), "n"),  # type: ignore[arg-type]
    (lambda: MapGrid(4, plane_bounds=((0, 1), (2, 1))), "plane_bounds"),
    (lambda: MapGrid(4, root="middle"), "root"),  # type: ignore[arg-type]
    (lambda: IndicatorRun("lyapunov"), "indicator"),  # type: ignore[arg-type]
    (lambda: IndicatorRun(t_end=0.0), "t_end"), (lambda: IndicatorRun(n_samples=0), "n_samples"),
    (lambda: IndicatorRun(tangent="sphere"), "tangent"),  # type: ignore[arg-type]
    (lambda: IndicatorRun(tol=0.1), "tol"), (lambda: IndicatorRun(tol=True), "tol"),
])
def test_specs_refuse_bad_fields_naming_them(make, name) -> None:
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        make()


def test_chaos_map_refuses_what_is_not_a_grid_or_a_run() -> None:
    with pytest.raises(ValueError, match="grid must be a MapGrid"):
        chaos_map(PAPER, H, 0.0, "theta2=0", "8")
    with pytest.raises((TypeError, ValueError), match="run must be a.? IndicatorRun"):
        chaos_map(PAPER, H, 0.0, "theta2=0", 4, 10.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="unexpected keyword argument 'n_orbits'"):
        chaos_map(PAPER, H, 0.0, "theta2=0", n_orbits=4)


def test_the_grid_and_the_run_give_the_map_and_flat_keywords_are_refused() -> None:
    new = chaos_map(PAPER, H, 0.0, "theta2=0", MapGrid((4, 5), root="smallest"),
                    IndicatorRun("both", t_end=8.0, n_samples=16, tangent="energy",
                                 tol=1e-10),
                    engine=resolve_engine("numba", Capability.TANGENT, n_threads=1))
    assert int(new.accessible.sum()) > 0 and new.attrs["root"] == "smallest"
    assert (new.attrs["nx"], new.attrs["ny"], new.attrs["t_end"]) == (4, 5, 8.0)
    for former in ("n", "plane_bounds", "root", "indicator", "t_end", "n_samples", "tangent",
                   "tol", "batch_size", "n_threads"):
        with pytest.raises(TypeError, match=f"unexpected keyword argument '{former}'"):
            chaos_map(PAPER, H, 0.0, "theta2=0", **{former: 1})
