"""Kernel families: one module each, each with ``kernels(model, measurements, built)`` returning (slot, kernel) pairs
that ``derive.codegen.emitter`` orders into a model's module (its ``LAYOUT``); templates in ``../templates/``."""
