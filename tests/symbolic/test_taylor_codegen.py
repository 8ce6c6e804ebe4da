"""The committed Taylor jets are still what the symbolic layer generates.

``andoyer.kernels.generated.recurrences`` is regenerated in memory from
:mod:`andoyer.symbolic` and compared with the committed file: the text where the SymPy
version is the one that wrote it, and always the numbers (jets of random states and
bodies, the section tapes and their constants). The jets themselves are checked
against the field in ``tests/kernels/test_taylor.py``.
"""

from __future__ import annotations

import importlib.util
from types import ModuleType

import numpy as np
import pytest
import sympy as sp

from andoyer.kernels.generated import recurrences as committed
from andoyer.symbolic import taylor_codegen


@pytest.fixture(scope="module")
def source() -> str:
    return taylor_codegen.generate_taylor_source()


@pytest.fixture(scope="module")
def regenerated(source: str, tmp_path_factory: pytest.TempPathFactory) -> ModuleType:
    path = tmp_path_factory.mktemp("taylor_codegen") / "regenerated_taylor.py"
    path.write_text(source)
    spec = importlib.util.spec_from_file_location("regenerated_taylor", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_same_text_as_committed(source: str) -> None:
    if committed.SYMPY_VERSION != sp.__version__:
        pytest.skip(f"generated with SymPy {committed.SYMPY_VERSION}, this is {sp.__version__}")
    with open(committed.__file__ or "") as f:
        assert f.read() == source, "regenerate: python -m andoyer.symbolic.taylor_codegen"


def test_same_numbers_as_committed(regenerated: ModuleType) -> None:
    rng = np.random.default_rng(0)
    for _ in range(3):
        body = rng.uniform(0.2, 2.0, 7)
        q0 = np.array(committed.ep_taylor_constants(*body))
        q1 = np.array(regenerated.ep_taylor_constants(*body))
        np.testing.assert_array_equal(q0, q1)
        x0 = np.zeros((9, 6))
        x0[0] = rng.normal(size=6)
        x1 = x0.copy()
        committed.ep_taylor_jet(x0, 8, q0)
        regenerated.ep_taylor_jet(x1, 8, q1)
        np.testing.assert_array_equal(x0, x1)
        w0 = np.zeros((9, 6))
        w0[0] = rng.normal(size=6)
        w1 = w0.copy()
        committed.ep_taylor_tangent_jet(x0, w0, 8, q0)
        regenerated.ep_taylor_tangent_jet(x1, w1, 8, q1)
        np.testing.assert_array_equal(w0, w1)
        # the lane jets (plain Python here: andoyer.kernels.simd's fallbacks)
        X0 = rng.normal(size=(9, 6, 8))
        W0 = rng.normal(size=(9, 6, 8))
        X1, W1 = X0.copy(), W0.copy()
        m = np.empty((committed.LANE_PRODUCTS, 8))
        committed.ep_taylor_jet_lanes(X0, 8, q0, m)
        committed.ep_taylor_tangent_jet_lanes(X0, W0, 8, q0, m)
        regenerated.ep_taylor_jet_lanes(X1, 8, q1, m)
        regenerated.ep_taylor_tangent_jet_lanes(X1, W1, 8, q1, m)
        np.testing.assert_array_equal(X0, X1)
        np.testing.assert_array_equal(W0, W1)
    assert committed.SECTION_TAPES == regenerated.SECTION_TAPES
    assert committed.MARGIN_TAPES == regenerated.MARGIN_TAPES
    for kind in range(len(committed.SECTION_TAPES)):
        for name in ("section_constants", "margin_constants"):
            assert (getattr(committed, name)(kind, 0.3, 0.7, 0.8, 0.6)
                    == getattr(regenerated, name)(kind, 0.3, 0.7, 0.8, 0.6))
