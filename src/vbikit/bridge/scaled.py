"""A bridge model with every stiffness scaled: the model a field calibration fits.

[`ScaledBridge`][vbikit.field.ScaledBridge] wraps any [`ModalBridge`][vbikit.bridge.ModalBridge] and scales its stiffness
matrix by a factor f > 0 with the mass matrix unchanged (a uniform change of Young's modulus):

* K → f K, M unchanged: the eigenproblem K φ = ω² M φ keeps its mass-normalised mode shapes φᵢ,
  and every circular frequency becomes ωᵢ √f (frequencies × √f);
* slopes φᵢ′ and strain shapes (curvature φᵢ″ × lever arm) are those of the base model;
* modal damping: every ratio ζᵢ set to ``damping_ratio`` ζ, or the base model's ratios when None;
* geometry (span, skew, deck edges, default response section) is the base model's.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge.base import ModalBridge


class ScaledBridge(ModalBridge):
    """``base`` with all stiffnesses × ``stiffness_factor`` f [-] and a uniform ``damping_ratio`` ζ [-].

    ωᵢ = √f ωᵢ(base) [rad/s]; mode, slope and strain shapes unchanged.

    Parameters
    ----------
    base : ModalBridge
        The bridge model to scale.
    stiffness_factor : float
        Factor f [-] on all stiffnesses.
    damping_ratio : float, optional
        Uniform modal damping ratio ζ [-]; None keeps the base model's ratios.
    """

    def __init__(self, base: ModalBridge, stiffness_factor: float = 1.0, damping_ratio: float | None = None) -> None:
        if not (np.isfinite(stiffness_factor) and stiffness_factor > 0):
            raise ValueError(f"stiffness_factor must be > 0, got {stiffness_factor!r}")
        if damping_ratio is not None and not 0.0 <= damping_ratio < 1.0:
            raise ValueError(f"damping_ratio must be in [0, 1), got {damping_ratio!r}")
        self.base = base
        self.span = base.span
        self.stiffness_factor = float(stiffness_factor)
        self._zeta = damping_ratio

    @property
    def lateral_invariant(self) -> bool:
        return self.base.lateral_invariant

    @property
    def omega(self) -> NDArray[np.float64]:
        return np.sqrt(self.stiffness_factor) * self.base.omega

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        z = self.base.damping_ratios
        return z if self._zeta is None else np.full_like(z, self._zeta)

    @property
    def shape_source(self) -> ModalBridge:
        return self.base.shape_source  # the shapes and geometry are the base model's

    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.base.mode_shapes(x, y)

    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.base.mode_slopes(x, y)

    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.base.strain_shapes(x, y)

    # the base model's geometry (a skew deck's oblique supports) is unchanged by the scaling
    @property
    def skew(self) -> float:
        return float(getattr(self.base, "skew", 0.0))

    @property
    def skew_tan(self) -> float:
        return self.base.skew_tan

    @property
    def lateral_edges(self) -> tuple[float, float]:
        return self.base.lateral_edges

    def default_x_at(self, y: float) -> float:
        return self.base.default_x_at(y)

    @property
    def default_response_x(self) -> float:
        return self.base.default_response_x
