"""Coordinate charts of the heavy top: Euler-Poisson (global), Andoyer-Deprit, Hess.

Each module maps both ways, is vectorised over leading axes and documents its
singular set.
"""

from andoyer.charts.andoyer_deprit import Singular as Singular
from andoyer.charts.andoyer_deprit import from_andoyer as from_andoyer
from andoyer.charts.andoyer_deprit import to_andoyer as to_andoyer
from andoyer.charts.euler_poisson import area_integral as area_integral
from andoyer.charts.euler_poisson import energy as energy
from andoyer.charts.euler_poisson import geometric_integral as geometric_integral
from andoyer.charts.hess import from_hess as from_hess
from andoyer.charts.hess import to_hess as to_hess

__all__ = ["Singular", "from_andoyer", "to_andoyer", "area_integral", "energy",
           "geometric_integral", "from_hess", "to_hess"]
