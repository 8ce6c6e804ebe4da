"""Symbolic layer: H written once, chart Hamiltonians and equations derived (SymPy).

Imported only on demand (code generation, checks); never on a hot path.
"""
