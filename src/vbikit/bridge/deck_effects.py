"""Girder bending moments, shears and bearing reactions of the slab-on-girder grillage.

Load effects (``vbikit.bridge.effects``) of [`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge].
A point force P at (x, y) enters the grillage as its consistent load (Hermite in x and across y):
girder line j carries the share c_j P as a point load on its element e = [a, b] ∋ x.  Girder j's
internal forces at a section s in element e follow from that element's end forces, exactly for the
Euler–Bernoulli element (standard element force recovery):

    Q_a = (K_e u_e)[w_a, θ_a] − f_e[w_a, θ_a]       (force and couple of node a on the element)
    M(s) = Q_w (s − a) − Q_θ + Σ_{x_p ∈ [a, s)} c_j P (s − x_p),   V(s) = Q_w + Σ_{x_p ∈ [a, s]} c_j P,

with f_e the element's own consistent load.  The part K_e u_e is linear in the nodal displacements,
gᵀu, so its influence function is vᵀF(x, y) with v = K⁻¹g (one sparse solve per effect); the
f_e and direct terms are added for loads in element e.  A bearing reaction is (K u − F) at its
DOF (rigid) or −k_b w (spring).  Per unit modal coordinate: the girder's EI ∂²φ/∂x² for moments;
for shears EI ∂³φ/∂x³ on the element (its mid-element value) corrected by the inertia ω² m φ (s −
x_mid); for reactions (K φ − ω² M φ) at the bearing.  The moment and shear modal values neglect the
element's own inertia within the element: an O((k h)²) error, k the mode's wavenumber, h the
element length (4e-3 for the first bending mode of Bridge 2 with 34 elements).

At a station the girder moment jumps by the couple the transverse members apply to the node
(their torsion, and on a skew deck their bending, act on ∂w/∂x): a moment or shear at a station
is the one just right of it, M(s⁺) and V(s⁺), from the element that starts there.  A section
within ``STATION_TOLERANCE`` × span of a station is that station,
so a skew girder's station asked for at x = ξ_i + y_g tan θ is read there whatever the round-off
of x − y_g tan θ.

The grillage enters through the public attributes of ``DeckModel`` — among them its DOF
numbering ``DofMap`` (``dof_map``) — so this module does not import the
grillage's module.
"""
from __future__ import annotations

from typing import Optional, Protocol

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from vbikit._kept import Kept
from vbikit.bridge.base import GirderDeck
from vbikit.bridge.effects import EFFECT_KINDS, LoadEffect, TabulatedInfluence, kept_effect
from vbikit.bridge.elements import beam_element_stiffness
from vbikit.bridge.nodal import DofMap, NodalModes, girder_line_strain, hermite_basis, snap_to_stations


class DeckModel(GirderDeck, Protocol):
    """What the load effects read of a grillage deck ([`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge])."""

    span: float
    skew: float
    bearing_stiffness: Optional[float]

    @property
    def dof_map(self) -> DofMap: ...
    @property
    def nodal_modes(self) -> NodalModes: ...
    @property
    def omega(self) -> NDArray[np.float64]: ...
    @property
    def support_stations(self) -> tuple[int, ...]: ...
    @property
    def support_x(self) -> NDArray[np.float64]: ...
    @property
    def line_properties(self) -> dict[str, NDArray[np.float64]]: ...
    def assemble(self) -> tuple[sp.csr_matrix, sp.csr_matrix, NDArray[np.intp]]: ...
    def girder_element_EI(self, line: int, element: int) -> float: ...
    def girder_x(self, girder: int, xi: ArrayLike) -> NDArray[np.float64]: ...
    def span_coordinate(self, x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]: ...
    def span_index(self, x: float) -> int: ...


def load_weights(dofs: DofMap, x: ArrayLike, y: ArrayLike
                 ) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.intp], NDArray[np.float64]]:
    """Consistent load of unit upward forces at (x, y): DOF indices and coefficients (n, 12), the
    element index e of each point and its line shares c (n, n_lines).  Along the lines: Hermite in
    ξ = x − y tan θ on (w, ∂w/∂x), linear on ∂w/∂y; across them (along the transverse members):
    Hermite on w and on the slope along the members, ∂w/∂y + tan θ ∂w/∂x — the interpolation of
    ``NodalModes`` with the FE model's linear transverse slopes.  Points
    off the deck (ξ outside 0 … span) get zero coefficients.  ``dofs`` is the grillage's DOF map."""
    xs, ys = dofs.stations, dofs.line_y
    nx = dofs.n_elements
    tan = dofs.skew_tan
    x = np.asarray(x, float).ravel()
    y = np.broadcast_to(np.asarray(y, float), x.shape).ravel()
    if tan:
        x = x - y * tan  # ξ
    e = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, nx - 1)
    h = xs[e + 1] - xs[e]
    t = (x - xs[e]) / h
    nxh = hermite_basis(t, h, 0)
    nxh1 = hermite_basis(t, h, 1) if tan else None
    nxl = (1 - t, t)
    n = x.size
    if ys.size == 1:
        j0 = np.zeros(n, int)
        j1 = j0
        cw0, cs0 = np.ones(n), y - ys[0]
        cw1 = cs1 = np.zeros(n)
    else:
        j = np.clip(np.searchsorted(ys, y, side="right") - 1, 0, ys.size - 2)
        b = ys[j + 1] - ys[j]
        ny = hermite_basis((y - ys[j]) / b, b, 0)
        j0, j1 = j, j + 1
        cw0, cs0, cw1, cs1 = (np.array(v, float) * np.ones(n) for v in ny)
        lo, hi = y < ys[0], y > ys[-1]
        for mask, jj in ((lo, 0), (hi, ys.size - 1)):
            j0 = np.where(mask, jj, j0)
            j1 = np.where(mask, jj, j1)
            cw0 = np.where(mask, 1.0, cw0)
            cs0 = np.where(mask, y - ys[jj], cs0)
            cw1 = np.where(mask, 0.0, cw1)
            cs1 = np.where(mask, 0.0, cs1)
    idx = np.empty((n, 12), np.intp)
    coef = np.empty((n, 12))
    k = 0
    for jj, cw, cs in ((j0, cw0, cs0), (j1, cw1, cs1)):
        for a in (0, 1):
            node = dofs.dof(jj, e + a, 0)
            idx[:, k], coef[:, k] = node, cw * nxh[2 * a]
            idx[:, k + 1], coef[:, k + 1] = node + 1, cw * nxh[2 * a + 1]
            idx[:, k + 2], coef[:, k + 2] = node + 2, cs * nxl[a]
            if nxh1 is not None:  # the slope along an oblique member holds tan θ ∂w/∂x
                coef[:, k] += cs * tan * nxh1[2 * a]
                coef[:, k + 1] += cs * tan * nxh1[2 * a + 1]
            k += 3
    off = (x < 0.0) | (x > xs[-1])
    coef[off] = 0.0
    shares = np.zeros((n, ys.size))
    rows = np.arange(n)
    shares[rows, j0] = cw0  # one entry per row in each statement: as np.add.at, without its per-element loop
    shares[rows, j1] += cw1
    shares[off] = 0.0
    return idx, coef, e, shares


#: Sample points t = (ξ − a)/h of each element at which a wheel line's influence values are tabulated
#: (``DeckInfluence``), and the monomial coefficients of the cubic through them (rows: t⁰ … t³).
_NODES_T = np.array([0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0])
_TO_MONOMIAL = np.linalg.inv(np.vander(_NODES_T, 4, increasing=True))
#: Wheel lines y whose tables one influence function keeps (oldest dropped first).
LINE_TABLES_KEPT = 256


class DeckInfluence(TabulatedInfluence):
    """I(x, y) of one grillage load effect: vᵀF(x, y) with F the consistent load of unit forces at the
    points (``load_weights``, shared by every effect of the deck), plus, for a moment or shear, the
    terms of the points inside the section's element e = [a, a + h] on girder line j (module docstring).

    Along one wheel line (y fixed) vᵀF is, on each element, a cubic in t = (ξ − a)/h: the coefficients
    of ``load_weights`` are Hermite cubics, linear or (skew) Hermite-derivative terms in t times
    factors of y alone.  So the values at t = 0, 1/3, 2/3, 1 of every element (one ``load_weights``
    call of 4 × n_elements points per line, kept on this object per y) give vᵀF at any point of the
    line by the cubic through them — equal to the direct evaluation (``direct``) up to round-off.
    The terms of points in the section's own element are c_j(y) times −(s − a)·N₁ + N₂ + (s − ξ for
    ξ < s) for a moment, −N₁ + (1 for ξ ≤ s) for a shear (N the Hermite basis of the element):
    their cubic part is added to that element's row of the table, their kink (or step) at s to the
    values (``TabulatedInfluence``), with the line's share c_j(y) kept with the table."""

    def __init__(self, bridge: DeckModel, v: NDArray[np.float64], kind: str = "reaction", element: int = -1,
                 line: int = 0, a: float = 0.0, h: float = 1.0, s: float = 0.0) -> None:
        self.bridge, self.dofs, self.v = bridge, bridge.dof_map, v
        self.kind, self.element, self.line, self.a, self.h, self.s = kind, element, line, a, h, s
        self.kink, self.section = ("none" if kind == "reaction" else kind), s
        self._line_tables: Kept[float, tuple[NDArray[np.float64], float]] = Kept(LINE_TABLES_KEPT)

    @property
    def stations(self) -> NDArray[np.float64]:
        return self.dofs.stations

    @property
    def skew_tan(self) -> float:
        return float(self.dofs.skew_tan)

    def line_tables(self, lines) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        kept = [self.line_table(float(y)) for y in lines]
        poly = np.concatenate([k[0] for k in kept], axis=1) if len(kept) != 1 else kept[0][0]
        return poly, np.array([k[1] for k in kept])

    def _section_cubic(self, xi: NDArray[np.float64]) -> NDArray[np.float64]:
        """The cubic part of the section's own element's terms at ξ (per unit share c_j)."""
        a, h, s = self.a, self.h, self.s
        n = hermite_basis((xi - a) / h, h, 0)
        return -(s - a) * n[0] + n[1] if self.kind == "moment" else -n[0]

    def _kink(self, xi: NDArray[np.float64]) -> NDArray[np.float64]:
        """The kinked part of the section's own element's terms at ξ (per unit share c_j)."""
        s = self.s
        return np.where(xi < s, s - xi, 0.0) if self.kind == "moment" else np.where(xi <= s, 1.0, 0.0)

    @property
    def shared_key(self) -> int:
        return id(self.dofs)

    def line_table(self, y: float) -> tuple[NDArray[np.float64], float]:
        """Monomial coefficients (4, n_elements) in t (rows t⁰ … t³) of I along the wheel line y [m]
        without the kink (or step) at the section, and the share c_j(y) of the section's girder line j
        (cached)."""
        return self._line_tables.get(y, lambda: self._line_table(y))

    def _line_table(self, y: float) -> tuple[NDArray[np.float64], float]:
        """``line_table``'s entry of the wheel line y [m], computed."""
        xs = self.dofs.stations
        xi = (xs[:-1, None] + _NODES_T[None, :] * np.diff(xs)[:, None]).ravel()
        x = xi + y * self.dofs.skew_tan if self.dofs.skew_tan else xi
        idx, coef, _, shares = load_weights(self.dofs, x, y)
        values = (self.v[idx] * coef).sum(axis=1).reshape(-1, 4)
        c = float(shares[0, self.line])
        if self.kind != "reaction":
            values[self.element] += c * self._section_cubic(xi.reshape(-1, 4)[self.element])
        return np.ascontiguousarray((values @ _TO_MONOMIAL.T).T), c

    def shared(self, x: NDArray[np.float64], y: NDArray[np.float64]):
        """The distinct wheel lines y, each point's row (line, element) in their stacked tables, its
        ξ and t on the element and whether it is off the deck."""
        dofs = self.dofs
        xs = dofs.stations
        x = np.asarray(x, float).ravel()
        y = np.broadcast_to(np.asarray(y, float), x.shape).ravel()
        xi = x - y * dofs.skew_tan if dofs.skew_tan else x
        e = np.clip(np.searchsorted(xs, xi, side="right") - 1, 0, dofs.n_elements - 1)
        t = (xi - xs[e]) / (xs[e + 1] - xs[e])
        lines, which = np.unique(y, return_inverse=True)
        off = (xi < 0.0) | (xi > xs[-1])
        return lines, which.ravel() * dofs.n_elements + e, xi, e, t, off

    def apply(self, part, x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        lines, row, xi, e, t, off = part
        if not lines.size:
            return np.zeros(0)
        poly, shares = self.line_tables(lines)
        out = ((poly[3][row] * t + poly[2][row]) * t + poly[1][row]) * t + poly[0][row]  # Horner
        out[off] = 0.0
        if self.kind != "reaction":
            inside = (e == self.element) & ~off
            if np.any(inside):
                out[inside] += shares[row[inside] // self.dofs.n_elements] * self._kink(xi[inside])
        return out

    def direct(self, x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        """I(x, y) from ``load_weights`` of the points themselves (no tables)."""
        x = np.asarray(x, float).ravel()
        y = np.broadcast_to(np.asarray(y, float), x.shape).ravel()
        idx, coef, el, shares = load_weights(self.dofs, x, y)
        out = (self.v[idx] * coef).sum(axis=1)
        if self.kind == "reaction":
            return out
        inside = el == self.element
        if np.any(inside):
            xi = self.bridge.span_coordinate(x[inside], y[inside])
            out[inside] += shares[inside, self.line] * (self._section_cubic(xi) + self._kink(xi))
        return out


def _factor(bridge: DeckModel):
    """K, M, free DOFs and the LU factors of the free stiffness, kept on the bridge object."""
    cache = bridge.__dict__.setdefault("_load_effect_cache", {})
    if "factor" not in cache:
        K, M, free = bridge.assemble()
        cache["factor"] = (K.tocsr(), M.tocsr(), free, spla.splu(K[free][:, free].tocsc()))
    return cache["factor"]


def _field(bridge: DeckModel, g: NDArray[np.float64], fixed_dof: Optional[int] = None) -> NDArray[np.float64]:
    """v with gᵀu = vᵀF for every load F (u = K⁻¹F on the free DOFs); a reaction at a fixed DOF d
    adds K_{d,f} u − F_d (``g`` then unused)."""
    K, _, free, lu = _factor(bridge)
    v = np.zeros(K.shape[0])
    if fixed_dof is None:
        v[free] = lu.solve(g[free])
    else:
        v[free] = lu.solve(np.asarray(K[free][:, [fixed_dof]].todense()).ravel())
        v[fixed_dof] = -1.0
    return v


def deck_strain_influence(bridge: DeckModel, x: float, y: float) -> DeckInfluence:
    """The influence function of the girder bottom-fibre strain at the point (x, y) [m] — ε = c_g ∂²w/∂x²
    on the girder lines, linear between them (``girder_line_strain``, as ``strain_shapes`` reads the
    modes) — under a unit upward force at any (x_p, y_p), from the full stiffness: ε = gᵀu with u = K⁻¹F
    and g the strain's row over the DOFs, so I = vᵀF(x_p, y_p) with v = K⁻¹g (one sparse solve with the
    deck's kept factor, as a reaction's field; Maxwell–Betti).  The exact static strain of the grid,
    which the modes' static strain reaches only with every mode (Σ φᵢφᵢᵀ/ωᵢ² = K⁻¹ over the free DOFs,
    mass-normalised modes); a point off the deck has g = 0."""
    dofs = bridge.dof_map
    xi = float(snap_to_stations(np.array([x - y * dofs.skew_tan]), dofs.stations)[0])
    e = int(np.clip(np.searchsorted(dofs.stations, xi, side="right") - 1, 0, dofs.n_elements - 1))
    stations = range(max(e - 1, 0), min(e + 3, dofs.n_stations))  # the element's nodes and their neighbours
    cols = np.array([dofs.dof(j, i, k) for j in range(dofs.n_lines) for i in stations for k in range(3)])
    unit = np.zeros((dofs.n_dof, cols.size))
    unit[cols, np.arange(cols.size)] = 1.0  # strain is local: no other DOF enters it
    g = np.zeros(dofs.n_dof)
    g[cols] = girder_line_strain(dofs.nodal(unit), bridge.line_properties["c"], x, y)[0]
    return DeckInfluence(bridge, _field(bridge, g))


def deck_load_effect(bridge: DeckModel, kind: str, x: Optional[float] = None,
                     girder: Optional[int] = None, support: Optional[int] = None) -> LoadEffect:
    """Moment or shear of ``girder`` at section x [m], or the reaction of its bearing at support
    ``support`` (0 = entry, then the interior supports, the last = exit); kept on the bridge per
    request (``vbikit.bridge.effects.kept_effect``: with its influence field and wheel-line tables)."""
    key = (kind, x, support, girder)  # as given: a bad value is refused by the making, never kept
    return kept_effect(bridge, key, lambda: _deck_load_effect(bridge, kind, x, girder, support))


def _deck_load_effect(bridge: DeckModel, kind: str, x: Optional[float] = None,
                      girder: Optional[int] = None, support: Optional[int] = None) -> LoadEffect:
    """``deck_load_effect`` made anew."""
    if kind not in EFFECT_KINDS:
        raise ValueError(f"load effect must be one of {', '.join(EFFECT_KINDS)}, got {kind!r}")
    if girder is None:
        girder = int(bridge.default_girder or 1)
    j = bridge.girder_index(girder)
    dofs = bridge.dof_map
    nx, xs = dofs.n_elements, dofs.stations
    K, M, free, _ = _factor(bridge)
    omega = bridge.omega
    modes = bridge.nodal_modes
    full = dofs.vector(modes)
    supports = bridge.support_stations
    sx = bridge.support_x
    spans = np.diff(sx)
    if kind == "reaction":
        if support is None or not 0 <= int(support) < len(supports):
            raise ValueError(f"reaction: support must be 0 … {len(supports) - 1}, got {support!r}")
        support = int(support)
        d = dofs.dof(j, supports[support], 0)
        if bridge.bearing_stiffness is None:
            v = _field(bridge, np.zeros(K.shape[0]), fixed_dof=d)
            modal = (K @ full)[d] - omega**2 * (M @ full)[d]
        else:
            g = np.zeros(K.shape[0])
            g[d] = -bridge.bearing_stiffness
            v = _field(bridge, g)
            modal = -bridge.bearing_stiffness * full[d]

        length = spans[0] if support == 0 else spans[-1] if support == spans.size else 0.5 * (spans[support - 1] + spans[support])
        return LoadEffect("reaction", float(bridge.girder_x(girder, sx[support])), modal, DeckInfluence(bridge, v),
                          float(length),
                          girder=girder, support=support)
    y_line = float(bridge.girder_y[j])
    xi_s = None if x is None else float(bridge.span_coordinate(x, y_line))
    if xi_s is not None:  # a section within round-off of a station is that station (read just right of it)
        xi_s = float(snap_to_stations(xi_s, xs))
    if xi_s is None or not 0.0 <= xi_s <= bridge.span:
        where = "" if not bridge.skew else f" (girder {girder}'s bearings are at x = {bridge.girder_x(girder, 0.0):.6g} and {bridge.girder_x(girder, bridge.span):.6g} m)"
        raise ValueError(f"{kind}: section x must be within the span 0 … {bridge.span:g} m{where}, got {x!r}")
    s = xi_s  # the section's ξ (= x without skew)
    e = int(np.clip(np.searchsorted(xs, s, side="right") - 1, 0, nx - 1))
    a, b = xs[e], xs[e + 1]
    h = b - a
    EI = bridge.girder_element_EI(j, e)
    ke = beam_element_stiffness(EI, h)
    element_dofs = [dofs.dof(j, e, 0), dofs.dof(j, e, 1), dofs.dof(j, e + 1, 0), dofs.dof(j, e + 1, 1)]
    g = np.zeros(K.shape[0])
    row = (s - a) * ke[0] - ke[1] if kind == "moment" else ke[0]
    g[element_dofs] = row
    v = _field(bridge, g)
    if kind == "moment":
        modal = EI * modes.line_values(np.array([s]), 2)[j, 0]
    else:
        k2 = modes.line_values(np.array([a, b]), 2)[j]  # curvatures at the element ends
        m_line = float(bridge.line_properties["m"][j])
        phi = modes.line_values(np.array([s]), 0)[j, 0]
        modal = EI * (k2[1] - k2[0]) / h + omega**2 * m_line * phi * (s - 0.5 * (a + b))
    influence = DeckInfluence(bridge, v, kind, e, j, a, h, s)

    k = int(np.argmin(np.abs(sx - s)))
    interior = abs(sx[k] - s) <= 1e-9 * bridge.span and 0 < k < spans.size
    if kind == "moment" and interior:
        length = 0.5 * (spans[k - 1] + spans[k])
    else:
        length = spans[bridge.span_index(s)]
    return LoadEffect(kind, float(x), modal, influence, float(length), girder=girder,
                      hogging_region=bool(kind == "moment" and interior))
