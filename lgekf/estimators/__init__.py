"""Estimators built on the generated kernels: smoothing, IMM, noise learning, data association, tracking.

Layer 2 of the runtime: imports ``lgekf.core`` (and ``lgekf.io``) and the generated kernels, never
``experiments``, ``apps`` or ``cli``.
"""
