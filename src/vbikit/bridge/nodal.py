"""Mode shapes given at the nodes of a rectangular deck grid, evaluated anywhere on the deck.

Both the slab-on-girder FE model (``vbikit.bridge.girder_deck``) and modes imported from
other programs (``vbikit.bridge.modefile``) store their modes the same way: on ``n_lines``
longitudinal lines y = y_j (girder lines, ascending y) at ``n_st`` stations x = x_i (ascending,
x_0 = 0, x_last = span), every mode has the nodal values

* ``w``   vertical displacement [kg^-1/2] (mass-normalised, z up),
* ``wx``  longitudinal slope ∂w/∂x [kg^-1/2 m^-1],
* ``wy``  transverse slope ∂w/∂y [kg^-1/2 m^-1] (rotation of the line about the x axis),

arrays of shape (n_lines, n_st, n_modes).  Interpolation rule (the FE model's own shape
functions along the girders, documented in ``docs/bridges.md``):

* along a line, w(x) is the cubic Hermite polynomial of (w, ∂w/∂x) of the element containing x
  (Euler–Bernoulli beam element); it is C¹ in x and its second derivative is the girder curvature;
* the transverse slope along a line, ∂w/∂y(x), is the C² cubic spline through its nodal values;
* across y between two lines, w is the cubic Hermite polynomial of (w, ∂w/∂y) at the two lines
  (the transverse beam element); outside the outermost lines (deck overhangs) the deck section
  is extrapolated rigidly: w = w_j + ∂w/∂y|_j · (y − y_j).

φ(x, y) is therefore C¹ in x at every y, as the solver's Hermite track tables assume, and it
reproduces w exactly on every line.  Outside 0 ≤ x ≤ span every shape is zero.

Skew decks (``skew_tan`` = tan θ ≠ 0).  The support lines are oblique: line j's stations lie at
x = ξ_i + y_j tan θ, so ``x`` holds the stations ξ_i along the lines (the distance from each line's
entry support) and a deck point (x, y) has ξ = x − y tan θ.  Between lines w is interpolated along
the oblique transverse members (constant ξ) — the cubic Hermite polynomial in y of w and of the
slope along them per unit y, ∂w/∂y + tan θ ∂w/∂x — and over the overhangs the section along that
direction moves rigidly; ∂φ/∂x at fixed y is ∂/∂ξ of that.  A point is on the deck while
0 ≤ ξ ≤ span.  ``wx`` and ``wy`` stay the Cartesian slopes; tan θ = 0 is the rectangular grid.
Between the lines of a skew deck φ is only C⁰ in x: its slope jumps at the stations by
tan θ · N(y) · Δ(∂²w/∂ξ²) of the lines (N the Hermite weight of the slope across), which the
solver's track tables, sampled on one side of a station, smooth over one table cell.

Grid helpers shared by the grid models: ``hermite_basis`` (the cubic Hermite shape functions),
``snap_to_stations`` (a section within round-off of a station is that station),
``girder_line_strain`` (bottom-fibre strains read on the lines) and ``DofMap`` (the
numbering of a three-DOF-per-node grid, how FE solutions become ``NodalModes``).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline


def hermite_basis(t: NDArray[np.float64], h: NDArray[np.float64] | float, order: int) -> tuple[NDArray[np.float64], ...]:
    """Cubic Hermite basis (N1, N2, N3, N4) for (value₀, slope₀, value₁, slope₁) at local t ∈ [0, 1]
    on an interval of length h, or its ``order``-th derivative with respect to the physical coordinate."""
    if order == 0:
        return (1 - 3 * t**2 + 2 * t**3, h * (t - 2 * t**2 + t**3), 3 * t**2 - 2 * t**3, h * (t**3 - t**2))
    if order == 1:
        return ((-6 * t + 6 * t**2) / h, 1 - 4 * t + 3 * t**2, (6 * t - 6 * t**2) / h, 3 * t**2 - 2 * t)
    if order == 2:
        return ((-6 + 12 * t) / h**2, (-4 + 6 * t) / h, (6 - 12 * t) / h**2, (6 * t - 2) / h)
    raise ValueError(order)


#: a section within this fraction of the span of a station is at the station: on a skew deck
#: x = ξ_i + y tan θ comes back as ξ = x − y tan θ with round-off either side of the node, where the
#: girders' curvatures and moments jump (a section at a station is read just right of it)
STATION_TOLERANCE = 1e-9


def snap_to_stations(xi: ArrayLike, stations: NDArray[np.float64]) -> NDArray[np.float64]:
    """ξ [m] with every value within ``STATION_TOLERANCE`` × the span (the stations' extent) of a
    station replaced by that station (read on the element right of it, whatever its round-off)."""
    xi = np.asarray(xi, float)
    k = np.clip(np.searchsorted(stations, xi), 1, stations.size - 1)
    near = np.where(np.abs(stations[k] - xi) < np.abs(stations[k - 1] - xi), k, k - 1)
    close = np.abs(stations[near] - xi) <= STATION_TOLERANCE * (stations[-1] - stations[0])
    return np.where(close, stations[near], xi)


@dataclass(frozen=True)
class NodalModes:
    """Nodal mode shapes on a rectangular grid and their interpolation (see module docstring)."""

    x: NDArray[np.float64]  # stations (n_st,), ascending, x[0] = 0, x[-1] = span
    y: NDArray[np.float64]  # line positions (n_lines,), ascending
    w: NDArray[np.float64]  # (n_lines, n_st, n_modes)
    wx: NDArray[np.float64]
    wy: NDArray[np.float64]
    skew_tan: float = 0.0  # tan θ of the support lines' skew (module docstring)
    _wy_spline: CubicSpline = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        x, y = np.asarray(self.x, float), np.asarray(self.y, float)
        if x.ndim != 1 or x.size < 2 or np.any(np.diff(x) <= 0):
            raise ValueError("stations x must be at least two strictly ascending values")
        if y.ndim != 1 or y.size < 1 or np.any(np.diff(y) <= 0):
            raise ValueError("line positions y must be strictly ascending")
        shape = (y.size, x.size)
        for name in ("w", "wx", "wy"):
            a = np.asarray(getattr(self, name), float)
            if a.ndim != 3 or a.shape[:2] != shape:
                raise ValueError(f"{name} must have shape (n_lines, n_stations, n_modes) = {shape + ('n',)}, got {a.shape}")
            object.__setattr__(self, name, a)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)
        if not np.isfinite(self.skew_tan):
            raise ValueError(f"skew_tan must be finite, got {self.skew_tan!r}")
        object.__setattr__(self, "skew_tan", float(self.skew_tan))
        # spline along x (axis 1) of the transverse slopes; not-a-knot ends
        spline = CubicSpline(x, self.wy, axis=1) if x.size > 2 else None
        object.__setattr__(self, "_wy_spline", spline)

    @property
    def n_modes(self) -> int:
        return self.w.shape[2]

    @property
    def span(self) -> float:
        return float(self.x[-1])

    # ------------------------------------------------------------ along the lines
    def _locate_x(self, x: NDArray[np.float64]) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.float64]]:
        e = np.clip(np.searchsorted(self.x, x, side="right") - 1, 0, self.x.size - 2)
        h = self.x[e + 1] - self.x[e]
        return e, (x - self.x[e]) / h, h

    def line_values(self, x: NDArray[np.float64], order: int = 0) -> NDArray[np.float64]:
        """∂^order w / ∂x^order on every line at stations x: shape (n_lines, n_points, n_modes)."""
        e, t, h = self._locate_x(x)
        n = hermite_basis(t, h, order)
        w, wx = self.w, self.wx
        return (n[0][None, :, None] * w[:, e] + n[1][None, :, None] * wx[:, e]
                + n[2][None, :, None] * w[:, e + 1] + n[3][None, :, None] * wx[:, e + 1])

    def line_transverse_slopes(self, x: NDArray[np.float64], order: int = 0) -> NDArray[np.float64]:
        """∂/∂x^order of ∂w/∂y on every line at x: shape (n_lines, n_points, n_modes)."""
        if self._wy_spline is None:  # two stations: linear
            e, t, h = self._locate_x(x)
            if order == 0:
                return self.wy[:, e] * (1 - t)[None, :, None] + self.wy[:, e + 1] * t[None, :, None]
            return np.broadcast_to(((self.wy[:, 1] - self.wy[:, 0]) / h[0])[:, None, :], (self.y.size, x.size, self.n_modes))
        return self._wy_spline(x, nu=order)

    # ------------------------------------------------------------ anywhere
    def evaluate(self, x: ArrayLike, y: ArrayLike, order_x: int = 0) -> NDArray[np.float64]:
        """∂^order_x φ / ∂x^order_x at the points (x, y) (broadcast): shape (n_points, n_modes).

        ``order_x`` is 0 (values) or 1 (longitudinal slopes).  Zero outside 0 ≤ x ≤ span.
        """
        x, y = np.broadcast_arrays(np.atleast_1d(np.asarray(x, float)), np.atleast_1d(np.asarray(y, float)))
        x, y = x.ravel(), y.ravel()
        out = np.zeros((x.size, self.n_modes))
        if self.skew_tan:
            x = x - y * self.skew_tan  # ξ; ∂/∂x at fixed y is ∂/∂ξ
        on = (x >= 0.0) & (x <= self.span)
        if not np.any(on):
            return out
        xo, yo = x[on], y[on]
        w = self.line_values(xo, order_x)  # (n_lines, p, m)
        if self.y.size == 1 and not self.skew_tan and np.all(yo == self.y[0]):
            out[on] = w[0]  # on the only line: its transverse slope times 0 adds nothing (a beam)
            return out
        s = self.line_transverse_slopes(xo, order_x)
        if self.skew_tan:  # slope along the oblique transverse members, per unit y
            s = s + self.skew_tan * self.line_values(xo, order_x + 1)
        p = np.arange(xo.size)
        ly = self.y
        if ly.size == 1:
            res = w[0] + s[0] * (yo - ly[0])[:, None]
        else:
            j = np.clip(np.searchsorted(ly, yo, side="right") - 1, 0, ly.size - 2)
            b = ly[j + 1] - ly[j]
            t = (yo - ly[j]) / b
            n = hermite_basis(t, b, 0)
            res = (n[0][:, None] * w[j, p] + n[1][:, None] * s[j, p] + n[2][:, None] * w[j + 1, p] + n[3][:, None] * s[j + 1, p])
            lo, hi = yo < ly[0], yo > ly[-1]  # overhangs: rigid extrapolation of the outer line
            res[lo] = w[0, p[lo]] + s[0, p[lo]] * (yo[lo] - ly[0])[:, None]
            res[hi] = w[-1, p[hi]] + s[-1, p[hi]] * (yo[hi] - ly[-1])[:, None]
        out[on] = res
        return out

    def curvatures(self, x: ArrayLike, line_index: ArrayLike) -> NDArray[np.float64]:
        """∂²w/∂x² [kg^-1/2 m^-2] of line ``line_index`` at x (broadcast), shape (n_points, n_modes); zero off the span
        (x is the deck's x: on a skew deck line j's ξ is x − y_j tan θ)."""
        x, j = np.broadcast_arrays(np.atleast_1d(np.asarray(x, float)), np.atleast_1d(np.asarray(line_index, int)))
        x, j = x.ravel(), j.ravel()
        out = np.zeros((x.size, self.n_modes))
        if self.skew_tan:
            x = x - self.y[j] * self.skew_tan  # ξ on line j
        on = (x >= 0.0) & (x <= self.span)
        if np.any(on):
            k = self.line_values(x[on], 2)
            out[on] = k[j[on], np.arange(k.shape[1])]
        return out


def girder_line_strain(modes: NodalModes, lever_arm: NDArray[np.float64], x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
    """ε = c_g ∂²w/∂x² on the line(s) y (linear between lines, clamped beyond), shape (n_points, n_modes);
    ``lever_arm`` c_g [m] per line; on a skew deck the lines are read at the point's own ξ = x − y tan θ
    (along the oblique members); at a station (within round-off, ``snap_to_stations``) on the
    element right of it."""
    x, y = np.broadcast_arrays(np.atleast_1d(np.asarray(x, float)), np.atleast_1d(np.asarray(y, float)))
    x, y = x.ravel(), y.ravel()
    xi = snap_to_stations(x - y * modes.skew_tan if modes.skew_tan else x, modes.x)
    out = np.zeros((x.size, modes.n_modes))
    on = (xi >= 0.0) & (xi <= modes.span)
    if not np.any(on):
        return out
    k = modes.line_values(xi[on], 2)  # (n_lines, p, m)
    p = np.arange(k.shape[1])
    ly = modes.y
    if ly.size == 1:
        out[on] = lever_arm[0] * k[0]
        return out
    yc = np.clip(y[on], ly[0], ly[-1])
    j = np.clip(np.searchsorted(ly, yc, side="right") - 1, 0, ly.size - 2)
    t = ((yc - ly[j]) / (ly[j + 1] - ly[j]))[:, None]
    out[on] = (1 - t) * lever_arm[j][:, None] * k[j, p] + t * lever_arm[j + 1][:, None] * k[j + 1, p]
    return out


@dataclass(frozen=True)
class DofMap:
    """Numbering of the degrees of freedom of a deck grid with three DOFs per node (w, ∂w/∂x, ∂w/∂y):
    node (line j, station i) has DOFs 3 (j n_st + i) + k, k = 0 (w), 1 (∂w/∂x), 2 (∂w/∂y).

    ``stations`` ξ_i [m] along the lines (ascending, 0 … span), ``line_y`` y_j [m] of the lines
    (ascending), ``skew_tan`` tan θ of the support lines (line j's node i lies at x = ξ_i + y_j tan θ).
    """

    stations: NDArray[np.float64]
    line_y: NDArray[np.float64]
    skew_tan: float = 0.0

    @property
    def n_stations(self) -> int:
        return int(self.stations.size)

    @property
    def n_elements(self) -> int:
        """Elements along each line (n_st − 1)."""
        return int(self.stations.size) - 1

    @property
    def n_lines(self) -> int:
        return int(self.line_y.size)

    @property
    def n_dof(self) -> int:
        """Total number of DOFs, 3 n_lines n_st."""
        return 3 * self.n_lines * self.n_stations

    def dof(self, line: ArrayLike, station: ArrayLike, k: int) -> Any:
        """DOF index (int, or an int array for array arguments) of component k (0: w, 1: ∂w/∂x, 2: ∂w/∂y)
        at node (``line``, ``station``), both 0-based."""
        return 3 * (line * self.n_stations + station) + k  # type: ignore[operator]

    def nodal(self, u: NDArray[np.float64]) -> NodalModes:
        """Columns of ``u`` (n_dof, n) over all DOFs as ``NodalModes`` on this grid."""
        shape = (self.n_lines, self.n_stations, u.shape[1])
        return NodalModes(self.stations, self.line_y, u[0::3].reshape(shape), u[1::3].reshape(shape),
                          u[2::3].reshape(shape), self.skew_tan)

    def vector(self, modes: NodalModes) -> NDArray[np.float64]:
        """The inverse of ``nodal``: nodal values of ``modes`` as a (n_dof, n_modes) matrix."""
        n = modes.n_modes
        out = np.zeros((self.n_dof, n))
        out[0::3] = modes.w.reshape(-1, n)
        out[1::3] = modes.wx.reshape(-1, n)
        out[2::3] = modes.wy.reshape(-1, n)
        return out
