"""Validated (ball-arithmetic) computations of the heavy top: enclosures, not estimates.

Arb's balls through python-flint: :mod:`~andoyer.integrate.validated.arithmetic` (the body
given exactly by decimals, the field (1) derived from H as monomials, exact evaluation of
SymPy polynomials in balls). Everything here is a rigorous enclosure: a result is a ball
(or a box of balls) that contains the exact value, for the decimal body named.

It sits at the integrate level, not beside the float kernels: the kernels are Numba code on
plain floats and never load SymPy, while a validated method needs the field derived from
the one Hamiltonian by SymPy (:mod:`andoyer.symbolic`) and Arb (python-flint) objects.
"""
