"""The applications: ``track`` (every object of a measurement file) with ``noise``/``defaults`` (the noise
from the data) and ``divergence`` (monitoring and recovery), ``robustness`` (the robustness set of
``lgekf track``) and ``evaluate`` (real ground-truth trajectories). Import core, io and experiments;
nothing below imports them."""
