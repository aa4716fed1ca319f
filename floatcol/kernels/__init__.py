"""Numba kernels: one pixel column at a time, front to back.

Nothing here imports sympy or matplotlib; the kernels see a surface only as three
compiled function values (f, f_u, f_v) or a height grid, and a view only as a flat
float64 parameter vector (see ``layout.py``).
"""
