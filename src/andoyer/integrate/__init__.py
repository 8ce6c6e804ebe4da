"""Orbits and Poincare sections (friendly layer over the engines)."""
