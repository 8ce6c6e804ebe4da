"""The unperturbed body: Euler-Poinsot motion, equilibria, fixed points, separatrices,
phase portraits."""
