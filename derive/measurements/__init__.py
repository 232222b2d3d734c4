"""Measurement-model definitions, one file each (see ``base.MeasurementModel``); ``load_measurements``."""

from ..models import _load_definitions

__all__ = ["load_measurements"]


def load_measurements(folder=None) -> dict:
    """{name: MeasurementModel} of every definition file in ``folder`` (default: this package), sorted."""
    return _load_definitions(folder, __name__, "MEASUREMENT")
