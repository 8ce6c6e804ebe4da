"""A public API a user can guess, and ``import andoyer`` stays light."""

import subprocess
import sys

import andoyer


def test_guessable_names():
    from andoyer import (  # noqa: F401
        RigidBody,
        Section,
        cite,
        fill_section,
        poincare,
        propagate,
        propagate_hess_manifold,
    )

    for name in andoyer.__all__:
        assert getattr(andoyer, name) is not None, name
    assert {"propagate", "poincare", "Section", "fill_section"} <= set(dir(andoyer))


def test_import_andoyer_does_not_load_the_heavy_layers():
    code = ("import sys, andoyer; "
            "print(sorted(m for m in ('xarray', 'numba', 'sympy', 'heyoka', 'panel') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, check=True).stdout.strip()
    assert out == "[]"
