"""Every list of chaos indicators is the registry's (:mod:`andoyer.analysis.chaos.registry`):
the map's choices, the CLI's, the scan task's, the colour scales and labels, the
atlas, the explorer's line and the variables of the datasets. A list typed by hand
somewhere that differs from the table fails here."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from andoyer.analysis.chaos.registry import (
    ALL_OF_THEM,
    INDICATORS,
    MAP_CHOICES,
    MAP_EXTRAS,
    MAP_INDICATORS,
    PANEL_INDICATORS,
    chosen,
)
from andoyer.integrate.engines.values import Capability, TangentFlow


def _cli_choices(module, dest: str) -> tuple[str, ...]:
    parser = argparse.ArgumentParser()
    module.register(parser.add_subparsers())
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    (command,) = sub.choices.values()
    action = next(a for a in command._actions if a.dest == dest)
    return tuple(action.choices)


def derived_lists() -> dict[str, tuple[str, ...]]:
    """Each list of indicators andoyer derives, by where it is used."""
    from andoyer.analysis.chaos import specs
    from andoyer.cli import chaos_map as cli_chaos_map
    from andoyer.explore.orbits import EXPLORER_INDICATORS
    from andoyer.plot import atlas, chaos, style
    from andoyer.scan.tasks import TASKS

    check = TASKS["chaos_map"].options["indicator"].check
    scan = []
    for name in INDICATORS:
        try:
            check("indicator", name)
            scan.append(name)
        except ValueError:
            pass
    return {
        "IndicatorRun choices": specs.INDICATOR_CHOICES,
        "andoyer chaos-map --indicator": _cli_choices(cli_chaos_map, "indicator"),
        "scan chaos_map indicator": tuple(scan),
        "plot.style.SCALES": tuple(k for k in style.SCALES if k in INDICATORS),
        "plot.chaos.COLOUR_BAR_LABELS": tuple(chaos.COLOUR_BAR_LABELS),
        "plot.atlas indicators": tuple(atlas._INDICATORS),
        "explorer line": EXPLORER_INDICATORS,
    }


def expected_lists() -> dict[str, tuple[str, ...]]:
    coloured = tuple(k for k, s in INDICATORS.items() if s.colours is not None)
    return {
        "IndicatorRun choices": MAP_CHOICES,
        "andoyer chaos-map --indicator": MAP_CHOICES,
        "scan chaos_map indicator": MAP_INDICATORS,
        "plot.style.SCALES": coloured,
        "plot.chaos.COLOUR_BAR_LABELS": coloured,
        "plot.atlas indicators": MAP_INDICATORS,
        "explorer line": (*PANEL_INDICATORS, *MAP_EXTRAS),
    }


def test_every_derived_list_is_the_registry():
    assert derived_lists() == expected_lists()


def test_the_check_catches_a_list_that_differs(monkeypatch):
    from andoyer.plot import atlas

    monkeypatch.setattr(atlas, "_INDICATORS", ("fli",))
    assert derived_lists()["plot.atlas indicators"] != expected_lists()["plot.atlas indicators"]


def test_labels_and_scales_are_the_rows():
    from andoyer.plot.chaos import COLOUR_BAR_LABELS
    from andoyer.plot.style import COLOUR_MAPS, SCALES

    for name, spec in INDICATORS.items():
        if spec.colours is None:
            continue
        scale = SCALES[name]
        assert (scale.cmap, scale.label, scale.vmin, scale.vmax) == (
            COLOUR_MAPS[spec.colours], spec.label, spec.vmin, spec.vmax)
        assert COLOUR_BAR_LABELS[name] == spec.label


def test_every_row_is_computable_and_needs_a_capability():
    n, k = 2, 5
    t = np.linspace(0.0, 4.0, k)
    rho = np.cumsum(np.ones((n, k, 1)), axis=1)
    flow = TangentFlow(t=np.broadcast_to(t, (n, k)), y=np.zeros((n, k, 6)),
                       u=np.zeros((n, k, 1, 6)), rho=rho, megno=np.ones((n, k, 2)),
                       count=np.full(n, k), ok=np.ones(n, dtype=bool))
    for name, spec in INDICATORS.items():
        Capability(spec.capability)
        value = spec.function()(flow, t)
        assert value.shape == (n, k), name
    assert chosen(ALL_OF_THEM) == MAP_INDICATORS
    assert set(MAP_EXTRAS) <= set(INDICATORS) and set(PANEL_INDICATORS) <= set(INDICATORS)


@pytest.mark.parametrize("indicator", MAP_CHOICES)
def test_chaos_map_stores_the_chosen_indicators_and_describes_them(indicator):
    from andoyer.analysis.chaos import IndicatorRun, chaos_map
    from andoyer.body import RigidBody

    ds = chaos_map(RigidBody.paper(), 0.2466, 0.0, "theta2=0", grid=2,
                   run=IndicatorRun(indicator, t_end=5.0, n_samples=4), engine="numba")
    stored = [k for k in ds.data_vars if k in INDICATORS]
    assert stored == [*chosen(indicator), *MAP_EXTRAS]
    for k in stored:
        assert ds[k].attrs["long_name"] == INDICATORS[k].long_name


def test_indicators_dataset_has_every_row():
    from andoyer.analysis.chaos import indicators
    from andoyer.body import RigidBody

    ds = indicators(RigidBody.paper(), [0.3, 0.0, 0.3, 1.0, 0.0], 5.0, n_times=3,
                    chart="andoyer", engine="numba")
    assert [k for k in ds.data_vars if k in INDICATORS] == list(INDICATORS)
    for k, spec in INDICATORS.items():
        assert ds[k].attrs["symbol"] == spec.symbol


def test_the_package_gives_the_functions_not_modules():
    """``from andoyer.analysis.chaos import indicators`` is the function (the module that
    defines it is :mod:`andoyer.analysis.chaos.lyapunov`), without a warning."""
    import warnings

    from andoyer.analysis.chaos import lyapunov

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        from andoyer.analysis.chaos import chaos_map, indicators
    assert indicators is lyapunov.indicators and chaos_map is lyapunov.chaos_map
    assert callable(indicators)
