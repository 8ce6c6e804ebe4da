"""The paper itself: the check of its printed formulas and the trajectories of Fig. 3."""
