"""The table of names is the one the code uses, and the user guide shows it."""

from pathlib import Path

from andoyer import RigidBody
from andoyer.integrate import propagate
from andoyer.integrate.results import VARIABLE_ATTRS
from andoyer.notation import COORDINATE, COORDINATES, NOTATION, storage_name

GUIDE = Path(__file__).resolve().parents[1] / "docs" / "guide.md"


def test_guide_notation_table_is_the_table():
    text = GUIDE.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| `")]
    for sym in NOTATION:
        assert any(f"`{sym.code}`" in r and f"`{sym.storage}`" in r and sym.equation in r
                   for r in rows), sym


def test_storage_names_differ_ignoring_case():
    names = [c.storage.lower() for c in COORDINATES]
    assert len(names) == len(set(names))


def test_datasets_take_names_and_attrs_from_the_table():
    ds = propagate(RigidBody.paper(), [0.3, 0.1, 0.2, 1.0, 0.0], [0.0, 1.0], chart="andoyer",
                   engine="numba")
    for code in ("l", "g", "L", "G", "M", "theta1", "J1", "H"):
        var = ds[storage_name(code)]
        c = COORDINATE[storage_name(code)]
        assert var.attrs["long_name"] == c.long_name and var.attrs["units"] == c.units
    assert set(VARIABLE_ATTRS) <= {c.storage for c in COORDINATES}
