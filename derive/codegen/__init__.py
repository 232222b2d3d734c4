"""SymPy -> numba: the printer and straight-line kernels (printer), the generic emitter (emitter),
and `lgekf derive` (build)."""
