"""Every variant of a factory-made kernel has a name of its own.

Numba names machine code after a function's qualified name and a per-process counter:
two variants with one qualified name, compiled by two processes into the on-disk cache,
can share a symbol, and a process loading both then runs one body for both (seen: tangent
crossings of G3 = 0 running the state's loop after two test workers filled a fresh
cache; numba/numba#10486). :func:`andoyer.kernels.common.variant` tags each variant.
"""

from __future__ import annotations

import itertools

import pytest

from andoyer.kernels.common import variant
from andoyer.kernels.dop853 import attitude
from andoyer.kernels.dop853 import flow as dop853_flow
from andoyer.kernels.dop853 import tangent as dop853_tangent
from andoyer.kernels.taylor import flow


def _name(f: object) -> str:
    return getattr(f, "py_func", f).__qualname__


def test_taylor_orbit_loops_and_entry_points_are_named_per_variant() -> None:
    kinds = (flow.STATE, flow.TANGENT, flow.ATTITUDE)
    for field in ("take_step", "propagate_orbit", "record"):
        names = [_name(getattr(k, field)) for k in kinds]
        assert len(set(names)) == 3, names
    loops = [_name(f) for k in kinds for f in (*k.crossings_orbit, *k.crossings_from)]
    assert len(set(loops)) == len(loops), loops
    entries = [_name(f) for f in flow.CROSSINGS_BLOCKS.values()]
    assert len(set(entries)) == len(entries) == 6, entries
    assert _name(flow.CROSSINGS_BLOCKS[(True, 0)]).endswith("__tangent_component")


def test_dop853_steppers_are_named_per_field() -> None:
    steppers = (dop853_flow.EP, attitude._STEPPER, dop853_tangent._STEPPER)
    for a, b in itertools.combinations(steppers, 2):
        for f, g in zip(a, b, strict=True):
            assert _name(f) != _name(g), (_name(f), _name(g))


def test_a_tag_is_a_plain_name() -> None:
    with pytest.raises(ValueError, match="tag must be letters"):
        variant("a.b")
