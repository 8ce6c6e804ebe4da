"""chaos_map's options grouped (issue 25, item 6): MapGrid (where the orbits start),
IndicatorRun (what is integrated), engine options on the engine; the flat keywords of the
previous release still work for one release, warn, and give the same map."""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pytest

from andoyer import IndicatorRun, MapGrid, RigidBody
from andoyer.analysis.chaos.lyapunov import chaos_map
from andoyer.analysis.chaos.specs import FORMER_KEYWORDS, regroup
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


def test_former_keywords_warn_and_give_the_same_map() -> None:
    new = chaos_map(PAPER, H, 0.0, "theta2=0", MapGrid((4, 5), root="smallest"),
                    IndicatorRun("both", t_end=8.0, n_samples=16, tangent="energy",
                                 tol=1e-10),
                    engine=resolve_engine("numba", Capability.TANGENT, n_threads=1))
    former = {"n": (4, 5), "root": "smallest", "indicator": "both", "t_end": 8.0,
              "n_samples": 16, "tangent": "energy", "tol": 1e-10, "n_threads": 1}
    assert set(former) | {"plane_bounds", "batch_size"} == set(FORMER_KEYWORDS)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        old = chaos_map(PAPER, H, 0.0, "theta2=0", engine="numba", **former)
    messages = [str(w.message) for w in caught if w.category is DeprecationWarning]
    assert len(messages) == len(former)
    assert "chaos_map(t_end=...) is deprecated and will be removed in the next release; " \
           "use run=IndicatorRun(t_end=...)" in messages
    assert any("use grid=MapGrid(root=...)" in m for m in messages)
    assert any("resolve_engine(name, n_threads=...)" in m for m in messages)
    # the warning points at the caller, not at andoyer's wrappers
    assert {w.filename for w in caught if w.category is DeprecationWarning} == {__file__}
    assert int(new.accessible.sum()) > 0 and new.attrs["root"] == "smallest"
    for v in ("fli", "megno", "mle", "J2", "accessible"):
        np.testing.assert_array_equal(old[v].values, new[v].values)
    for key in ("t_end", "tolerance", "tangent", "indicator", "n_samples", "nx", "ny"):
        assert old.attrs[key] == new.attrs[key], key


def test_former_plane_bounds_and_engine_options_reach_their_place() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        grid, run, options = regroup(
            "chaos_map", MapGrid(6), IndicatorRun("megno"),
            {"plane_bounds": ((0.0, 3.0), (0.2, 0.4)), "batch_size": 4, "n_threads": 2})
    assert grid == MapGrid(6, plane_bounds=((0.0, 3.0), (0.2, 0.4)))
    assert run == IndicatorRun("megno")
    assert options == {"batch_size": 4, "n_threads": 2}
