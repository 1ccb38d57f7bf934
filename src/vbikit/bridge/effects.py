"""Load effects (bending moment, shear, support reaction) of a modal bridge.

A load effect R is a linear function of the loads.  A model that offers load effects gives,
for each effect, the two ingredients of the mode-acceleration method (e.g. Clough & Penzien,
*Dynamics of Structures*, 2nd ed., 1993, §13-5; Craig & Kurdila, *Fundamentals of Structural
Dynamics*, 2006, §14.4):

* ``influence(x, y)``: its static value under a unit upward point force at (x, y) [per N],
  from the *full* stiffness of the model (not from the retained modes);
* ``modal``: its value r_i per unit modal coordinate of each retained mode.

With wheel forces f_p(t) (z up) at (x_p, y_p) the two estimates of R(t) are

* mode superposition:  R(t) = Σ_i r_i ξ_i(t);
* mode acceleration:   R(t) = Σ_p I(x_p, y_p) f_p(t) − Σ_i r_i (ξ̈_i + 2 ζ_i ω_i ξ̇_i) / ω_i²,

which are the same with all modes; the second converges much faster with few modes because
the quasi-static part (the part that bending moments and shears need many modes for) is exact.

Sign conventions (SI units): moment [N·m] sagging positive (bottom fibre in tension); shear
[N] V = dM/dx, the sum of the upward forces left of the section (taken just right of it,
x = s⁺: a point load or support at x = s counts as left); reaction [N] the upward force of
the support on the bridge (positive under downward loads).
"""
from __future__ import annotations

import abc
from dataclasses import dataclass, field
from typing import Any, Callable, Hashable, Literal, Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import kept_for

EffectKind = Literal["moment", "shear", "reaction"]
EFFECT_KINDS: tuple[str, ...] = ("moment", "shear", "reaction")
EFFECT_UNITS = {"moment": "N m", "shear": "N", "reaction": "N"}


@dataclass(frozen=True)
class LoadEffect:
    """One load effect of a bridge (see the module docstring).

    ``x`` [m] the section (moment, shear) or the support position (reaction); ``girder`` the
    girder (1-based) on a slab-on-girder deck, None on a beam; ``support`` the support index
    (0 = entry support) for a reaction; ``loaded_length`` [m] the span length that design codes
    use for this effect (AASHTO Standard 3.8.2.2: the span for sagging moment and shear, the
    mean of the two adjacent spans at an interior support); ``hogging_region``: the section is
    at an interior support, where the moment of interest is negative.
    """

    kind: EffectKind
    x: float
    modal: NDArray[np.float64]
    influence: Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]] = field(repr=False)
    loaded_length: float
    girder: Optional[int] = None
    support: Optional[int] = None
    hogging_region: bool = False

    @property
    def units(self) -> str:
        return EFFECT_UNITS[self.kind]

    @property
    def label(self) -> str:
        where = f"support {self.support} (x = {self.x:g} m)" if self.kind == "reaction" else f"x = {self.x:g} m"
        return f"{self.kind} at {where}" + (f", girder {self.girder}" if self.girder is not None else "")


#: load effects one bridge object keeps (``kept_effect``; least recently used dropped first)
EFFECTS_KEPT = 64


def kept_effect(bridge: object, key: Hashable, make: Callable[[], "LoadEffect"]) -> "LoadEffect":
    """The load effect ``key`` (e.g. kind, section, girder, support) of ``bridge``, made by ``make()``
    the first time and kept for the bridge (``vbikit._kept.kept_for``; bridges are immutable): a kept bridge's later runs
    reuse the effect and whatever its influence function keeps (a deck's wheel-line tables).
    Shared: nothing may change a returned effect."""
    try:
        hash(key)
    except TypeError:  # e.g. a section given as an array: made, not kept
        return make()
    return kept_for(bridge, "load effects", EFFECTS_KEPT).get(key, make)


class SharedInfluence(abc.ABC):
    """An influence function I(x, y) whose costly part depends on the load points only and is the
    same for every effect of one model (a grillage deck's consistent load of the points):
    ``shared(x, y)`` computes it, ``apply(part, x, y)`` finishes one effect's values, and effects with
    equal ``shared_key`` share the part (``influence_values``)."""

    @property
    @abc.abstractmethod
    def shared_key(self) -> Hashable:
        """Effects with equal keys accept each other's ``shared`` part."""

    @abc.abstractmethod
    def shared(self, x: NDArray[np.float64], y: NDArray[np.float64]) -> Any:
        """The part of I(x, y) common to every effect with this ``shared_key``."""

    @abc.abstractmethod
    def apply(self, part: Any, x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        """I(x, y) [per N] from the ``shared`` part of the same points."""

    def __call__(self, x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, float).ravel()
        y = np.broadcast_to(np.asarray(y, float), x.shape).ravel()
        return self.apply(self.shared(x, y), x, y)


class TabulatedInfluence(SharedInfluence):
    """A ``SharedInfluence`` tabulated along wheel lines: on each element [ξ_e, ξ_(e+1)] of
    ``stations`` (ξ = x − y·``skew_tan``, 0 ≤ ξ ≤ the last station) I(x, y) is the cubic in
    t = (ξ − ξ_e)/(ξ_(e+1) − ξ_e) whose monomial coefficients are ``line_tables``, plus, on the
    section's own element ``element`` only, the share c(y) times the kink of a moment (s − ξ for
    ξ < s, else 0) or the step of a shear (1 for ξ ≤ s, else 0), ``s`` = ``section``; nothing for a
    reaction (``kink`` = "none").  A compiled reduction over moving points reads these tables
    (``vbikit.analysis.line_sums``); ``apply`` evaluates the same at any points."""

    #: the term of the section's own element: "none" (reaction), "moment" or "shear"
    kink: str = "none"
    element: int = -1
    section: float = 0.0

    @property
    @abc.abstractmethod
    def stations(self) -> NDArray[np.float64]:
        """ξ [m] of the element ends (ascending)."""

    @property
    @abc.abstractmethod
    def skew_tan(self) -> float:
        """tan θ of the support lines (ξ = x − y tan θ)."""

    @abc.abstractmethod
    def line_tables(self, lines: Sequence[float]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Monomial coefficients (4, n_lines × n_elements) in t (rows t⁰ … t³; line-major) along the
        wheel lines ``lines`` [m], and each line's share c(y) of the section's girder line."""


class UniformLineInfluence(TabulatedInfluence):
    """A ``TabulatedInfluence`` that is the same along every wheel line (a beam: I depends on x
    alone): the cubic rows ``poly`` (4, n_elements) in t on the elements of ``stations`` (skew 0,
    c(y) = 1), plus the kink of a moment or the step of a shear at ``section`` on the element
    ``element`` (``TabulatedInfluence``).  A simply supported beam's influence lines are linear
    between its supports with the kink or step at the section, so one element [0, L] with rows
    t⁰, t¹ holds them exactly (``vbikit.bridge.beam``)."""

    def __init__(self, stations: NDArray[np.float64], poly: NDArray[np.float64], kink: str = "none",
                 element: int = -1, section: float = 0.0) -> None:
        stations = np.ascontiguousarray(stations, float)
        poly = np.ascontiguousarray(poly, float)
        if stations.ndim != 1 or stations.size < 2 or np.any(np.diff(stations) <= 0.0):
            raise ValueError("stations must be at least two ascending positions [m]")
        if poly.shape != (4, stations.size - 1):
            raise ValueError(f"poly must have shape (4, {stations.size - 1}) (rows t⁰ … t³ per element), "
                             f"got {poly.shape}")
        if kink not in ("none", "moment", "shear"):
            raise ValueError(f"kink must be none, moment or shear, got {kink!r}")
        if kink != "none" and not 0 <= element < stations.size - 1:
            raise ValueError(f"element must be in 0 … {stations.size - 2} with a {kink} kink, got {element!r}")
        self._stations, self.poly = stations, poly
        self.kink, self.element, self.section = kink, int(element), float(section)
        self._key = ("uniform-line", stations.tobytes())

    @property
    def stations(self) -> NDArray[np.float64]:
        return self._stations

    @property
    def skew_tan(self) -> float:
        return 0.0

    @property
    def shared_key(self) -> Hashable:
        return self._key

    def line_tables(self, lines: Sequence[float]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        n = len(lines)
        return (self.poly if n == 1 else np.ascontiguousarray(np.tile(self.poly, (1, n)))), np.ones(n)

    def __call__(self, x: NDArray[np.float64], y: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """I at x [m] (any shape; y is ignored), 0 off the stations."""
        x = np.asarray(x, float)
        return self.apply(self.shared(x, None), x, None).reshape(x.shape)  # type: ignore[arg-type]

    def shared(self, x: NDArray[np.float64], y: NDArray[np.float64]):
        """Each point's element e, its t on it, its ξ = x and whether it is off the stations."""
        xs = self._stations
        xi = np.asarray(x, float).ravel()
        e = np.clip(np.searchsorted(xs, xi, side="right") - 1, 0, xs.size - 2)
        t = (xi - xs[e]) / (xs[e + 1] - xs[e])
        return xi, e, t, (xi < xs[0]) | (xi > xs[-1])

    def apply(self, part, x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        xi, e, t, off = part
        c = self.poly[:, e]
        out = ((c[3] * t + c[2]) * t + c[1]) * t + c[0]  # Horner, as vbikit.analysis.line_sums
        if self.kink != "none":
            s, here = self.section, e == self.element
            out += here * (np.where(xi < s, s - xi, 0.0) if self.kink == "moment" else np.where(xi <= s, 1.0, 0.0))
        out[off] = 0.0
        return out


def influence_values(effects: Sequence[LoadEffect], x: NDArray[np.float64],
                     y: NDArray[np.float64]) -> NDArray[np.float64]:
    """I(x_p, y_p) of every effect at the load points (x, y) [m] (1-D), shape (n_points, n_effects);
    influence functions that share a part (``SharedInfluence``) compute it once."""
    x = np.asarray(x, float).ravel()
    y = np.broadcast_to(np.asarray(y, float), x.shape).ravel()
    out = np.empty((x.size, len(effects)))
    groups: dict[Hashable, list[int]] = {}
    for i, e in enumerate(effects):
        if isinstance(e.influence, SharedInfluence):
            groups.setdefault(e.influence.shared_key, []).append(i)
        else:
            out[:, i] = e.influence(x, y)
    for members in groups.values():
        part = effects[members[0]].influence.shared(x, y)  # type: ignore[attr-defined]
        for i in members:
            out[:, i] = effects[i].influence.apply(part, x, y)  # type: ignore[attr-defined]
    return out


def jump_positions(bridge: Any, effect: LoadEffect) -> NDArray[np.float64]:
    """ξ [m] (along the span, ``ModalBridge.span_coordinate``) where the influence line of ``effect``
    may jump or kink on every wheel line, sorted, unique: the section of a moment (kink) or a shear
    (jump), and for a shear or a reaction the support lines (``support_x``: the deck ends, where a
    point leaves the deck and I drops to 0 — a reaction at an end support and a shear next to it
    jump there — and the joints of a series of spans).  Not a moment's support lines: a moment's
    influence vanishes at a deck end (a pinned or bearing-supported girder end carries none), so a
    point entering there adds nothing at that instant, and the value computed at ξ = 0⁺ would be the
    influence solution's round-off only (which, alone on the deck, would read as an extreme of the
    other sign: ``opposite_static_peak``)."""
    xs = set() if effect.kind == "moment" else {float(v) for v in np.asarray(bridge.support_x, float)}
    if effect.kind != "reaction":
        f = effect.influence
        xs.add(float(f.section) if isinstance(f, TabulatedInfluence) and f.kink != "none" else float(effect.x))
    return np.array(sorted(xs))


def kink_positions(bridge: Any, effect: LoadEffect, y: float | None = None) -> NDArray[np.float64]:
    """ξ [m] where the history of ``effect`` may jump or kink as a contact point on the wheel line
    ``y`` [m] passes: its ``jump_positions``, every support line (``support_x``: a moment's influence
    kinks where a point enters or leaves the deck, though it is 0 there) and, for an influence
    tabulated along wheel lines, the stations where that line's cubics meet with a break of value or
    slope (``station_kinks``: a grillage's line between two girders), sorted, unique."""
    def make() -> tuple[Any, NDArray[np.float64]]:
        out = np.union1d(jump_positions(bridge, effect), np.asarray(bridge.support_x, float))
        if y is not None and isinstance(effect.influence, TabulatedInfluence):
            out = np.union1d(out, station_kinks(effect.influence, float(y)))
        out.setflags(write=False)
        return effect, out  # (the effect kept with its identity: no other can take it while kept)

    # kept by the bridge per effect and line: every event of a stream asks for the same few
    return kept_for(bridge, "kink positions", KINK_POSITIONS_KEPT).get((id(effect), y), make)[1]


#: the ``kink_positions`` a bridge keeps (per effect and wheel line)
KINK_POSITIONS_KEPT = 256


#: a tabulated line breaks at a station where its value or slope changes by more than this fraction
#: of its largest value or slope (round-off of the tables' cubics: ≈ 1e-13, ``TabulatedInfluence``)
STATION_BREAK = 1e-8
def station_kinks(influence: TabulatedInfluence, y: float) -> NDArray[np.float64]:
    """The interior stations ξ [m] of ``influence`` at which its cubics along the wheel line ``y`` [m]
    (``line_tables``, without the section's own kink or step) meet with a break: the end value or
    slope of one element against the start of the next, beyond ``STATION_BREAK`` of the line's
    largest (``kink_positions`` keeps them per effect and line)."""
    poly = np.asarray(influence.line_tables([y])[0], float)  # (4, n_elements), rows t⁰ … t³
    h = np.diff(np.asarray(influence.stations, float))
    start_value, end_value = poly[0], poly.sum(axis=0)
    start_slope, end_slope = poly[1] / h, (poly[1] + 2.0 * poly[2] + 3.0 * poly[3]) / h
    value_scale = max(float(np.abs(poly).sum(axis=0).max(initial=0.0)), 1e-300)
    slope_scale = max(float(np.abs(np.r_[start_slope, end_slope]).max(initial=0.0)), 1e-300)
    broken = (np.abs(end_value[:-1] - start_value[1:]) > STATION_BREAK * value_scale) | \
        (np.abs(end_slope[:-1] - start_slope[1:]) > STATION_BREAK * slope_scale)
    return np.asarray(influence.stations, float)[1:-1][broken]
