"""The values crossing the engine seam: the one section class of users and engines."""

from __future__ import annotations

import math

import numpy as np
import pytest

import andoyer
from andoyer.errors import ArgumentTypeError
from andoyer.integrate.engines import base
from andoyer.integrate.engines.values import ALL_KINDS, REVERSIBLE, Section, runtime_parameters
from andoyer.notation import SECTION_ANGLES, SECTION_COORDINATES, SECTION_PLANES


def test_users_and_engines_share_one_section_class():
    assert andoyer.Section is Section
    assert andoyer.integrate.Section is Section
    assert base.Section is Section


def test_one_default_direction_everywhere():
    """A Poincare section in one direction (coordinate increasing) unless asked."""
    assert Section("G3").direction == 1
    assert Section.parse("G3=0").direction == 1
    assert Section.from_kind(ALL_KINDS.index("G3")).direction == 1
    assert Section.from_kind(2, 0.0, 0).direction == 0


@pytest.mark.parametrize(("text", "section"), [
    ("theta2=0", Section("theta2", 0.0, 1)),
    ("G3=0.5:-", Section("G3", 0.5, -1)),
    ("g = 1 : 0", Section("g", 1.0, 0)),
    ("L=-0.2:+1", Section("L", -0.2, 1)),
    ("psi=0.3:-1", Section("psi", 0.3, -1)),
])
def test_parse_and_construct_agree(text, section):
    assert Section.parse(text) == section


def test_from_kind_is_the_kernels_index():
    for k, coord in enumerate(ALL_KINDS):
        sec = Section.from_kind(k, 0.25, -1)
        assert (sec.coord, sec.kind, sec.value, sec.direction) == (coord, k, 0.25, -1)


def test_every_section_coordinate_is_a_kind_and_back():
    """The one table of section coordinates and the kernels' kinds are the same set."""
    assert set(SECTION_COORDINATES) == set(ALL_KINDS)
    assert {c for c in ALL_KINDS if Section(c).is_angle} == set(SECTION_ANGLES)


def test_angles_are_reduced_components_are_not():
    assert Section("g", 7.0).value == pytest.approx(7.0 - 2 * math.pi, abs=1e-15)
    assert Section("theta2", -1.0).value == pytest.approx(2 * math.pi - 1.0, abs=1e-15)
    assert Section("G3", 7.0).value == 7.0
    assert Section("psi", 7.0).value == 7.0  # not a chart's angle: the kernels wrap it


def test_direction_and_value_are_stored_as_int_and_float():
    sec = Section("G3", np.float32(0.5), np.int64(-1))
    assert type(sec.value) is float and type(sec.direction) is int
    assert sec == Section("G3", 0.5, -1)


@pytest.mark.parametrize(("args", "error", "words"), [
    (("M",), ValueError, "unknown section coordinate 'M'"),
    (("J3",), ValueError, "M and J3 are constants of motion"),
    ((3,), ArgumentTypeError, "section coordinate must be a name"),
    (("G3", "0"), ArgumentTypeError, "section value must be a number"),
    (("G3", True), ArgumentTypeError, "section value must be a number"),
    (("G3", None), ArgumentTypeError, "section value must be a number"),
    (("G3", math.nan), ValueError, "section value must be finite"),
    (("G3", math.inf), ValueError, "section value must be finite"),
    (("G3", 0.0, 2), ValueError, "section direction must be"),
    (("G3", 0.0, True), ValueError, "section direction must be"),
    (("G3", 0.0, 0.5), ValueError, "section direction must be"),
    (("G3", 0.0, "+"), ValueError, "section direction must be"),
])
def test_bad_arguments_are_named(args, error, words):
    with pytest.raises(error, match=words):
        Section(*args)


def test_parse_errors_name_the_text():
    for text, words in [("g", "cannot parse section 'g'"), ("g==0", "is not a number"),
                        ("g=0:x", "cannot parse"), ("M=0", "unknown section coordinate")]:
        with pytest.raises(ValueError, match=words):
            Section.parse(text)
    with pytest.raises(ArgumentTypeError, match="section must be a string"):
        Section.parse(0.0)  # type: ignore[arg-type]


def test_from_kind_names_kind():
    with pytest.raises(ValueError, match="kind must be an integer"):
        Section.from_kind(len(ALL_KINDS))
    with pytest.raises(ValueError, match="section direction"):
        Section.from_kind(0, 0.0, 2)


def test_reversed_follows_the_one_table():
    for coord, s in REVERSIBLE.items():
        sec = Section(coord, 0.5, 1)
        back = sec.reversed()
        assert back.coord == coord and back.direction == -s
        assert math.isclose(math.remainder(back.value - s * 0.5, 2 * math.pi), 0.0,
                            abs_tol=1e-15)
    irreversible = [c for c in ALL_KINDS if c not in REVERSIBLE]
    assert irreversible
    with pytest.raises(ValueError, match="native backward flow"):
        Section(irreversible[0]).reversed()


def test_chart_plane_and_attrs():
    assert Section("theta2").chart == "hess" and Section("g").chart == "andoyer"
    assert Section("G1").chart == "euler_poisson" and Section("psi").chart is None
    assert Section("theta2").plane is SECTION_PLANES["theta2"]
    with pytest.raises(ValueError, match="no filled plane"):
        _ = Section("G3").plane
    assert Section("g", 1.0, -1).attrs() == {
        "section_coord": "g", "section_value": 1.0, "section_direction": -1,
        "section_chart": "andoyer"}
    assert "section_chart" not in Section("psi").attrs()


def test_runtime_parameters_take_the_section_value():
    p = runtime_parameters((0.4, 0.5, 0.5, 0.01, 1.0, 0.0, 0.0, 0.0), Section("g", 0.5))
    assert p[8:11].tolist() == [0.5, math.cos(0.5), math.sin(0.5)]


def test_poincare_refuses_a_section_of_no_chart():
    from andoyer import RigidBody, poincare

    with pytest.raises(ValueError, match="section 'psi' is no chart's coordinate"):
        poincare(RigidBody.paper(), [0.0, 0.6, 0.8, 0.0, 0.6, 0.8], "psi=0", 2)
