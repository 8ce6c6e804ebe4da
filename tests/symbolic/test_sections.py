"""The one table of section coordinates (:data:`andoyer.notation.SECTION_COORDINATES`):
SymPy checks each reversal sign on the generated section functions
(``f(R y; s value) = s f(y; value)`` with ``R = diag(-1, -1, -1, 1, 1, 1)``), and every
section table andoyer uses is derived from it."""

from __future__ import annotations

import pytest
import sympy as sp

from andoyer.notation import SECTION_ANGLES, SECTION_COORDINATES
from andoyer.symbolic.hamiltonian import S
from andoyer.symbolic.sections import section_function, sv, value


def _reversed(f: sp.Expr, s: int) -> sp.Expr:
    """``f(R y; s value)``: momenta flipped, the value (and its sine) times ``s``."""
    G1, G2, G3 = S.y[:3]
    return f.subs({G1: -G1, G2: -G2, G3: -G3, value: s * value, sv: s * sv},
                  simultaneous=True)


def reversal_sign(coord: str) -> int | None:
    """The sign ``s`` with ``f(R y; s value) = s f(y; value)``, or None (SymPy)."""
    f, _ = section_function(coord)
    for s in (1, -1):
        if sp.simplify(sp.expand(_reversed(f, s) - s * f)) == 0:
            return s
    return None


@pytest.mark.parametrize("coord", sorted(SECTION_COORDINATES))
def test_each_reversal_sign_is_the_section_functions(coord):
    assert reversal_sign(coord) == SECTION_COORDINATES[coord].reversal


def test_the_check_catches_a_wrong_sign():
    f, _ = section_function("G3")
    assert sp.simplify(_reversed(f, 1) - f) != 0  # G3 flips: +1 is wrong


def test_every_section_table_is_derived_from_the_one_table():
    from andoyer.integrate.engines.values import ALL_KINDS, REVERSIBLE, Section
    from andoyer.kernels.generated.equations import EXTRA_SECTION_KINDS, SECTION_KINDS
    from andoyer.plot.section import LABELS  # noqa: F401 (the plot layer imports)
    from andoyer.symbolic import sections

    table = SECTION_COORDINATES
    assert REVERSIBLE == {k: s.reversal for k, s in table.items() if s.reversal is not None}
    assert tuple(k for k in ALL_KINDS if Section(k).is_angle) == sections.ANGLES \
        == SECTION_ANGLES
    assert {k: Section(k).chart for k in ALL_KINDS} == {k: s.chart for k, s in table.items()}
    # Where each coordinate is undefined: the table's singular sets, read by the section.
    y = [[0.0, 0.0, 1e-9, 0.0, 0.0, 1.0]]  # G -> 0: every angle undefined
    assert {k for k in ALL_KINDS if Section(k).defined_distance(y, 1.0)[0] < 1e-6} \
        == {k for k, s in table.items() if s.needs}
    assert set(sections.EXTRA_ANGLES) == {k for k, s in table.items() if s.chart is None}
    assert set(table) == set(SECTION_KINDS) | set(EXTRA_SECTION_KINDS)


def test_the_g_sections_on_the_axes_are_f_without_the_square_root() -> None:
    """Where sin(value) = 0 the reduced f of g times |G| is f, where cos(value) = 0 it is f:
    polynomials, no square root (f has one)."""
    from andoyer.symbolic.sections import _G, cv, section_function_reduced

    f = section_function("g")[0]
    assert f.has(_G)
    at_pi = section_function_reduced("g", "sin")
    at_half_pi = section_function_reduced("g", "cos")
    for q in (at_pi, at_half_pi):
        assert q is not None and q.is_polynomial(*S.y) and not q.has(_G)
    assert sp.simplify(f.subs(sv, 0) - _G * at_pi) == 0
    assert sp.simplify(f.subs(cv, 0) - at_half_pi) == 0
    with pytest.raises(ValueError, match="vanishing"):
        section_function_reduced("g", "tan")


@pytest.mark.parametrize("vanishing", ["sin", "cos"])
@pytest.mark.parametrize("coord", sorted(SECTION_COORDINATES))
def test_only_g_has_a_reduced_section_function(coord: str, vanishing: str) -> None:
    from andoyer.symbolic.sections import section_function_reduced

    # theta2's f keeps g's square root mixed with the rotation by phi0 on both axes;
    # l, theta1, psi have no square root to save; the smooth coordinates are not angles.
    assert (section_function_reduced(coord, vanishing) is not None) == (coord == "g")
