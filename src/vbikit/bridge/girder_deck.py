"""Simply supported slab-on-girder deck: a grillage FE model reduced to its modes.

Model (argued in ``docs/bridges.md``)
-------------------------------------
Longitudinal members along every girder line y_g, cut into ``n_elements`` equal elements,
transverse members (deck slab strips, plus diaphragms where there are diaphragms) joining
neighbouring girder lines at every station.  Every node has three DOFs:

* w = vertical displacement [m] (z up),
* ∂w/∂x = longitudinal slope (rotation about y) [-],
* ∂w/∂y = transverse slope (rotation about x, the girder's twist) [-].

Longitudinal member j (Euler–Bernoulli + St Venant torsion, cubic Hermite bending on (w, ∂w/∂x),
linear torsion on ∂w/∂y):

* EI_j: composite transformed section of the girder and its tributary deck width b_j (deck
  mid-plane t/2 above the girder top, no haunch, full composite action; n = E_deck / E_girder)
  — [`vbikit.bridge.sections.composite_beam_properties`][vbikit.bridge.composite_beam_properties] — plus a parapet's EI on the
  outer girders.  Interior b_j = s (girder spacing), outer b_j = s/2 + overhang.
* GJ_j = G_girder J_girder + G_deck t³/6 · b_j (the slab's torsion split equally between the
  two grillage directions, Hambly, *Bridge Deck Behaviour*, 2nd ed., 1991, §5).
* Mass: girder ρA (rotary inertia ρ I_girder about the line) plus, on the outer girders, the
  deck overhang (and parapet) moving rigidly with the girder's section — the same kinematics
  as the mode-shape extrapolation over the overhang: per length m = Σ μ, first moment
  S = Σ μ d, second moment J = Σ μ d² (d = lateral distance from the girder line); consistent
  (Hermite × Hermite for m, Hermite × linear for S, linear × linear for J).

Transverse member at station i (cubic Hermite bending on (w, ∂w/∂y), linear torsion on ∂w/∂x):
slab strip of width l_i (the station's tributary length) with EI = E_deck t³ l_i / (12 (1 − ν²)),
GJ = G_deck t³ l_i / 6 and the slab's mass (ρ t + wearing surface) l_i per length as a consistent
Hermite mass in y — the same cubic that interpolates the mode shapes between girder lines;
diaphragms (rectangle b_d × h_d of deck concrete) add E b_d h_d³ / 12, G β h_d b_d³ and their
mass ρ b_d h_d.  (Along x the deck mass is thus lumped at the stations: O(h²) convergence.)

Supports: every girder bearing restrains w at x = 0 and x = span (rigid, or a vertical spring
of ``bearing_stiffness`` [N/m] per bearing).

Skew supports (``skew`` = θ [°], |θ| ≤ 45°; the oblique ("skew") grillage mesh of Hambly, *Bridge
Deck Behaviour*, 2nd ed., 1991, ch. 5, and the ``Oblique`` mesh of ospgrillage, Ngan & Caprani 2022).  The support lines pass through (x_k, 0) on the deck centreline (x_k = 0,
the interior supports, span) at θ to the y axis: a point (x, y) lies on support line k when
ξ = x − y tan θ = x_k; θ > 0 puts the left (y > 0) end of a support line further along +x.  ξ is
the distance along a girder from its entry bearing: the stations are stations of ξ, girder line j's
node i lies at x = ξ_i + y_j tan θ, and diaphragm and damage positions are ξ.  The transverse
members run along the skew, between the nodes of one station: length s / cos θ, slab strip width
l_i cos θ (so each strip still carries the deck area l_i s), bending on the slope along the member
and torsion on the slope across it, transformed to the nodes' (∂w/∂x, ∂w/∂y).  The overhang strips
move with the girder's section normal to x, as without skew (a second-order difference from the
oblique section the mode shapes are extrapolated along).  θ = 0 is exactly the rectangular deck.
Grillage practice keeps the oblique mesh to moderate skew: ospgrillage's meshing rules (its
documentation, "Meshing types and rules", "based on common industrial practice of grillage
analysis") allow it up to 30° and an orthogonal mesh above 11°; ``vbikit run`` warns above 30°.  A single-girder model is also restrained in twist
at its supports (a fork support), otherwise it could roll freely.

The generalised eigenproblem K φ = ω² M φ is assembled with scipy.sparse and solved by
``scipy.sparse.linalg.eigsh`` in shift-invert mode (σ = 0) for the lowest modes; the modes are
mass-normalised (φᵀ M φ = 1) and evaluated anywhere by ``vbikit.bridge.nodal.NodalModes``.

Girder numbering: Girder 1 is the girder at the most negative y (the right-hand girder for a
driver travelling in +x, since y is positive to the left); Girder n is at the most positive y.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields
from functools import cached_property
from typing import Optional

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge import mode_cache
from vbikit.bridge.base import DEFAULT_DAMPING_RATIO, ModalBridge
from vbikit.bridge.damage import Damage, active_damage, stiffness_factor
from vbikit.bridge.deck_effects import DeckInfluence, deck_load_effect, deck_strain_influence, load_weights
from vbikit.bridge.effects import LoadEffect
from vbikit.bridge.eigen import lowest_modes
from vbikit.bridge.elements import (
    bar_element_mass,
    bar_element_stiffness,
    beam_element_mass,
    beam_element_stiffness,
    hermite_linear_coupling,
    oblique_member_rotation,
)
from vbikit.bridge.nodal import DofMap, NodalModes, girder_line_strain
from vbikit.bridge.sections import (
    AASHTO_GIRDERS,
    GirderSection,
    composite_beam_properties,
)

#: largest skew angle [°] of the support lines the oblique-mesh grillage takes
MAX_SKEW = 45.0
#: above this skew [°] grillage practice uses an orthogonal mesh (ospgrillage's meshing rules allow
#: the oblique mesh up to 30°): a warning
OBLIQUE_MESH_ADVISED_SKEW = 30.0

#: bumped whenever the model changes in a way that changes its modes (invalidates caches)
MODEL_VERSION = "girder_deck-2"


def approximate_torsion_constant(section: GirderSection) -> float:
    """St Venant torsion constant estimate J ≈ A⁴ / (4π² I_p) [m⁴] of a compact solid section
    (Saint-Venant's approximation; Roark's *Formulas for Stress and Strain*, 7th ed., Table 10.7
    note), with the polar moment I_p replaced by the strong-axis I (so J is overestimated by
    at most I_p/I − 1, ≈ 10 % for AASHTO girders).  [substitute] for the unpublished J."""
    return section.area**4 / (4.0 * np.pi**2 * section.inertia)


@dataclass(frozen=True)
class SlabOnGirderBridge(ModalBridge):
    """Simply supported slab-on-girder bridge (grillage FE model, see the module docstring).

    Parameters (SI units)
    ---------------------
    span : float
        Span between bearings [m].
    n_girders : int
        Number of girders (≥ 1).
    girder_spacing : float
        Centre-to-centre girder spacing s [m].
    overhang : float
        Deck overhang beyond the outer girders' centre lines [m]; deck width = (n − 1) s + 2 overhang.
    girder : GirderSection or str
        Girder section, or an AASHTO type "I" … "VI" (`vbikit.bridge.sections.AASHTO_GIRDERS`).
    deck_thickness : float
        Slab thickness t [m].
    E_girder, E_deck : float
        Young's moduli [Pa].
    poisson : float
        Poisson's ratio ν of the concrete [-] (G = E / (2 (1 + ν))).
    density : float
        Concrete density ρ [kg/m³] (girders, deck and diaphragms).
    girder_torsion_constant : float, optional
        St Venant J of one girder [m⁴]; default `approximate_torsion_constant`.
    diaphragms : tuple of float
        x positions [m] of the diaphragms (snapped to the nearest station); default the two ends.
    diaphragm_width : float
        Diaphragm thickness b_d along x [m].
    diaphragm_depth : float, optional
        Diaphragm depth h_d [m]; default 0.75 × girder depth.
    bearing_stiffness : float, optional
        Vertical stiffness per bearing [N/m]; None = rigid bearings.
    parapet_EI, parapet_mass : float
        Bending stiffness [N·m²] and mass per length [kg/m] of each edge parapet/railing, carried
        by the outer girder lines (mass at the deck edge).
    extra_mass_per_area : float
        Wearing surface and other superimposed mass [kg/m²] over the whole deck.
    damping_ratio : float
        Modal damping ratio ζ, all modes [-].
    n_modes : int
        Number of modes kept (if ``max_frequency`` is None).
    max_frequency : float, optional
        Keep every mode up to this frequency [Hz] instead of a fixed number.
    n_elements : int, optional
        Elements along the span; default the even number giving elements ≤ 0.5 m, at least 20.
    default_lateral_offset : float
        Vehicle centreline y [m] a scenario uses when it does not set ``crossing.lateral_offset``.
    spans : tuple of float, optional
        Several spans [m] (adding up to ``span``) with the girders continuous over the interior
        supports: bearings under every girder at every support, diaphragms there by default.
    skew : float
        Skew angle θ of every support line [degrees], −45 … 45, positive when the left (y > 0) end
        of a support line lies further along +x (the oblique mesh of the bridges guide, "Skew
        supports"); 0 = square.
    damage : tuple of Damage
        Local stiffness losses of single girders (``vbikit.bridge.damage.Damage`` with ``girder``):
        the girder elements' EI × (1 − severity × the fraction of the element inside the region).
    default_girder : int
        Girder (1-based) a scenario reports when it sets neither ``response.girder`` nor ``response.y``.
    name : str
        Label only.
    use_cache, cache_dir
        On-disk mode cache (keyed by a hash of every parameter that changes the modes); never
        needed for correctness.  ``cache_dir`` None = ``vbikit.bridge.mode_cache.default_cache_dir``.
    """

    span: float
    n_girders: int = 5
    girder_spacing: float = 2.13
    overhang: float = 0.615
    girder: GirderSection | str = "II"
    deck_thickness: float = 0.20
    E_girder: float = 36e9
    E_deck: float = 33e9
    poisson: float = 0.2
    density: float = 2400.0
    girder_torsion_constant: Optional[float] = None
    diaphragms: tuple[float, ...] | None = None
    diaphragm_width: float = 0.25
    diaphragm_depth: Optional[float] = None
    bearing_stiffness: Optional[float] = None
    parapet_EI: float = 0.0
    parapet_mass: float = 0.0
    extra_mass_per_area: float = 0.0
    damping_ratio: float = DEFAULT_DAMPING_RATIO
    n_modes: int = 10
    max_frequency: Optional[float] = None
    n_elements: Optional[int] = None
    default_lateral_offset: float = 0.0
    default_girder: int = 1
    damage: tuple[Damage, ...] = ()
    spans: Optional[tuple[float, ...]] = None
    skew: float = 0.0
    name: str = ""
    use_cache: bool = field(default=True, compare=False)
    cache_dir: Optional[str] = field(default=None, compare=False)

    def __post_init__(self) -> None:
        if isinstance(self.girder, str):
            if self.girder not in AASHTO_GIRDERS:
                raise ValueError(f"unknown girder type {self.girder!r}; allowed: {', '.join(AASHTO_GIRDERS)}")
            object.__setattr__(self, "girder", AASHTO_GIRDERS[self.girder])
        for k in ("span", "girder_spacing", "deck_thickness", "E_girder", "E_deck", "density", "diaphragm_width"):
            v = getattr(self, k)
            if not (np.isfinite(v) and v > 0):
                raise ValueError(f"{k} must be a positive finite number, got {v!r}")
        for k in ("overhang", "parapet_EI", "parapet_mass", "extra_mass_per_area"):
            v = getattr(self, k)
            if not (np.isfinite(v) and v >= 0):
                raise ValueError(f"{k} must be >= 0, got {v!r}")
        object.__setattr__(self, "damage", tuple(self.damage))
        for i, d in enumerate(self.damage):
            if d.girder is None or not 1 <= d.girder <= self.n_girders:
                raise ValueError(f"bridge.damage.{i}: girder must be 1 … {self.n_girders}, got {d.girder!r}")
            if d.end > self.span + 1e-9:
                raise ValueError(f"bridge.damage.{i}: the region {d.position:g} … {d.end:g} m ends beyond the span ({self.span:g} m)")
        if isinstance(self.skew, bool) or not (np.isfinite(self.skew) and abs(self.skew) <= MAX_SKEW):
            raise ValueError(f"skew must be an angle in degrees within -{MAX_SKEW:g} … {MAX_SKEW:g}, got {self.skew!r}")
        object.__setattr__(self, "skew", float(self.skew) + 0.0)  # + 0.0: a skew of −0.0 is 0.0 (no "−0°" in outputs)
        if int(self.n_girders) != self.n_girders or self.n_girders < 1:
            raise ValueError(f"n_girders must be an integer >= 1, got {self.n_girders!r}")
        if not -1.0 < self.poisson < 0.5:
            raise ValueError(f"poisson must be in (-1, 0.5), got {self.poisson!r}")
        if not 0.0 <= self.damping_ratio < 1.0:
            raise ValueError(f"damping_ratio must be in [0, 1), got {self.damping_ratio!r}")
        if int(self.n_modes) != self.n_modes or self.n_modes < 1:
            raise ValueError(f"n_modes must be an integer >= 1, got {self.n_modes!r}")
        if self.max_frequency is not None and not self.max_frequency > 0:
            raise ValueError(f"max_frequency must be > 0 Hz, got {self.max_frequency!r}")
        if self.n_elements is not None and (int(self.n_elements) != self.n_elements or self.n_elements < 2):
            raise ValueError(f"n_elements must be an integer >= 2, got {self.n_elements!r}")
        if self.bearing_stiffness is not None and not self.bearing_stiffness > 0:
            raise ValueError(f"bearing_stiffness must be > 0 N/m (or None for rigid), got {self.bearing_stiffness!r}")
        if not 1 <= self.default_girder <= self.n_girders:
            raise ValueError(f"default_girder must be 1 … {self.n_girders}, got {self.default_girder!r}")
        if self.spans is not None:
            spans = tuple(float(v) for v in self.spans)
            if not spans or any(not (np.isfinite(v) and v > 0) for v in spans):
                raise ValueError(f"spans must be positive span lengths [m], got {self.spans!r}")
            if abs(sum(spans) - self.span) > 1e-9 * self.span:
                raise ValueError(f"spans {spans} add up to {sum(spans):g} m, not to span = {self.span:g} m")
            object.__setattr__(self, "spans", spans)
        supports = tuple(float(v) for v in self.support_x)
        d = supports if self.diaphragms is None else tuple(float(v) for v in self.diaphragms)
        if any(not 0.0 <= v <= self.span for v in d):
            raise ValueError(f"diaphragms must stand in 0 … {self.span:g} m (the span), got {list(d)}")
        object.__setattr__(self, "diaphragms", d)

    # ------------------------------------------------------------------ geometry
    @property
    def section(self) -> GirderSection:
        assert isinstance(self.girder, GirderSection)
        return self.girder

    @property
    def girder_y(self) -> NDArray[np.float64]:
        """y [m] of the girder centre lines, Girder 1 first (most negative y)."""
        return (np.arange(self.n_girders) - (self.n_girders - 1) / 2.0) * self.girder_spacing

    @property
    def default_response_y(self) -> float:
        """y [m] of the default girder's line (responses are read there unless y is given)."""
        return float(self.girder_y[self.default_girder - 1])

    @property
    def deck_width(self) -> float:
        """Total deck width (n − 1) s + 2 · overhang [m]."""
        return (self.n_girders - 1) * self.girder_spacing + 2.0 * self.overhang

    @property
    def element_count(self) -> int:
        return int(sum(self._span_elements()))

    def _span_elements(self) -> list[int]:
        """Elements per span: ``n_elements`` (shared in proportion to the span lengths on several
        spans), else 2 per metre rounded up to an even number, at least 20 per span."""
        spans = (self.span,) if self.spans is None else self.spans
        if self.n_elements is not None:
            if len(spans) == 1:
                return [int(self.n_elements)]
            return [max(2, int(round(self.n_elements * L / self.span))) for L in spans]
        return [max(20, 2 * int(np.ceil(L / (2 * 0.5)))) for L in spans]

    @property
    def stations(self) -> NDArray[np.float64]:
        if self.spans is None:
            return np.linspace(0.0, self.span, self.element_count + 1)
        edges = np.concatenate([[0.0], np.cumsum(self.spans)])
        parts = [np.linspace(a, b, n + 1)[:-1] for a, b, n in zip(edges[:-1], edges[1:], self._span_elements())]
        return np.concatenate(parts + [[self.span]])

    @property
    def support_stations(self) -> tuple[int, ...]:
        """Station indices of the supports (entry, interior supports, exit)."""
        return tuple(int(v) for v in np.concatenate([[0], np.cumsum(self._span_elements())]))

    @property
    def support_x(self) -> NDArray[np.float64]:
        """Support positions [m] (entry, interior supports, exit) along the girders (ξ; x on a square deck)."""
        if self.spans is None:
            return np.array([0.0, self.span])
        xs = np.concatenate([[0.0], np.cumsum(self.spans)])
        xs[-1] = self.span  # the sum of the spans may differ from span by round-off
        return xs

    @property
    def default_section(self) -> float:  # type: ignore[override]
        """ξ [m] of the first span's midpoint (midspan of a single span), the same on every girder line."""
        return 0.5 * float(self.support_x[1])

    @property
    def skew_tan(self) -> float:
        """tan θ of the support lines' skew [-]."""
        return float(np.tan(np.radians(self.skew))) if self.skew else 0.0

    @property
    def lateral_edges(self) -> tuple[float, float]:
        """y [m] of the deck edges, ±width/2 (the deck's x extent reaches (width/2)·|tan θ| beyond 0 and span)."""
        return -0.5 * self.deck_width, 0.5 * self.deck_width

    def girder_x(self, girder: int, xi: ArrayLike) -> NDArray[np.float64]:
        """x [m] of the points at ξ [m] along girder ``girder`` (1-based): ξ + y_g tan θ."""
        return np.asarray(xi, float) + float(self.girder_y[self.girder_index(girder)]) * self.skew_tan

    @property
    def span_lengths(self) -> tuple[float, ...]:
        """Length [m] of every span (``spans``, or the single span)."""
        return (float(self.span),) if self.spans is None else self.spans

    def _tributary(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Lower and upper y of each girder line's tributary deck strip."""
        y = self.girder_y
        edges = np.concatenate(([y[0] - self.overhang], 0.5 * (y[1:] + y[:-1]), [y[-1] + self.overhang]))
        return edges[:-1], edges[1:]

    @cached_property
    def line_properties(self) -> dict[str, NDArray[np.float64]]:
        """Per girder line: EI [N·m²], GJ [N·m²], m [kg/m], S [kg], J [kg·m], lever arm c [m], tributary width b [m].

        EI, GJ and c use the whole tributary deck width b; m, S, J hold the girder and the rigid
        overhang strip only (the deck between girder lines is carried by the transverse members)."""
        g, t = self.section, self.deck_thickness
        lo, hi = self._tributary()
        y = self.girder_y
        G_g = self.E_girder / (2 * (1 + self.poisson))
        G_d = self.E_deck / (2 * (1 + self.poisson))
        J_g = self.girder_torsion_constant if self.girder_torsion_constant is not None else approximate_torsion_constant(g)
        mu = self.density * t + self.extra_mass_per_area  # deck mass per area
        n = self.n_girders
        out = {k: np.zeros(n) for k in ("EI", "GJ", "m", "S", "J", "c", "b")}
        for j in range(n):
            b = hi[j] - lo[j]
            comp = composite_beam_properties(g, 1, b, t, self.E_girder, self.E_deck, self.density)
            a0 = lo[j] - y[j] if j == 0 else 0.0  # rigid overhang strips only
            a1 = hi[j] - y[j] if j == n - 1 else 0.0
            out["b"][j] = b
            out["c"][j] = comp.neutral_axis_depth
            out["EI"][j] = comp.EI
            out["GJ"][j] = G_g * J_g + G_d * t**3 / 6.0 * b
            out["m"][j] = self.density * g.area + mu * (a1 - a0)
            out["S"][j] = mu * (a1**2 - a0**2) / 2.0
            out["J"][j] = mu * (a1**3 - a0**3) / 3.0 + self.density * g.inertia
        for j, d in ((0, -self.overhang), (n - 1, self.overhang)):
            if self.parapet_EI or self.parapet_mass:
                out["EI"][j] += self.parapet_EI
                out["m"][j] += self.parapet_mass
                out["S"][j] += self.parapet_mass * d
                out["J"][j] += self.parapet_mass * d * d
        return out

    @property
    def strain_lever_arm(self) -> NDArray[np.float64]:
        """Height c [m] of each girder line's composite neutral axis above its bottom fibre (``line_properties["c"]``)."""
        return self.line_properties["c"]

    # ------------------------------------------------------------------ FE model
    def girder_element_EI(self, line: int, element: int) -> float:
        """EI [N·m²] of girder line ``line`` (0-based) in element ``element``, damage included."""
        EI = float(self.line_properties["EI"][line])
        damage = active_damage(self.damage)
        if not damage:
            return EI
        xs = self.stations
        return EI * stiffness_factor(damage, float(xs[element]), float(xs[element + 1]), girder=line + 1)

    @cached_property
    def dof_map(self) -> DofMap:
        """The grid's DOF numbering (``DofMap``): node (line j, station i) →
        3 (j (n_el + 1) + i) + (0: w, 1: ∂w/∂x, 2: ∂w/∂y), with the stations ξ, the girder lines' y and tan θ."""
        return DofMap(self.stations, self.girder_y, self.skew_tan)

    def assemble(self) -> tuple[sp.csr_matrix, sp.csr_matrix, NDArray[np.intp]]:
        """Global stiffness K [N/m …], mass M [kg …] (all DOFs) and the indices of the free DOFs.

        DOF order: node (line j, station i) → 3 (j (n_el + 1) + i) + (0: w, 1: ∂w/∂x, 2: ∂w/∂y).
        """
        nx = self.element_count
        xs = self.stations
        n_lines = self.n_girders
        dof = self.dof_map.dof
        ndof = self.dof_map.n_dof
        rows: list[NDArray[np.intp]] = []
        cols: list[NDArray[np.intp]] = []
        kv: list[NDArray[np.float64]] = []
        mv: list[NDArray[np.float64]] = []

        def add(dofs: list[int], ke: NDArray[np.float64] | None, me: NDArray[np.float64] | None) -> None:
            d = np.asarray(dofs)
            r, c = np.meshgrid(d, d, indexing="ij")
            rows.append(r.ravel())
            cols.append(c.ravel())
            kv.append(np.zeros(d.size**2) if ke is None else ke.ravel())
            mv.append(np.zeros(d.size**2) if me is None else me.ravel())

        p = self.line_properties
        for j in range(n_lines):
            for i in range(nx):
                h = xs[i + 1] - xs[i]
                d = [dof(j, i, 0), dof(j, i, 1), dof(j, i + 1, 0), dof(j, i + 1, 1),
                     dof(j, i, 2), dof(j, i + 1, 2)]
                ke = np.zeros((6, 6))
                me = np.zeros((6, 6))
                ke[:4, :4] = beam_element_stiffness(self.girder_element_EI(j, i), h)
                ke[4:, 4:] = bar_element_stiffness(p["GJ"][j] / h)
                me[:4, :4] = beam_element_mass(p["m"][j], h)
                me[4:, 4:] = bar_element_mass(p["J"][j], h)
                cpl = p["S"][j] * hermite_linear_coupling(h)
                me[:4, 4:] = cpl
                me[4:, :4] = cpl.T
                add(d, ke, me)
        # transverse members at every station
        G_d = self.E_deck / (2 * (1 + self.poisson))
        t = self.deck_thickness
        trib = np.empty(nx + 1)
        trib[1:-1] = 0.5 * (xs[2:] - xs[:-2])
        trib[0], trib[-1] = 0.5 * (xs[1] - xs[0]), 0.5 * (xs[-1] - xs[-2])
        diaph = np.zeros(nx + 1, dtype=int)
        for xd in self.diaphragms:  # type: ignore[union-attr]
            diaph[int(np.argmin(np.abs(xs - xd)))] += 1
        hd = self.diaphragm_depth if self.diaphragm_depth is not None else 0.75 * self.section.depth
        bd = self.diaphragm_width
        ratio = min(bd, hd) / max(bd, hd)
        EI_d = self.E_deck * bd * hd**3 / 12.0
        GJ_d = G_d * (1.0 - 0.63 * ratio) / 3.0 * max(bd, hd) * min(bd, hd) ** 3  # Roark Table 10.7 case 4 (approx.)
        m_d = self.density * bd * hd
        mu = self.density * t + self.extra_mass_per_area
        y = self.girder_y
        cos = float(np.cos(np.radians(self.skew)))
        rotation = oblique_member_rotation(self.skew)
        for i in range(nx + 1):
            width = trib[i] * cos if self.skew else trib[i]  # slab strip width normal to the member
            EI = self.E_deck * t**3 * width / (12.0 * (1.0 - self.poisson**2)) + diaph[i] * EI_d
            GJ = G_d * t**3 / 6.0 * width + diaph[i] * GJ_d
            for j in range(n_lines - 1):
                b = (y[j + 1] - y[j]) / cos if self.skew else y[j + 1] - y[j]  # member length
                ke = np.zeros((6, 6))
                me = np.zeros((6, 6))
                ke[:4, :4] = beam_element_stiffness(EI, b)
                ke[4:, 4:] = bar_element_stiffness(GJ / b)
                me[:4, :4] = beam_element_mass(mu * width + diaph[i] * m_d, b)
                if rotation is None:  # local (w_a, ∂w/∂y_a, w_b, ∂w/∂y_b, ∂w/∂x_a, ∂w/∂x_b)
                    d = [dof(j, i, 0), dof(j, i, 2), dof(j + 1, i, 0), dof(j + 1, i, 2),
                         dof(j, i, 1), dof(j + 1, i, 1)]
                else:  # to the nodes' (w, ∂w/∂x, ∂w/∂y) at both ends
                    d = [dof(j, i, k) for k in range(3)] + [dof(j + 1, i, k) for k in range(3)]
                    ke = rotation.T @ ke @ rotation
                    me = rotation.T @ me @ rotation
                add(d, ke, me)
        fixed: list[int] = []
        for j in range(n_lines):
            for i in self.support_stations:
                if self.bearing_stiffness is None:
                    fixed.append(dof(j, i, 0))
                else:
                    add([dof(j, i, 0)], np.array([[self.bearing_stiffness]]), None)
                if n_lines == 1:
                    fixed.append(dof(j, i, 2))
        r, c = np.concatenate(rows), np.concatenate(cols)
        K = sp.coo_matrix((np.concatenate(kv), (r, c)), shape=(ndof, ndof)).tocsr()
        M = sp.coo_matrix((np.concatenate(mv), (r, c)), shape=(ndof, ndof)).tocsr()
        free = np.setdiff1d(np.arange(ndof), fixed)
        return K, M, free

    # ------------------------------------------------------------------ modes
    def cache_key(self) -> str:
        """sha256 of every parameter that changes the modes (not damping, labels or cache settings)."""
        params = {f.name: getattr(self, f.name) for f in fields(self)
                  if f.name not in ("damping_ratio", "name", "use_cache", "cache_dir", "default_lateral_offset", "default_girder")}
        params["girder"] = asdict(self.section)
        damage = active_damage(self.damage)
        params.pop("damage", None)
        if damage:  # no key without damage: an intact deck keeps its cache file
            params["damage"] = [asdict(d) for d in damage]
        if not self.skew:  # nor without skew: a square deck keeps its cache file
            params.pop("skew")
        params["n_elements"] = self.element_count
        return mode_cache.cache_key(MODEL_VERSION, params)

    def _solve(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(ω [rad/s], nodal mode matrix over all DOFs (ndof, n_modes)) from the sparse eigenproblem."""
        K, M, free = self.assemble()
        Kf = K[free][:, free].tocsc()
        Mf = M[free][:, free].tocsc()
        n = free.size
        want = self.n_modes if self.max_frequency is None else max(self.n_modes, 10)
        while True:
            k = min(want, n)
            lam, vec = lowest_modes(Kf, Mf, k)
            if self.max_frequency is None or k == n or np.sqrt(max(lam[-1], 0.0)) / (2 * np.pi) > self.max_frequency:
                break
            want *= 2
        if self.max_frequency is not None:
            keep = np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi) <= self.max_frequency
            keep[0] = True
            lam, vec = lam[keep], vec[:, keep]
        if np.any(lam <= 0):
            raise ValueError("the deck model has a mechanism (zero-frequency mode); check supports and parameters")
        norms = np.sqrt(np.einsum("im,im->m", vec, Mf @ vec))
        vec = vec / norms
        full = np.zeros((K.shape[0], vec.shape[1]))
        full[free] = vec
        w = full[0::3]
        sign = np.sign(w[np.argmax(np.abs(w), axis=0), np.arange(w.shape[1])])
        return np.sqrt(lam), full * sign

    @cached_property
    def nodal_modes(self) -> NodalModes:
        """The mode shapes at the grid nodes (``NodalModes``) — solved or read from the cache."""
        path = mode_cache.cache_path("slab-on-girder", self.cache_key(), self.cache_dir) if self.use_cache else None
        cached = mode_cache.load_modes(path) if path is not None else None
        if cached is None:
            omega, full = self._solve()
            if path is not None:
                mode_cache.save_modes(path, omega, full)
        else:
            omega, full = cached
        object.__setattr__(self, "_omega", np.asarray(omega))
        return self.dof_map.nodal(full)

    # ------------------------------------------------------------------ ModalBridge
    @property
    def omega(self) -> NDArray[np.float64]:
        self.nodal_modes  # noqa: B018 - solves (or reads) the modes
        return self._omega  # type: ignore[attr-defined]

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        return np.full(self.omega.size, self.damping_ratio)

    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.nodal_modes.evaluate(x, y, 0)

    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.nodal_modes.evaluate(x, y, 1)

    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Girder bottom-fibre strain ε = c_g ∂²w_g/∂x² per unit modal coordinate (tension positive).

        c_g is the height of girder g's composite neutral axis above its bottom fibre.  On a
        girder line this is that girder's strain; between girder lines it is interpolated
        linearly between the two girders; beyond the outer girders it is the outer girder's.
        """
        return girder_line_strain(self.nodal_modes, self.line_properties["c"], x, y)

    # ------------------------------------------------------------------ extras
    def girder_index(self, girder: int) -> int:
        """0-based line index of 1-based girder number ``girder`` (checked)."""
        if not 1 <= int(girder) <= self.n_girders:
            raise ValueError(f"girder must be 1 … {self.n_girders}, got {girder!r}")
        return int(girder) - 1

    def load_vector(self, x: ArrayLike, y: ArrayLike, forces: ArrayLike) -> NDArray[np.float64]:
        """Consistent nodal load vector (all DOFs) of vertical point forces [N] (z up) at (x, y)
        (``vbikit.bridge.deck_effects.load_weights``: Hermite along the lines and across them,
        linear along the lines for the transverse slopes); a force at a node loads only that
        node's w; forces off the deck load nothing."""
        x, y, f = (np.atleast_1d(np.asarray(a, float)).ravel() for a in np.broadcast_arrays(x, y, forces))
        idx, coef, _, _ = load_weights(self.dof_map, x, y)
        F = np.zeros(self.dof_map.n_dof)
        np.add.at(F, idx.ravel(), (coef * f[:, None]).ravel())
        return F

    def static_solution(self, x: ArrayLike, y: ArrayLike, forces: ArrayLike) -> NodalModes:
        """Full-stiffness static solution K u = F for point forces [N] (z up) at (x, y), as a one-column
        ``NodalModes`` (evaluate deflections [m] with ``.evaluate`` and curvatures with ``.curvatures``)."""
        K, _, free = self.assemble()
        F = self.load_vector(x, y, forces)
        u = np.zeros(K.shape[0])
        u[free] = spla.spsolve(K[free][:, free].tocsc(), F[free])
        return self.dof_map.nodal(u[:, None])

    def strain_influence(self, x: float, y: float) -> DeckInfluence:
        """Influence function of the girder strain at (x, y) [m] (``strain_shapes``' strain) from the
        full stiffness: the exact static strain the modes converge to
        (``vbikit.bridge.deck_effects.deck_strain_influence``)."""
        return deck_strain_influence(self, float(x), float(y))

    def load_effect(self, kind: str, x: Optional[float] = None, support: Optional[int] = None,
                    girder: Optional[int] = None) -> LoadEffect:
        """Moment or shear of ``girder`` (default: the default girder) at section x [m] (the deck's x; on
        a skew deck the girder's span runs from x = y_g tan θ), or the reaction of its bearing at
        support 0 (entry), 1, … (``vbikit.bridge.deck_effects``)."""
        return deck_load_effect(self, kind, x, girder, support)

    def default_load_effects(self, girder: Optional[int] = None) -> list[LoadEffect]:
        """Of ``girder``: the moment at the middle of every span and over every interior support, the
        shear just right of every support but the last, and the reaction of every bearing."""
        g = int(self.default_girder) if girder is None else int(girder)
        xs = self.girder_x(g, self.support_x)  # the girder's supports (oblique support lines: shifted)
        n = xs.size - 1
        out = [self.load_effect("moment", 0.5 * (xs[k] + xs[k + 1]), girder=girder) for k in range(n)]
        out += [self.load_effect("moment", float(xs[k]), girder=girder) for k in range(1, n)]
        out += [self.load_effect("shear", float(xs[k]), girder=girder) for k in range(n)]
        return out + [self.load_effect("reaction", support=k, girder=girder) for k in range(n + 1)]

    def mode_descriptions(self) -> list[str]:
        """Short descriptions of the modes, e.g. "1st bending", "1st torsion", "transverse (2 nodal lines)"."""
        return describe_modes(self.nodal_modes)


def describe_modes(modes: NodalModes) -> list[str]:
    """Classify each mode from its nodal deflections: longitudinal half-waves m (sign changes along
    the most-deflected line + 1) and the transverse pattern at the most-deflected station —
    symmetric one-signed → "bending", antisymmetric with one sign change → "torsion", otherwise
    "transverse" with its number of nodal lines."""
    out = []
    for k in range(modes.n_modes):
        w = modes.w[:, :, k]
        if modes.y.size == 1 and np.abs(w).max() < np.abs(modes.wy[:, :, k]).max():  # twist of a single line
            line = modes.wy[0, 1:-1, k]
            s = np.sign(line[np.abs(line) > 1e-6 * np.abs(line).max()])
            m = int(np.sum(s[1:] != s[:-1])) + 1
            out.append(f"torsion, {m} half-wave{'s' if m > 1 else ''} along the span")
            continue
        j, i = np.unravel_index(np.argmax(np.abs(w)), w.shape)
        line = w[j, 1:-1] if w.shape[1] > 2 else w[j]
        tol = 1e-6 * np.abs(w).max()
        s = np.sign(line[np.abs(line) > tol])
        half_waves = int(np.sum(s[1:] != s[:-1])) + 1 if s.size else 1
        sec = w[:, i]
        sym, anti = 0.5 * (sec + sec[::-1]), 0.5 * (sec - sec[::-1])
        ss = np.sign(sec[np.abs(sec) > 1e-3 * np.abs(sec).max()])
        changes = int(np.sum(ss[1:] != ss[:-1])) if ss.size else 0
        if sec.size == 1 or (changes == 0 and np.linalg.norm(anti) < np.linalg.norm(sym)):
            kind = "bending"
        elif changes == 1 and np.linalg.norm(anti) > np.linalg.norm(sym):
            kind = "torsion"
        else:
            kind = f"transverse ({changes} nodal lines)"
        out.append(f"{kind}, {half_waves} half-wave{'s' if half_waves > 1 else ''} along the span")
    return out
