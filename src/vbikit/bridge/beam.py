"""Simply supported Euler–Bernoulli beam, reduced to its exact modes.

Equations (e.g. Frýba, *Vibration of Solids and Structures under Moving Loads*, 1972, ch. 1):

* mode shapes, mass-normalised:  φₙ(x) = √(2 / (m L)) · sin(nπx / L),   0 ≤ x ≤ L
* circular frequencies:          ωₙ = (nπ / L)² · √(EI / m)
* bottom-fibre strain:           ε = c · ∂²w/∂x²,  ∂²φₙ/∂x² = −(nπ/L)² φₙ

with m the mass per length [kg/m], EI the bending stiffness [N·m²] and c the distance from the
neutral axis to the bottom fibre [m].  z is up, so a downward load gives negative ξ₁, negative
deflection and positive (tensile) bottom strain.  The beam has no transverse extent: mode
shapes do not depend on y.

Load effects (``vbikit.bridge.effects``), closed forms: reactions of a unit upward force at x,
R₀ = −(1 − x/L), R_L = −x/L; M(s) = R₀ s + (s − x)·[x < s], V(s) = R₀ + [x ≤ s] (0 off the span;
linear in t = x/L on the one element [0, L] with the kink or step at s:
``vbikit.bridge.effects.UniformLineInfluence``, reduced by the compiled ``vbikit.analysis.line_sums``);
per unit modal coordinate M = EI ∂²φ/∂x², V = EI ∂³φ/∂x³, R₀ = V(0), R_L = −V(L).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge.base import DEFAULT_DAMPING_RATIO, ModalBridge
from vbikit.bridge.effects import EFFECT_KINDS, LoadEffect, UniformLineInfluence, kept_effect


def _positive(name: str, value: float) -> None:
    """ValueError unless ``value`` is a positive finite number (not a string or a boolean: a trial's ``span="25"``
    failed in numpy's words)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) or not np.isfinite(value) \
            or value <= 0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")



def _off_span(values: NDArray[np.float64], on: NDArray[np.bool_]) -> NDArray[np.float64]:
    """``values`` (stations × modes) with the rows of stations off the span set to 0 (in place)."""
    if not on.all():
        values[~on[:, 0]] = 0.0
    return values

@dataclass(frozen=True)
class EulerBernoulliBeam(ModalBridge):
    """Simply supported Euler–Bernoulli beam.

    Parameters
    ----------
    span : float
        Span length L [m].
    EI : float
        Bending stiffness [N·m²].
    mass_per_length : float
        Mass per unit length m [kg/m].
    damping_ratio : float
        Modal damping ratio ζ [-], the same for every mode (0 ≤ ζ < 1); default
        ``DEFAULT_DAMPING_RATIO`` (2 %, as scenarios).
    n_modes : int
        Number of retained bending modes.
    neutral_axis_depth : float
        Distance c [m] from the neutral axis down to the bottom fibre, used for strain.
    """

    span: float
    EI: float
    mass_per_length: float
    damping_ratio: float = DEFAULT_DAMPING_RATIO
    n_modes: int = 10
    neutral_axis_depth: float = 0.5

    def __post_init__(self) -> None:
        _positive("span", self.span)
        _positive("EI", self.EI)
        _positive("mass_per_length", self.mass_per_length)
        _positive("neutral_axis_depth", self.neutral_axis_depth)
        if not 0.0 <= self.damping_ratio < 1.0:
            raise ValueError(f"damping_ratio must be in [0, 1), got {self.damping_ratio!r}")
        if int(self.n_modes) != self.n_modes or self.n_modes < 1:
            raise ValueError(f"n_modes must be an integer >= 1, got {self.n_modes!r}")

    # ---------------------------------------------------------------- modal data
    @property
    def wavenumbers(self) -> NDArray[np.float64]:
        """nπ/L [1/m] for n = 1..n_modes."""
        return np.arange(1, self.n_modes + 1) * np.pi / self.span

    @property
    def omega(self) -> NDArray[np.float64]:
        return self.wavenumbers**2 * np.sqrt(self.EI / self.mass_per_length)

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        return np.full(self.n_modes, self.damping_ratio)

    def _arg(self, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        on = (x >= 0.0) & (x <= self.span)
        return np.outer(x, self.wavenumbers), on[:, None]

    @property
    def _amplitude(self) -> float:
        return float(np.sqrt(2.0 / (self.mass_per_length * self.span)))

    @property
    def lateral_invariant(self) -> bool:
        return True  # φ(x): y is ignored

    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        arg, on = self._arg(x)
        out = np.sin(arg, out=arg)  # in place: the tables of a crossing evaluate thousands of stations
        out *= self._amplitude
        return _off_span(out, on)

    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        arg, on = self._arg(x)
        out = np.cos(arg, out=arg)
        out *= self._amplitude * self.wavenumbers
        return _off_span(out, on)

    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return -self.neutral_axis_depth * self.wavenumbers**2 * self.mode_shapes(x, y)

    # ---------------------------------------------------------------- closed forms
    def static_midspan_deflection(self, load: float) -> float:
        """Exact static midspan deflection P L³ / (48 EI) [m] (positive number) under a point load [N] at midspan."""
        return load * self.span**3 / (48.0 * self.EI)

    # ---------------------------------------------------------------- load effects
    def load_effect(self, kind: str, x: float | None = None, support: int | None = None,
                    girder: int | None = None) -> LoadEffect:
        """Moment or shear at section x [m], or the reaction of support 0 (entry) or 1 (exit); closed forms
        (kept on the beam per request: ``vbikit.bridge.effects.kept_effect``)."""
        key = (kind, x, support, girder)  # as given: a bad value is refused by the making, never kept
        return kept_effect(self, key, lambda: self._load_effect(kind, x, support, girder))

    def _load_effect(self, kind: str, x: float | None, support: int | None, girder: int | None) -> LoadEffect:
        """``load_effect`` made anew."""
        if girder is not None:
            raise ValueError("a beam has no girders: leave girder unset")
        if kind not in EFFECT_KINDS:
            raise ValueError(f"load effect must be one of {', '.join(EFFECT_KINDS)}, got {kind!r}")
        L, k = self.span, self.wavenumbers
        amp = self._amplitude
        shear_modal = lambda s: -self.EI * k**3 * amp * np.cos(k * s)  # noqa: E731
        stations = np.array([0.0, L])

        def line(c0: float, c1: float, kink: str = "none", s: float = 0.0) -> UniformLineInfluence:
            """c0 + c1 t, t = x/L, on the one element [0, L] (+ the kink or step at s)."""
            return UniformLineInfluence(stations, np.array([[c0], [c1], [0.0], [0.0]]), kink, 0 if kink != "none" else -1, s)

        if kind == "reaction":
            if support not in (0, 1):
                raise ValueError(f"reaction: support must be 0 or 1 on a simply supported beam, got {support!r}")
            if support == 0:  # R₀ = −(1 − x/L)
                return LoadEffect("reaction", 0.0, shear_modal(0.0), line(-1.0, 1.0), L, support=0)
            return LoadEffect("reaction", L, -shear_modal(L), line(0.0, -1.0), L, support=1)  # R_L = −x/L
        if x is None or not 0.0 <= x <= L:
            raise ValueError(f"{kind}: section x must be within 0 … {L:g} m, got {x!r}")
        s = float(x)
        if kind == "moment":  # M(s) = R₀ s + (s − x)·[x < s]
            modal = -self.EI * k**2 * amp * np.sin(k * s)
            return LoadEffect("moment", s, modal, line(-s, s, "moment", s), L)
        return LoadEffect("shear", s, shear_modal(s), line(-1.0, 1.0, "shear", s), L)  # V(s) = R₀ + [x ≤ s]

    def default_load_effects(self) -> list[LoadEffect]:
        """Midspan moment, shear just right of the entry support, both reactions."""
        return [self.load_effect("moment", self.span / 2), self.load_effect("shear", 0.0),
                self.load_effect("reaction", support=0), self.load_effect("reaction", support=1)]
