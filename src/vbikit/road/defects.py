"""Deck defects as road features added to any profile.

Each defect adds a vertical offset Δz(x) [m] (z up) over [start, start + length]:

* ``depression`` — a dip of ``depth`` (default 0.020 m [paper]: the 20 mm depression at the
  bridge entry), trapezoidal with linear ramps; [substitute] length 0.6 m with 0.05 m ramps,
  starting at the bridge entry (x = 0) — the paper's Fig. 4 is not available.
* ``bump`` — a raised block of ``height`` (default 0.0381 m [paper]: the 1.5 in wood bump of
  the field test); [substitute] length 0.184 m (a nominal 2×8 board laid flat, 7.25 in) with
  0.005 m ramps, at the entry of the span.
* ``step`` — a joint with a step of ``height`` (signed, default +0.01 m [substitute]); the
  offset stays after the ramp (length = ramp length, default 0.02 m).
* ``pothole`` — a cosine dip of ``depth`` (default 0.05 m) and length (default 0.4 m)
  [substitute].

Shapes: "trapezoid" (linear ramps of length ``ramp`` at both ends), "cosine" (half-wave
1 − cos), "step" (one ramp, then constant).  Every breakpoint of a defect becomes a sample of
the profile (linear interpolation is then exact for the linear shapes).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from vbikit.road.profile import RoadOrigin, RoadProfile

DefectKind = Literal["depression", "bump", "step", "pothole"]
Shape = Literal["trapezoid", "cosine", "step"]

#: defaults per kind: (amplitude [m, signed z-up], length [m], ramp [m], shape)
DEFECT_DEFAULTS: dict[str, tuple[float, float, float, str]] = {
    "depression": (-0.020, 0.6, 0.05, "trapezoid"),
    "bump": (0.0381, 0.184, 0.005, "trapezoid"),
    "step": (0.01, 0.02, 0.02, "step"),
    "pothole": (-0.05, 0.4, 0.0, "cosine"),
}


@dataclass(frozen=True)
class Defect:
    """One road feature (see the module docstring; [`of_kind`][vbikit.road.Defect.of_kind] gives a
    kind's defaults).

    Parameters
    ----------
    kind : str
        "depression", "bump", "step" or "pothole".
    start : float
        Where it starts [m].
    amplitude : float
        Signed amplitude [m], z up.
    length : float
        Its length [m], > 0.
    ramp : float
        Ramp length [m] (trapezoid: in (0, length/2]).
    shape : str
        "trapezoid", "cosine" or "step".
    """

    kind: str
    start: float
    amplitude: float
    length: float
    ramp: float
    shape: str

    def __post_init__(self) -> None:
        if self.shape not in ("trapezoid", "cosine", "step"):
            raise ValueError(f"defect shape must be trapezoid, cosine or step, got {self.shape!r}")
        if not self.length > 0:
            raise ValueError(f"defect length must be > 0 m, got {self.length!r}")
        if self.shape == "trapezoid" and not 0 < 2 * self.ramp <= self.length:
            raise ValueError(f"defect ramp must be in (0, length/2] = (0, {self.length / 2:g}] m, got {self.ramp!r}")

    @classmethod
    def of_kind(cls, kind: str, start: float = 0.0, size: float | None = None, length: float | None = None,
                ramp: float | None = None, shape: str | None = None) -> "Defect":
        """A defect with the documented defaults of ``kind``; ``size`` is the depth or height [m] (positive)."""
        if kind not in DEFECT_DEFAULTS:
            raise ValueError(f"unknown defect kind {kind!r}; allowed: {', '.join(DEFECT_DEFAULTS)}")
        amp, dlen, dramp, dshape = DEFECT_DEFAULTS[kind]
        if size is not None:
            if kind != "step" and not size > 0:
                raise ValueError(f"defect size (depth or height) must be > 0 m, got {size!r}")
            amp = np.sign(amp) * size if kind != "step" else size
        shape = shape or dshape
        length = dlen if length is None else length
        if ramp is None:
            if shape == "step":
                ramp = length
            elif shape == "trapezoid":
                ramp = min(dramp if dramp > 0 else 0.05, length / 4 if dramp <= 0 else length / 2)
            else:
                ramp = dramp
        return cls(kind, float(start), float(amp), float(length), float(ramp), shape)

    @property
    def end(self) -> float:
        return self.start + self.length

    def breakpoints(self) -> NDArray[np.float64]:
        """Stations [m] where the shape has kinks (must be samples of the profile)."""
        if self.shape == "trapezoid":
            return np.array([self.start, self.start + self.ramp, self.end - self.ramp, self.end])
        return np.array([self.start, self.end])

    def offset(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Δz(x) [m]."""
        x = np.asarray(x, float)
        u = (x - self.start) / self.length
        inside = (u >= 0) & (u <= 1)
        if self.shape == "cosine":
            return np.where(inside, self.amplitude * 0.5 * (1 - np.cos(2 * np.pi * np.clip(u, 0, 1))), 0.0)
        if self.shape == "step":
            return self.amplitude * np.clip(u, 0.0, 1.0)
        rise = np.clip((x - self.start) / self.ramp, 0.0, 1.0)
        fall = np.clip((self.end - x) / self.ramp, 0.0, 1.0)
        return np.where(inside, self.amplitude * np.minimum(rise, fall), 0.0)


def with_defects(profile: RoadProfile, defects: list[Defect] | tuple[Defect, ...]) -> RoadProfile:
    """The profile plus every defect.  Breakpoints of linear shapes become samples; cosine shapes
    are sampled at ≤ length/80.  The profile's ``resolution`` becomes the shortest ramp (or
    cosine sample spacing), so the time step resolves the defect edges."""
    if not defects:
        return profile
    stations = [profile.x]
    finest = [profile.spacing] if profile.spacing > 0 else []
    for d in defects:
        stations.append(d.breakpoints())
        if d.shape == "cosine":
            n = 80
            stations.append(np.linspace(d.start, d.end, n + 1))
            finest.append(d.length / n)
        else:
            finest.append(d.ramp)
    x = np.unique(np.concatenate(stations))
    x = x[np.concatenate(([True], np.diff(x) > 1e-6))]  # merge stations closer than 1 µm
    x = x[(x >= profile.x[0]) & (x <= profile.x[-1])]
    z = profile.elevation(x) + sum(d.offset(x) for d in defects)
    label = profile.label + " + " + ", ".join(f"{d.kind} at {d.start:g} m" for d in defects)
    origin = profile.origin or RoadOrigin()
    origin = replace(origin, defects=origin.defects + tuple(d.kind for d in defects))
    return replace(profile, x=x, z=z, label=label, resolution=min(finest), origin=origin)
