"""The experiments layer: simulation (simulate), the paper's Monte Carlo study (study), metrics (RMSE,
NEES) and figures. Imports only ``lgekf.core`` and below."""
