"""The modal-bridge interface every bridge model implements.

A bridge enters the coupled solve (paper Eq. 9) only through its modal data: natural
circular frequencies ``omega`` [rad/s], modal damping ratios ``damping_ratios`` [-] and
*mass-normalised* mode shapes (Φᵀ M Φ = I), evaluated at deck points (x, y).  Any model
that can supply these — the Euler–Bernoulli beam here, a 3D slab-on-girder FE model or
modes imported from another program — plugs into the solver unchanged.

Optional capabilities are ``typing.Protocol`` classes, checked with ``isinstance``:
[`GirderDeck`][vbikit.bridge.GirderDeck] (girder lines: per-girder responses, deck width), [`HasLoadEffects`][vbikit.bridge.HasLoadEffects]
(moments, shears, reactions) and [`DescribesModes`][vbikit.bridge.DescribesModes] (a name for every mode).  Everything
every bridge can answer — the default vehicle offset, response point and section, the skew, the
supports and spans — is a [`ModalBridge`][vbikit.bridge.ModalBridge] attribute with a default, so callers need no
attribute probes.
"""
from __future__ import annotations

import abc
from typing import TYPE_CHECKING, Optional, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from vbikit.bridge.effects import LoadEffect


#: modal damping ratio [-] of every bridge model and scenario unless given (2 %, the paper's value)
DEFAULT_DAMPING_RATIO = 0.02


class ModalBridge(abc.ABC):
    """Abstract modal bridge.

    Deck points are (x, y): ``x`` [m] from the entry support along the span, ``y`` [m]
    from the deck centreline (positive left).  Mode shapes are mass-normalised, so the
    modal equations read ξ̈ᵢ + 2ζᵢωᵢ ξ̇ᵢ + ωᵢ² ξᵢ = Σ_p φᵢ(x_p, y_p) f_p with f_p the
    vertical point forces [N] (z up).  Outside the deck (x < 0 or x > span) every mode
    shape is zero, so wheels on the approach do not load the bridge.
    """

    #: span length [m]
    span: float
    #: vehicle centreline y [m] a crossing uses when it is not given (models override it)
    default_lateral_offset: float = 0.0
    #: label only (models override it)
    name: str = ""
    #: skew angle θ [°] of a model built with oblique support lines (the slab-on-girder grillage's
    #: oblique mesh); 0 for every other model — the geometry of any model is :attr:`skew_tan`
    skew: float = 0.0

    @property
    def default_section(self) -> float:
        """ξ [m] along the span (from the entry support line) of the section responses are read at
        when no x is given: midspan (a continuous beam or deck: the middle of its first span)."""
        return 0.5 * self.span

    @property
    def default_response_x(self) -> float:
        """x [m] of the deck point responses are read at when no x is given: the default section
        on the default response line."""
        return self.default_x_at(self.default_response_y)

    def default_x_at(self, y: float) -> float:
        """x [m] of the default section on the line at lateral position y [m]: ``default_section``,
        shifted by y tan θ on a skew deck (its support lines are oblique)."""
        t = self.skew_tan
        return self.default_section + float(y) * t if t else self.default_section

    @property
    def skew_tan(self) -> float:
        """tan θ [-] of the support lines' skew: 0 (square supports) unless a skew deck says otherwise
        (its support lines pass through (x_k, 0) with ξ = x − y tan θ = x_k on them)."""
        return 0.0

    @property
    def support_x(self) -> NDArray[np.float64]:
        """ξ [m] of the support lines, entry first: 0 and the span (models on several spans override it)."""
        return np.array([0.0, float(self.span)])

    @property
    def span_lengths(self) -> tuple[float, ...]:
        """Length [m] of every span between supports, entry first: (span,) for a single span."""
        return (float(self.span),)

    def span_index(self, x: float) -> int:
        """0-based span containing ξ = x [m] (an interior support belongs to the span on its right)."""
        xs = self.support_x
        return int(np.clip(np.searchsorted(xs, x, side="right") - 1, 0, xs.size - 2))

    @property
    def lateral_edges(self) -> tuple[float, float]:
        """y [m] of the deck's two lateral edges (only a skew deck's x extent depends on them)."""
        return 0.0, 0.0

    @property
    def deck_extent(self) -> tuple[float, float]:
        """(x_first, x_last) [m]: the x range of the deck over its whole width — the mode shapes
        vanish outside it.  0 … span; a skew deck reaches beyond both, to where its oblique support
        lines meet the lateral edges."""
        t = self.skew_tan
        if not t:
            return 0.0, float(self.span)
        shifts = [e * t for e in self.lateral_edges]
        return min(min(shifts), 0.0), float(self.span) + max(max(shifts), 0.0)

    @property
    def deck_overhang(self) -> float:
        """How far [m] the deck reaches beyond its supports along x (``deck_extent``): 0, or a skew deck's
        oblique ends, where a wheel touches the deck before its axle reaches the support line."""
        first, last = self.deck_extent
        return max(-first, last - float(self.span), 0.0)

    def span_coordinate(self, x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
        """ξ [m] of deck points (x, y): the distance along the span from the entry support line at
        the point's y — x itself; on a skew deck x − y·tan θ.  A point is on the deck while
        0 ≤ ξ ≤ span."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        t = self.skew_tan
        return x - y * t if t else np.array(x, float)

    @property
    def lateral_invariant(self) -> bool:
        """True when the mode shapes do not depend on y (a beam): wheels at the same x load and
        feel the bridge alike, whatever their y (callers may merge them).  Default False."""
        return False

    @property
    def default_response_y(self) -> float:
        """y [m] of the deck point responses and impact factors are read at when no y is given
        (the deck centreline; a slab-on-girder deck: its default girder's line)."""
        return 0.0

    @property
    @abc.abstractmethod
    def omega(self) -> NDArray[np.float64]:
        """Natural circular frequencies ωᵢ [rad/s], ascending, shape (n_modes,)."""

    @property
    @abc.abstractmethod
    def damping_ratios(self) -> NDArray[np.float64]:
        """Modal damping ratios ζᵢ [-], shape (n_modes,)."""

    @abc.abstractmethod
    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Mass-normalised vertical mode-shape values φᵢ(x, y) [kg^-1/2], shape (n_points, n_modes)."""

    @property
    def shape_source(self) -> "ModalBridge":
        """The bridge whose mode shapes (and geometry) these are: itself; a bridge that only rescales
        another's stiffness or damping (``ScaledBridge``) gives that one's.  Tables of the shapes
        (``vbikit.solve.tabulate``) are kept for it, shared by every bridge with the same shapes."""
        return self

    @abc.abstractmethod
    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Longitudinal derivatives ∂φᵢ/∂x [kg^-1/2 m^-1], shape (n_points, n_modes)."""

    @abc.abstractmethod
    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Bottom-fibre longitudinal strain per unit modal coordinate, shape (n_points, n_modes).

        Tension positive: for a beam ε_bottom = c · ∂²w/∂x² with c the distance from the
        neutral axis down to the bottom fibre (z up, so sagging curvature is positive).
        """

    # ------------------------------------------------------------------ derived
    @property
    def frequencies_hz(self) -> NDArray[np.float64]:
        """Natural frequencies fᵢ = ωᵢ / 2π [Hz]."""
        return self.omega / (2.0 * np.pi)

    def static_modal_coordinates(self, x: ArrayLike, y: ArrayLike, forces: ArrayLike) -> NDArray[np.float64]:
        """Static modal coordinates ξᵢ = Σ_p φᵢ(x_p, y_p) f_p / ωᵢ² for point forces f_p [N] (z up).

        ``x``, ``y``, ``forces`` broadcast to shape (..., n_points); the result has shape
        (..., n_modes).  This is the bridge's static solution within the retained modes.
        """
        x, y, f = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float), np.asarray(forces, float))
        lead = x.shape[:-1]
        phi = self.mode_shapes(x.ravel(), y.ravel()).reshape(*x.shape, self.omega.size)
        return np.einsum("...p,...pm->...m", f, phi).reshape(*lead, self.omega.size) / self.omega**2


@runtime_checkable
class GirderDeck(Protocol):
    """A deck with girder lines (Girder 1 at the most negative y): per-girder responses and sections."""

    @property
    def girder_y(self) -> NDArray[np.float64]:
        """y [m] of the girder lines, Girder 1 first (ascending)."""
    @property
    def n_girders(self) -> int:
        """Number of girders."""
    @property
    def default_girder(self) -> int:
        """Girder (1-based) responses are reported for when neither a girder nor a y is given."""
    @property
    def deck_width(self) -> Optional[float]:
        """Total deck width [m], centred on y = 0 (None when unknown)."""
    def girder_index(self, girder: int) -> int:
        """0-based line index of the 1-based ``girder`` (checked: ValueError outside 1 … n_girders)."""


@runtime_checkable
class HasLoadEffects(Protocol):
    """A bridge with load effects (``vbikit.bridge.effects``): moments, shears and reactions."""

    def load_effect(self, kind: str, x: Optional[float] = None, support: Optional[int] = None,
                    girder: Optional[int] = None) -> "LoadEffect":
        """``kind`` "moment" or "shear" at section x [m], or "reaction" of support index ``support``
        (0 = entry); ``girder`` on a girder deck (None: the default girder)."""
    def default_load_effects(self) -> "list[LoadEffect]":
        """The effects reported when none are asked for (moments at midspan and over supports, shears,
        reactions)."""


@runtime_checkable
class DescribesModes(Protocol):
    """A bridge that names its modes (e.g. "bending, 1 half-wave along the span")."""

    def mode_descriptions(self) -> list[str]:
        """One short description per mode, in the order of ``omega``."""
