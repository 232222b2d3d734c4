"""Numba kernels generated from derive/ (SymPy): one module per motion model, SE(2) and SE(3) blocks, the model table.

GENERATED FILE: DO NOT EDIT.
Source: derive/codegen/build.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
