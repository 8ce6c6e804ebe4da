"""andoyer: the heavy rigid body (Hess gyroscope) in Andoyer-Deprit variables."""

from andoyer._version import __version__ as __version__
from andoyer.analysis.paper.check import paper_check as paper_check
from andoyer.body import RigidBody as RigidBody
from andoyer.charts import Singular as Singular
from andoyer.charts import area_integral as area_integral
from andoyer.charts import energy as energy
from andoyer.charts import from_andoyer as from_andoyer
from andoyer.charts import from_hess as from_hess
from andoyer.charts import geometric_integral as geometric_integral
from andoyer.charts import to_andoyer as to_andoyer
from andoyer.charts import to_hess as to_hess
from andoyer.citation import cite as cite
from andoyer.dynamics import cyclic_rate as cyclic_rate
from andoyer.dynamics import hamiltonian as hamiltonian
from andoyer.dynamics import vector_field as vector_field

__all__ = [
    "__version__",
    "RigidBody",
    "Singular",
    "area_integral",
    "cite",
    "cyclic_rate",
    "hamiltonian",
    "paper_check",
    "vector_field",
    "energy",
    "from_andoyer",
    "from_hess",
    "geometric_integral",
    "to_andoyer",
    "to_hess",
]


#: Names imported on first use (they load xarray, Numba, SciPy): ``from andoyer import
#: propagate`` works, while ``import andoyer`` stays light.
_LAZY = {
    "propagate": "andoyer.integrate.api",
    "poincare": "andoyer.integrate.api",
    "initial_states": "andoyer.integrate.api",
    "integrate_canonical": "andoyer.integrate.api",
    "Section": "andoyer.integrate.engines.values",
    "fill_section": "andoyer.integrate.fill",
    "propagate_hess_manifold": "andoyer.integrate.hess_manifold",
    "chaos_map": "andoyer.analysis.chaos.lyapunov",
    "indicators": "andoyer.analysis.chaos.lyapunov",
    "MapGrid": "andoyer.analysis.chaos.specs",
    "IndicatorRun": "andoyer.analysis.chaos.specs",
}
__all__ += sorted(_LAZY)


def __getattr__(name: str) -> object:
    """The integration API and the explorer, imported on first use.

    ``andoyer.explore`` is the browser explorer (it loads Panel).
    """
    import importlib

    if name == "explore":
        return importlib.import_module("andoyer.explore")
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'andoyer' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | {"explore"})
