"""Lie-group foundations: angle functions (special), SE(2)/Rⁿ/products (groups), limits at ε = 0 (limits)."""
