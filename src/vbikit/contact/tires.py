"""Tire contact models: where a wheel touches the surface and how its tire force is built.

Every tire model maps one wheel to contact points p, each at a longitudinal offset ξ_p [m]
from the wheel centre (positive forward, towards +x on the bridge), with a spring k_p, a
dashpot c_p and a geometric gap g_p ≥ 0 (height of the tire's surface above its lowest point
at ξ_p; 0 for point and multi-point tires).  With s = deck displacement + road elevation
under the point and z_w the displacement of the wheel's lowest point (z up), the penetration
is δ_p = s(x_p) − g_p − z_w and

    F_p = k_p δ_p + c_p δ̇_p                                   (paper Eqs. 3–6)

F > 0 is compression.  A tire cannot pull: with loss of contact enabled (the default) a point
carries F_p = max(0, k_p δ_p + c_p δ̇_p) while δ_p > 0 and nothing otherwise; disk points are
always gated so (the disk's contact patch is where it penetrates).  The wheel force is the sum
over its points, except for the rigid disk, which acts through its single highest point (the
envelope).  All four models run through this one mechanism (``vbikit.solve.kernels``).

* [`PointTire`][vbikit.contact.PointTire] — one point under the wheel centre.
* [`MultiPointTire`][vbikit.contact.MultiPointTire] — the paper's n points of k/n, c/n over 0.254 m (Eq. 6); n = 1 is the
  point tire, through the same code, so it reproduces it exactly.
* [`DiskTire`][vbikit.contact.DiskTire] — deformable disk of radial springs (after Yin et al.; our formulation,
  model data §3).
* [`RigidDiskTire`][vbikit.contact.RigidDiskTire] — rigid disk following the surface envelope (after Chang et al.).

Each model declares its scenario ``name``, a ``description``, its ``references`` and its
``Parameters`` (the keys of its ``[tire]`` table) and is registered by name with
[`register_tire`][vbikit.contact.register_tire].
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray
from pydantic import Field

from vbikit.contact.base import ContactLayout, TireModel, TireParameters
from vbikit.contact.registry import register_tire

#: [public] AASHTO LRFD tire contact length 10 in [m]
AASHTO_CONTACT_LENGTH = 0.254


@register_tire
@dataclass(frozen=True)
class PointTire(TireModel):
    """Single-point contact: one spring–dashpot under the wheel centre."""

    name = "point"
    description = "single-point contact"

    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return np.zeros(1), np.ones(1)


@register_tire
@dataclass(frozen=True)
class MultiPointTire(TireModel):
    """The paper's multi-point tire (Eq. 6): n spring–dampers of k/n, c/n along the patch.

    Parameters
    ----------
    n_points : int
        Number of contact points n ≥ 1 ([paper] recommends 6).
    contact_length : float
        Patch length a [m]; default 0.254 m [public] AASHTO 10 in, as the paper.
    layout_rule : {"ends", "cells"}
        "ends" [substitute, default]: points from −a/2 to +a/2 at spacing a/(n − 1), the
        paper's "span a length of 25.4 cm" read literally; "cells": each point at the centre
        of one of n equal cells (spacing a/n).  n = 1 is the centre in both.
    """

    n_points: int = 6
    contact_length: float = AASHTO_CONTACT_LENGTH
    layout_rule: Literal["ends", "cells"] = "ends"
    name = "multipoint"
    description = "the paper's multi-point tire (Eq. 6): n points of k/n, c/n along the contact patch"
    references = ("MultiPointTire", "AASHTO-LRFD")

    class Parameters(TireParameters):
        """[tire] keys of the multi-point tire."""

        n_points: int = Field(6, ge=1, le=100, description="contact points per tire, each with k/n and c/n [-]")
        contact_length: float = Field(AASHTO_CONTACT_LENGTH, gt=0, le=2.0, description="patch length, AASHTO's 10 in [m]")
        layout: Literal["ends", "cells"] = Field(
            "ends", description="points from −a/2 to a/2 (ends) or at the centres of n equal cells (cells)")

    @classmethod
    def from_parameters(cls, parameters: TireParameters) -> MultiPointTire:
        p = parameters
        return cls(p.n_points, p.contact_length, p.layout)  # type: ignore[attr-defined]

    @property
    def patch_length(self) -> float:
        return self.contact_length if self.n_points > 1 else 0.0

    def __post_init__(self) -> None:
        if int(self.n_points) != self.n_points or self.n_points < 1:
            raise ValueError(f"n_points must be an integer >= 1, got {self.n_points!r}")
        if not self.contact_length > 0:
            raise ValueError(f"contact_length must be > 0 m, got {self.contact_length!r}")
        if self.layout_rule not in ("ends", "cells"):
            raise ValueError(f"layout_rule must be 'ends' or 'cells', got {self.layout_rule!r}")

    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        n, a = int(self.n_points), self.contact_length
        if n == 1:
            offsets = np.zeros(1)
        elif self.layout_rule == "ends":
            offsets = np.linspace(-a / 2, a / 2, n)
        else:
            offsets = (np.arange(n) + 0.5) * (a / n) - a / 2
        return offsets, np.full(n, 1.0 / n)

    def spacing(self) -> float:
        """Spacing between neighbouring points [m] (0 for n = 1)."""
        n = int(self.n_points)
        if n == 1:
            return 0.0
        return self.contact_length / (n - 1 if self.layout_rule == "ends" else n)

    def transfer(self, wavenumber: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """|H(ν)| = |Σ_p β_p exp(2πiνξ_p)|: how the points average a road harmonic of ν [cycle/m].

        For n equal weights at spacing s this is |sin(πνsn) / (n sin(πνs))| (model data §3),
        evaluated here without the 0/0 at νs = integer.
        """
        nu = np.asarray(wavenumber, dtype=float)
        offsets, weights = self.layout()
        return np.abs(np.exp(2j * np.pi * nu[..., None] * offsets) @ weights)


#: [substitute] truck tire radius R [m] (model data §3)
DEFAULT_TIRE_RADIUS = 0.5


def _disk_offsets(radius: float, spacing: float, max_gap: float) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """Offsets ξ_p (symmetric, spacing Δξ) over |ξ| ≤ ξ_max where the disk rises at most max_gap, and gaps g_p."""
    xi_max = float(np.sqrt(radius**2 - (radius - max_gap) ** 2))
    half = int(np.ceil(xi_max / spacing))
    offsets = np.arange(-half, half + 1) * spacing
    gaps = radius - np.sqrt(np.clip(radius**2 - offsets**2, 0.0, None))
    return offsets, gaps, spacing


def _check_disk(radius: float, spacing: float, max_gap: float) -> None:
    if not radius > 0:
        raise ValueError(f"tire radius must be > 0 m, got {radius!r}")
    if not 0 < spacing <= radius / 5:
        raise ValueError(f"disk point spacing must be in (0, radius/5] = (0, {radius / 5:g}] m, got {spacing!r}")
    if not 0 < max_gap < radius:
        raise ValueError(f"disk max_gap must be in (0, radius) m, got {max_gap!r}")


@dataclass(frozen=True)
class _DiskGeometry(TireModel):
    """Shared geometry of the disk tires: radius R [m], point spacing Δξ [m], arc height max_gap [m]."""

    radius: float = DEFAULT_TIRE_RADIUS
    spacing: float = 0.01
    max_gap: float = 0.1

    class Parameters(TireParameters):
        """[tire] keys of the disk tires."""

        radius: float = Field(DEFAULT_TIRE_RADIUS, gt=0.05, le=2.0, description="tire radius [m]")
        disk_spacing: float = Field(0.01, gt=0, le=0.1, description="spacing of the radial springs [m]")

    @classmethod
    def from_parameters(cls, parameters: TireParameters) -> _DiskGeometry:
        """Radius R and spacing from the scenario; the arc represented up to max_gap = R/5."""
        p = parameters
        return cls(radius=p.radius, spacing=p.disk_spacing, max_gap=p.radius / 5)  # type: ignore[attr-defined]

    def __post_init__(self) -> None:
        _check_disk(self.radius, self.spacing, self.max_gap)

    def _points(self) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        return _disk_offsets(self.radius, self.spacing, self.max_gap)

    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        offsets, gaps, _ = self._points()
        share = np.where(gaps == 0.0, 1.0, 0.0)
        return offsets, share / share.sum()


@register_tire
@dataclass(frozen=True)
class DiskTire(_DiskGeometry):
    """Deformable disk of radial springs (after Yin et al.; [substitute] formulation of model data §3).

    A disk of radius R whose lowest point moves with the wheel; penetration
    δ(ξ) = max(0, s(x_c + ξ) − z_w − g(ξ)), g(ξ) = R − √(R² − ξ²); wheel force
    F = k_ξ ∫ δ dξ + c_ξ ∫_{δ>0} δ̇ dξ, evaluated by the midpoint rule on points at spacing
    Δξ over the part of the disk within ``max_gap`` of its bottom, and applied to the deck
    where δ > 0 (the contact patch).  On a flat surface F = (4/3) k_ξ √(2R) d^{3/2} at
    compression d, with patch length 2√(2Rd).

    Calibration (per wheel, after model data §3): static load F_s and tangent stiffness at
    static equal to the single-point tire's k_t in the parabolic closed form: d_s = 1.5 F_s / k_t,
    k_ξ = F_s / ((4/3) √(2R) d_s^{3/2}); k_ξ is then scaled (by ≈ 1 %) so that the discrete
    circular disk carries exactly F_s at d_s.  The discrete tangent stiffness counts the springs
    in contact, so it matches k_t only to about one spring in the patch (≈ 2–3 % at Δξ = 1 cm).
    The damping per length c_ξ = c / (2√(2R d_s)) gives the tire's c at static.  For an HS20
    rear wheel (R = 0.5 m) the static patch is ≈ 0.34 m long.

    Parameters
    ----------
    radius : float
        R [m], default 0.5 m [substitute].
    spacing : float
        Δξ [m] between radial springs (default 0.01 m, the road sampling).
    max_gap : float
        Height [m] of the disk arc represented (default R/5 = 0.1 m): obstacles up to
        max_gap minus the tire's compression (≈ 0.09 m for a loaded truck wheel) are seen whole.
    """

    name = "disk"
    description = "deformable disk of radial springs (after Yin et al.)"
    references = ("Yin2010",)

    def static_compression(self, stiffness: float, static_load: float) -> float:
        """d_s = 1.5 F_s / k_t [m]."""
        return 1.5 * static_load / stiffness

    def contact_layout(self, stiffness: float, damping: float, static_load: float) -> ContactLayout:
        offsets, gaps, dxi = self._points()
        if stiffness <= 0 or static_load <= 0:
            raise ValueError("a disk tire needs a wheel with tire stiffness > 0 and a positive static load")
        d_s = self.static_compression(stiffness, static_load)
        if d_s >= self.max_gap:
            raise ValueError(f"static tire compression {d_s:.3f} m exceeds the disk's max_gap {self.max_gap} m")
        k_xi = static_load / (4.0 / 3.0 * np.sqrt(2 * self.radius) * d_s**1.5)
        # the discrete circular disk is ≈ 1 % softer than the parabolic closed form: rescale so
        # that the static wheel load is carried exactly at d_s
        k_xi *= static_load / (k_xi * dxi * np.clip(d_s - gaps, 0.0, None).sum())
        c_xi = damping / (2.0 * np.sqrt(2 * self.radius * d_s))
        static_force = k_xi * dxi * np.clip(d_s - gaps, 0.0, None)
        return ContactLayout(offsets, np.full_like(offsets, k_xi * dxi), np.full_like(offsets, c_xi * dxi), gaps,
                             static_force / static_force.sum(), np.full_like(offsets, dxi), gated=True)

    def static_patch_length(self, stiffness: float, static_load: float) -> float:
        """2√(2R d_s) [m]: contact length at the static load on a flat surface."""
        return float(2.0 * np.sqrt(2.0 * self.radius * self.static_compression(stiffness, static_load)))

    @property
    def patch_length(self) -> float:
        return 0.0


@register_tire
@dataclass(frozen=True)
class RigidDiskTire(_DiskGeometry):
    """Rigid disk (after Chang et al.): the tire spring sits under the envelope of the surface.

    The contact height is e(x_c) = max_{|ξ| ≤ ξ_max} [ s(x_c + ξ) − (R − √(R² − ξ²)) ], the top
    of the surface as seen by a rigid circle of radius R; one spring k and dashpot c (the
    single-point tire's) act between e and the wheel, at the point that attains the maximum.
    The maximum is taken over points at spacing Δξ (default 0.01 m) within ``max_gap`` of the
    bottom of the circle.  The contact height's rate is the deck velocity under the contact
    point plus v·e'(x_c), where the envelope slope e' equals the circle's slope g'(ξ*) at the
    continuous contact point (tangency; at a corner of the surface the circle rolls over it):
    the surface slope at the grid point is clamped to the range of g' over the point's cell
    [ξ_p − Δξ/2, ξ_p + Δξ/2], exact on smooth surfaces and the rolling rate at corners.

    Parameters
    ----------
    radius : float
        R [m], default 0.5 m [substitute].
    spacing : float
        Δξ [m] between the points (default 0.01 m).
    max_gap : float
        Height [m] above the bottom of the circle within which the points lie (default 0.1 m).
    """

    name = "rigid-disk"
    description = "rigid disk following the surface envelope (after Chang et al.)"
    references = ("Chang2011",)

    def contact_layout(self, stiffness: float, damping: float, static_load: float) -> ContactLayout:
        offsets, gaps, _ = self._points()
        share = np.where(gaps == 0.0, 1.0, 0.0)

        def slope(xi: NDArray[np.float64]) -> NDArray[np.float64]:
            xi = np.clip(xi, -0.999 * self.radius, 0.999 * self.radius)
            return xi / np.sqrt(self.radius**2 - xi**2)

        half = 0.5 * self.spacing
        return ContactLayout(offsets, np.full_like(offsets, stiffness), np.full_like(offsets, damping), gaps, share,
                             np.zeros_like(offsets), gated=True, envelope=True,
                             slope_range=np.column_stack([slope(offsets - half), slope(offsets + half)]))
