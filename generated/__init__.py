"""Numba kernels generated from derive/ (SymPy). Import the per-model modules.

GENERATED FILE: DO NOT EDIT.
Source: derive/build.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
