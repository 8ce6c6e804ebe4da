"""Checks of user input, naming the user's argument: the scalar checkers
(:mod:`andoyer.validation.scalars`: ``finite``, ``positive``, ``integer``, ``choice``,
``grid``, ``box``, ``level``, the limits of ``|G|`` and of counts), called where a value
arrives, and the decorator of public functions (:mod:`andoyer.validation.arguments`:
``checks_arguments``, each argument's range given at decoration)."""

from andoyer.validation.arguments import RANGES, ArgumentChecks, checks_arguments
from andoyer.validation.scalars import (
    MAX_ACTION,
    MAX_COUNT,
    MAX_ENERGY,
    MAX_MOMENTUM,
    box,
    choice,
    finite,
    finite_array,
    flag,
    floats,
    grid,
    integer,
    level,
    momentum_limit,
    positive,
    real_array,
)

__all__ = ["MAX_ACTION", "MAX_MOMENTUM", "MAX_ENERGY", "MAX_COUNT", "level", "momentum_limit",
           "finite", "positive", "integer", "real_array", "finite_array", "floats", "choice",
           "grid", "box", "flag", "RANGES", "ArgumentChecks", "checks_arguments"]
