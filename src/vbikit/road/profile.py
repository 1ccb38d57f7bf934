"""Road surface profiles: sampled elevations with linear interpolation.

Every profile — flat, random from a PSD (paper Eq. 7), or measured — is a
[`RoadProfile`][vbikit.road.RoadProfile]: elevations z_j [m] at increasing stations x_j [m] (x from the bridge
entry, negative on the approach), linearly interpolated in between.  Evaluating outside the
sampled range is an error: the crossing checks coverage before it starts.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray


@dataclass(frozen=True)
class RoadOrigin:
    """Where a road profile comes from, as data (the road warning names it and says what to check:
    ``vbikit.analysis.checks.road_origin``).

    Parameters
    ----------
    kind : str
        "random" (from a PSD: [`random_profile`][vbikit.road.random_profile]), "measured" (a profile
        file), "smooth" (r ≡ 0) or "" (given as arrays).
    road_class : str, optional
        A random road's class as the scenario names it ("A"…"H", "good"…, "psd").
    seed : int, optional
        A random road's seed.
    file : str, optional
        A measured profile's file name.
    defects : tuple of str
        The kinds of the defects added (``with_defects``), in order.
    shortest_wavelength : float, optional
        A random road's shortest wavelength 1/n_max [m] (its spectrum's band; set by ``random_profile``).
    roughness : float, optional
        A random road's spectrum at n₀ = 0.1 cycle/m, G_d(n₀) [m³/cycle] (ISO 8608's classification
        quantity; set by ``random_profile``).
    """

    kind: str = ""
    road_class: str | None = None
    seed: int | None = None
    file: str | None = None
    defects: tuple[str, ...] = ()
    shortest_wavelength: float | None = None
    roughness: float | None = None


@dataclass(frozen=True)
class RoadProfile:
    """Road elevation r(x) [m] (z up) sampled at stations ``x`` [m], linear in between.

    Parameters
    ----------
    x : ndarray
        Stations [m].
    z : ndarray
        Elevation r [m] at each station, z up.
    label : str
        The origin (e.g. "ISO C, seed 3").
    resolution : float, optional
        Length [m] of the shortest feature the time step must resolve (default: the finest
        sample spacing; see [`spacing`][vbikit.road.RoadProfile.spacing]).
    origin : RoadOrigin, optional
        Where the profile comes from, as data (set by ``random_profile``, ``read_profile_csv``,
        ``with_defects``, ``flat``); None: not known.
    """

    x: NDArray[np.float64]
    z: NDArray[np.float64]
    label: str = ""
    resolution: float | None = None
    origin: RoadOrigin | None = None

    def __post_init__(self) -> None:
        x, z = np.asarray(self.x, float), np.asarray(self.z, float)
        if x.ndim != 1 or x.shape != z.shape or x.size < 2:
            raise ValueError("road profile needs matching 1-D x and z arrays with at least 2 samples")
        if not (np.isfinite(x).all() and np.isfinite(z).all()):
            raise ValueError("road profile contains non-finite values")
        if (x[1:] <= x[:-1]).any():  # x_{j+1} − x_j ≤ 0 for finite x, without the differences' array
            raise ValueError("road profile stations x must be strictly increasing")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "z", z)

    @classmethod
    def flat(cls, x_min: float = -1e4, x_max: float = 1e4) -> "RoadProfile":
        """A perfectly smooth road (r ≡ 0) from x_min to x_max [m]."""
        return cls(np.array([x_min, x_max], float), np.zeros(2), "smooth", origin=RoadOrigin("smooth"))

    @property
    def spacing(self) -> float:
        """Shortest feature [m] the time step must resolve: ``resolution`` if given, else the finest
        sample spacing; 0 if the profile is flat (nothing to resolve).  Computed once (a profile is immutable)."""
        known = self.__dict__.get("_spacing")
        if known is None:
            if not np.any(self.z):
                known = 0.0
            elif self.resolution is not None:
                known = float(self.resolution)
            else:
                known = float(np.min(np.diff(self.x)))
            object.__setattr__(self, "_spacing", known)
        return known

    @property
    def has_features(self) -> bool:
        """``spacing`` > 0 (something for the time step to resolve), without the stations' differences
        ``spacing`` takes when not yet known: a profile that is not flat has strictly increasing stations,
        so its finest spacing is > 0, and a given ``resolution`` is its spacing."""
        known = self.__dict__.get("_spacing")
        if known is not None:
            return known > 0
        if not np.any(self.z):
            return False
        return self.resolution is None or float(self.resolution) > 0

    @property
    def band_limited(self) -> bool:
        """True for a generated road without defects: smooth, or random from a spectrum
        (``RoadOrigin.shortest_wavelength`` set: no wavelength below 1/n_max, 25 cm for ISO 8608's
        4 cycle/m), whose stations sample that signal rather than edges a time step must resolve one
        by one; measured profiles, defects and given arrays are not (every station may be an edge)."""
        origin = self.origin
        if origin is None or origin.defects:
            return False
        return origin.kind == "smooth" or (origin.kind == "random" and origin.shortest_wavelength is not None)

    def covers(self, x_min: float, x_max: float) -> bool:
        return bool(self.x[0] <= x_min and x_max <= self.x[-1])

    def _check(self, x: NDArray[np.float64]) -> None:
        if x.size and (x.min() < self.x[0] - 1e-9 or x.max() > self.x[-1] + 1e-9):
            raise ValueError(
                f"road profile '{self.label}' covers x = {self.x[0]:.3f} … {self.x[-1]:.3f} m, "
                f"but x = {x.min():.3f} … {x.max():.3f} m was requested"
            )

    def evaluate(self, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Elevation r(x) [m] and slope dr/dx [-] (right-hand slope at a station) in one pass.

        Searching is fastest when the last axis of ``x`` is sorted (one contact point's path).
        """
        x = np.asarray(x, float)
        self._check(x)
        seg = np.clip(np.searchsorted(self.x, x, side="right") - 1, 0, self.x.size - 2)
        slope = (self.z[seg + 1] - self.z[seg]) / (self.x[seg + 1] - self.x[seg])
        return self.z[seg] + slope * (x - self.x[seg]), slope

    def secant_rate(self, x: ArrayLike, vx: ArrayLike, span: float) -> NDArray[np.float64]:
        """The road rate the implicit integrators read [m/s] (``vbikit.solve.kernels``, "the road rate"):
        vx (r(x + a) − r(x − a)) / 2a at positions ``x`` [m] of points moving at ``vx`` [m/s], with
        a = |vx|·``span`` [s] (dt/2: the half steps around a step end); ``span`` < 0, the run's start:
        the road ahead only, vx (r(x + a) − r(x)) / a driving +x (vx (r(x) − r(x − a)) / a driving −x),
        a = |vx|·|span|.  Beyond the profile's ends its end segments extended as the kernels extend
        them; vx·dr/dx (``evaluate``) where a = 0."""
        x = np.asarray(x, float)
        vx = np.broadcast_to(np.asarray(vx, float), x.shape)
        a = np.abs(vx) * abs(span)
        lo, hi = x - a, x + a
        if span < 0.0:
            lo, hi = np.where(vx > 0.0, x, lo), np.where(vx > 0.0, hi, x)
        width = np.where(a > 0.0, hi - lo, 1.0)
        secant = (self._extended(hi) - self._extended(lo)) / width
        return vx * (secant if np.all(a > 0.0) else np.where(a > 0.0, secant, self.evaluate(x)[1]))

    def run_rates(self, x: ArrayLike, vx: ArrayLike, span: float, axis: int = 0) -> NDArray[np.float64]:
        """The road rates [m/s] the implicit integrators read at a run's step ends (``secant_rate``):
        positions ``x`` [m] and x-rates ``vx`` [m/s] with time along ``axis``, its first entry the
        run's start, read over the road ahead only (``span`` negated), every other entry the secant
        over ±|vx|·``span`` [s] (dt/2)."""
        x = np.asarray(x, float)
        vx = np.broadcast_to(np.asarray(vx, float), x.shape)
        rate = self.secant_rate(x, vx, span)
        first = (slice(None),) * (axis % x.ndim) + (0,)
        rate[first] = self.secant_rate(x[first], vx[first], -span)
        return rate

    def _extended(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """r(x) [m], beyond the profile's ends along its end segments."""
        inside = np.clip(x, self.x[0], self.x[-1])
        r, slope = self.evaluate(inside)
        return r + slope * (x - inside)

    def elevation(self, x: ArrayLike) -> NDArray[np.float64]:
        """r(x) [m]."""
        return self.evaluate(x)[0]

    def slope(self, x: ArrayLike) -> NDArray[np.float64]:
        """dr/dx [-] of the piecewise-linear profile."""
        return self.evaluate(x)[1]
