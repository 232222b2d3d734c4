"""The applications: ``track`` (every object of a measurement file) and ``evaluate`` (real ground-truth
trajectories). Import core, io and experiments; nothing below imports them."""
