"""The definition type of a measurement model: z ∈ G', Z = h(X)·exp(m), m ~ N(0, R) in the tangent of G'.

A measurement model is one file ``derive/measurements/<name>.py`` with ``MEASUREMENT = <Subclass>()``.
It declares the measurement group G', the measured vector z and how it maps to an element of G'
(``element``) and back (``vector``), h(X) through the motion model's ``position``/``heading``, and its
noise.  The emitter combines it with every motion model it ``fits``:

* innovation e = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K), ℋ = ∂/∂ε [log_G'(h(μ)⁻¹ h(μ·exp ε))]^∨ at ε = 0 (eq:calH);
* simulation: z = vector(h(X)·exp(m)).
"""

from __future__ import annotations

import sympy as sp

from ..space import PLANE

__all__ = ["MeasurementModel"]


class MeasurementModel:
    """Declared by every definition: ``group`` (G'), ``z_names`` (the measured vector, also the CSV
    columns), ``noise_names`` (the user's ``meas_std`` entries), ``description``, and the methods
    ``h``, ``element``, ``vector``, ``R`` and ``fits``."""

    name: str = ""  # the definition file's stem, set by the loader
    description: str = ""
    space = PLANE  # the space it observes (``derive.space``): it fits only the motion models of that space
    group = None
    z_names: tuple = ()
    noise_names: tuple = ()
    angles: tuple = ()  # entries of z that are angles (wrapped to (−π, π])

    @property
    def m(self) -> int:
        """Dimension of the measurement (tangent of G')."""
        return self.group.dim

    @property
    def z_symbols(self) -> tuple:
        return tuple(sp.Symbol(f"z_{nm}", real=True) for nm in self.z_names)

    @property
    def noise_symbols(self) -> tuple:
        return tuple(sp.Symbol(nm, positive=True) for nm in self.noise_names)

    def R(self) -> sp.Matrix:  # pragma: no cover - abstract
        """Covariance of m in the noise symbols."""
        raise NotImplementedError

    def h(self, model, X) -> sp.Matrix:  # pragma: no cover - abstract
        """h(X) ∈ G' for a state X of ``model``."""
        raise NotImplementedError

    def element(self, z) -> sp.Matrix:  # pragma: no cover - abstract
        """The element of G' a measured vector z stands for."""
        raise NotImplementedError

    def vector(self, Z) -> list:  # pragma: no cover - abstract
        """The measured vector of an element Z of G' (inverse of ``element``)."""
        raise NotImplementedError

    def fits(self, model) -> str | None:
        """None when this measurement applies to ``model``, else the reason why not (a model of another space; a
        definition adds its own reasons and calls this first)."""
        if model.space is not self.space:
            return (f"the {model.name} model moves in {model.space.dim}-D space, the {self.name} measurement observes "
                    f"{self.space.dim}-D positions")
        return None
