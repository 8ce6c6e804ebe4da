"""The decorator of public functions (``andoyer.validation.arguments``): types from the
annotations, ranges only where the decoration gives them."""

import pytest


def test_ranges_given_at_decoration_bound_the_arguments():
    """Each decorated function says at decoration which range each argument is held to
    (``ranges=``): the slow hunt's failures were each one of these classes (h = 1e300
    ending in heyoka's IntegrationError, counts of 1e300 in NumPy's "Maximum allowed size
    exceeded", closed forms returning NaN at inf). A name alone checks nothing."""
    import math

    import numpy as np

    from andoyer import RigidBody
    from andoyer.validation import MAX_COUNT, checks_arguments

    def plain(body: RigidBody, h: float, *, G: float = 1.0, M: float = 0.0,
              mu: "ArrayLike" = 0.01,  # noqa: F821 (a string, as under __future__)
              n: int = 8, sheet: int = 1, tol: float = 1e-9, theta1: float = 0.0) -> float:
        return 1.0

    f = checks_arguments(ranges={"h": "energy", "G": "length", "M": "action", "mu": "scale",
                                 "n": "count", "sheet": "sheet", "tol": "tolerance",
                                 "theta1": "angle"}, body="body")(plain)
    unranged = checks_arguments(plain)

    body = RigidBody.paper()
    assert f(body, 0.3) == 1.0
    for bad, match in (
            (dict(h=1e300), r"^h = 1e\+300: the energy level reaches"),
            (dict(h=math.inf), "^h must be finite"),
            (dict(G=-1.0), "^G must be >= 0"), (dict(G=1e300), r"^G must be within"),
            (dict(M=math.inf), "^M must be finite"),
            (dict(mu=[0.01, 1e300]), r"^mu must be within"),
            (dict(n=1e300), "^n must be an integer within"), (dict(n=-1), r"^n must be an "
                                                                        r"integer in \[0"),
            (dict(sheet=2), r"^sheet must be \+1 or -1"), (dict(sheet=1e300), "^sheet"),
            (dict(tol=-1.0), "^tol must be > 0"),
            (dict(theta1=math.inf), "^theta1 must be finite")):
        args = {"h": 0.3, **bad}
        with pytest.raises(ValueError, match=match):
            f(body, **args)
    assert f(body, 0.3, n=MAX_COUNT, G=np.float64(2.0)) == 1.0
    # the names alone: types are checked, ranges are not
    assert unranged(body, 1e300, G=-1.0, n=-1, sheet=2, tol=-1.0) == 1.0
    with pytest.raises(ValueError, match="^h must be a real number"):
        unranged(body, "0.3")
    # a range the annotation cannot hold is refused at decoration
    with pytest.raises(TypeError, match="n has range 'energy' but is not annotated"):
        checks_arguments(ranges={"n": "energy"})(plain)
    with pytest.raises(TypeError, match="is not one of"):
        checks_arguments(ranges={"h": "large"})(plain)


@pytest.mark.parametrize("kind", ["energy", "length", "action", "scale", "tolerance",
                                  "angle"])
def test_a_number_and_its_array_meet_the_same_range(kind):
    """A range's check of a number (its path without NumPy) says what the check of the
    same value as an array says: the same error, or none; an energy without a body is
    held to the square of the momentum limit."""
    import math

    import numpy as np

    from andoyer import RigidBody
    from andoyer.validation import MAX_MOMENTUM
    from andoyer.validation.arguments import _quantity

    def outcome(value, body):
        try:
            _quantity("x", value, kind, body)
        except ValueError as exc:
            return str(exc).split(", got")[0]
        return None

    body = RigidBody.paper()
    for v in (0.3, -0.5, 0.0, 3, 1e60, -1e60, 1e101, 1e201, -1e201, math.inf, -math.inf,
              math.nan, np.float64(-2.0), np.int64(7)):
        for b in (body, None):
            assert outcome(v, b) == outcome(np.array(v, dtype=float), b), (v, b)
    if kind == "energy":
        assert outcome(2 * MAX_MOMENTUM**2, None) == outcome([2 * MAX_MOMENTUM**2], None) \
            == f"x must be within +-{MAX_MOMENTUM**2:g}"


def test_calls_bind_as_the_signature_binds_them():
    """The decorator binds a call as :meth:`inspect.Signature.bind` does: by position and
    by name, defaults unchecked, the first bad argument in the signature's order named,
    and a call the signature refuses refused with the function's name."""
    from andoyer.validation import checks_arguments

    @checks_arguments
    def f(a: float, b: float = 1.0, *, c: int = 2) -> float:
        return a + b + c

    @checks_arguments
    def g(a: float, /, *rest, d: bool = False) -> float:  # noqa: ANN002
        return a

    assert f(1.0) == 4.0 and f(1.0, 2.0, c=3) == 6.0 and f(b=2.0, a=1.0) == 5.0
    assert g(1.0, 2.0, 3.0, d=True) == 1.0
    with pytest.raises(ValueError, match="^a must be a real number"):
        f("x", b="y")
    with pytest.raises(ValueError, match="^b must be a real number"):
        f(c="z", b="y", a=1.0)
    with pytest.raises(ValueError, match="^c must be an integer"):
        f(1.0, c=1.5)
    with pytest.raises(ValueError, match="^d must be True or False"):
        g(1.0, 2.0, d="yes")
    for call in (lambda: f(), lambda: f(1.0, 2.0, 3), lambda: f(1.0, a=2.0),
                 lambda: f(1.0, e=1.0), lambda: g(a=1.0)):
        with pytest.raises(TypeError, match=r"^(f|g): "):
            call()
