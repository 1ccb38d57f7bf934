"""Continuous Euler–Bernoulli beam over several spans, reduced to its modes.

Model
-----
Spans L_k (k = 1 … n) in a row, each with its own bending stiffness EI_k [N·m²] and mass per
length m_k [kg/m]; n + 1 supports at x_0 = 0, x_1 = L_1, …, x_n = ΣL_k.  Each support is rigid
in the vertical direction or a vertical spring k_j [N/m]; the two end supports may have
rotational springs k_θ [N·m/rad] (0 = pinned, inf = clamped).  Local damage
(``vbikit.bridge.damage``) lowers EI over a region.

Discretisation: cubic Hermite Euler–Bernoulli elements (two DOFs per node, w and ∂w/∂x),
``elements_per_span`` equal elements per span, with extra nodes at the ends of damaged regions
so that each element has one EI; consistent mass.  Element matrices (``vbikit.bridge.elements``; Przemieniecki,
*Theory of Matrix Structural Analysis*, 1968, §5.3 and §11.3):

    K_e = EI/h³ [[12, 6h, −12, 6h], [6h, 4h², −6h, 2h²], …],   M_e = m h/420 [[156, 22h, 54, −13h], …]

The lowest modes of K φ = ω² M φ come from ``scipy.sparse.linalg.eigsh`` (shift-invert about 0),
mass-normalised (φᵀ M φ = 1), and are evaluated between nodes with the same Hermite cubics, so
φ(x) is C¹ and its curvature is the element's.  With 40 elements per span the first six
frequencies of two or three equal spans agree with the closed forms (Blevins, *Formulas for
Natural Frequency and Mode Shape*, 1979, Table 8-1: λL = π, 3.9266, 2π, 7.0686 for two spans)
to better than 1e-6 (``tests/verification/test_continuous_beam.py``).

Load effects (``vbikit.bridge.effects``) follow from equilibrium of the part of the beam left
of the section: support reactions are linear in the loads (influence fields from the full
stiffness, exact at the nodes for Hermite elements), and

    M(s) = Σ_{x_j < s} R_j (s − x_j) − C_0 + ∫₀ˢ (s − x) q(x) dx,    V(s) = Σ_{x_j ≤ s} R_j + ∫₀^{s⁺} q(x) dx,

with q the applied loads (a point force, or the inertia load ω² m φ of a mode) and C_0 the
couple of the left rotational spring.  The beam has no transverse extent: nothing depends on y.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Optional, Sequence, Union

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge.base import DEFAULT_DAMPING_RATIO, ModalBridge
from vbikit.bridge.damage import Damage, active_damage, stiffness_factor
from vbikit.bridge.effects import EFFECT_KINDS, LoadEffect
from vbikit.bridge.eigen import lowest_modes
from vbikit.bridge.elements import beam_element_mass, beam_element_stiffness
from vbikit.bridge.nodal import NodalModes, hermite_basis

Numbers = Union[float, Sequence[float]]

#: Gauss–Legendre points and weights on [0, 1] (3 points: exact for the degree-4 integrands here)
#: longest span [m] a continuous beam takes (100 km: longer than any bridge; far beyond it the FE matrices
#: overflow)
MAX_SPAN = 1e5

_GAUSS_T = (np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]) + 1.0) / 2.0
_GAUSS_W = np.array([5.0, 8.0, 5.0]) / 18.0


def _per_span(name: str, value: Numbers, n: int) -> tuple[float, ...]:
    vals = (float(value),) * n if np.ndim(value) == 0 else tuple(float(v) for v in value)  # type: ignore[union-attr]
    if len(vals) != n:
        raise ValueError(f"bridge.{name}: give one number or one per span ({n}), got {len(vals)}")
    for v in vals:
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"bridge.{name}: every value must be a positive finite number, got {v!r}")
    return vals


def _stiffness(value: Optional[float]) -> float:
    """A support stiffness: None or inf = rigid (returned as inf), else a finite number >= 0."""
    return math.inf if value is None else float(value)


@dataclass(frozen=True)
class ContinuousBeam(ModalBridge):
    """Continuous beam over ``len(spans)`` spans (see the module docstring).

    Parameters
    ----------
    spans : sequence of float
        Span lengths [m], in the direction of travel.
    EI : float or sequence of float
        Bending stiffness [N·m²], one value or one per span.
    mass_per_length : float or sequence of float
        Mass per length [kg/m], one value or one per span.
    damping_ratio : float
        Modal damping ratio ζ [-], all modes (default 2 %, as every bridge model).
    n_modes : int
        Number of modes kept.
    neutral_axis_depth : float
        Neutral axis to bottom fibre c [m] (strain ε = c ∂²w/∂x²).
    support_stiffness : float or sequence, optional
        Vertical stiffness [N/m] of the supports (one value, or one per support, n_spans + 1);
        None or inf = rigid (default: every support rigid).
    rotational_stiffness : (float, float)
        Rotational springs [N·m/rad] at the entry and exit supports (0 = pinned, inf = clamped).
    elements_per_span : int
        Hermite elements per span.
    damage : sequence of Damage
        Local stiffness losses (``vbikit.bridge.damage.Damage`` without a girder).
    """

    spans: tuple[float, ...]
    EI: Numbers
    mass_per_length: Numbers
    damping_ratio: float = DEFAULT_DAMPING_RATIO
    n_modes: int = 10
    neutral_axis_depth: float = 0.5
    support_stiffness: Optional[Union[float, Sequence[Optional[float]]]] = None
    rotational_stiffness: tuple[float, float] = (0.0, 0.0)
    elements_per_span: int = 40
    damage: tuple[Damage, ...] = ()
    name: str = "continuous-beam"
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        spans = tuple(float(s) for s in np.atleast_1d(np.asarray(self.spans, float)))
        if not spans or any(not (math.isfinite(s) and s > 0) for s in spans):
            raise ValueError(f"bridge.spans: a list of positive span lengths [m], got {self.spans!r}")
        if any(s > MAX_SPAN for s in spans):  # the model cannot be solved: its element matrices would overflow
            raise OverflowError(f"bridge.spans: each span at most {MAX_SPAN:g} m, got {max(spans):g} m")
        n = len(spans)
        object.__setattr__(self, "spans", spans)
        object.__setattr__(self, "EI", _per_span("EI", self.EI, n))
        object.__setattr__(self, "mass_per_length", _per_span("mass_per_length", self.mass_per_length, n))
        ks = self.support_stiffness
        ks = (ks,) * (n + 1) if ks is None or np.ndim(ks) == 0 else tuple(ks)  # type: ignore[arg-type]
        if len(ks) != n + 1:
            raise ValueError(f"bridge.support_stiffness: one value or one per support ({n + 1}), got {len(ks)}")
        ks = tuple(_stiffness(k) for k in ks)
        if any(not k >= 0 for k in ks):
            raise ValueError(f"bridge.support_stiffness: values must be >= 0 N/m (inf = rigid), got {ks}")
        object.__setattr__(self, "support_stiffness", ks)
        rot = tuple(float(k) for k in self.rotational_stiffness)
        if len(rot) != 2 or any(not k >= 0 for k in rot):
            raise ValueError(f"bridge.rotational_stiffness: two values >= 0 N m/rad (entry, exit), got {self.rotational_stiffness!r}")
        object.__setattr__(self, "rotational_stiffness", rot)
        if not 0.0 <= self.damping_ratio < 1.0:
            raise ValueError(f"bridge.damping_ratio must be in [0, 1), got {self.damping_ratio!r}")
        if int(self.n_modes) != self.n_modes or self.n_modes < 1:
            raise ValueError(f"bridge.n_modes must be an integer >= 1, got {self.n_modes!r}")
        if int(self.elements_per_span) != self.elements_per_span or self.elements_per_span < 2:
            raise ValueError(f"bridge.elements_per_span must be an integer >= 2, got {self.elements_per_span!r}")
        if not (math.isfinite(self.neutral_axis_depth) and self.neutral_axis_depth > 0):
            raise ValueError(f"bridge.neutral_axis_depth must be > 0 m, got {self.neutral_axis_depth!r}")
        damage = tuple(self.damage)
        for i, d in enumerate(damage):
            if d.girder is not None:
                raise ValueError(f"bridge.damage.{i}: a beam has no girders; remove girder")
            if d.end > self.span + 1e-9:
                raise ValueError(f"bridge.damage.{i}: the region {d.position:g} … {d.end:g} m ends beyond the bridge "
                                 f"(length {self.span:g} m)")
        object.__setattr__(self, "damage", damage)

    # ------------------------------------------------------------------ geometry
    @property
    def span(self) -> float:  # type: ignore[override]
        """Total length [m] (first to last support)."""
        return float(sum(self.spans))

    @property
    def support_x(self) -> NDArray[np.float64]:
        """Support positions [m], shape (n_spans + 1,)."""
        return np.concatenate([[0.0], np.cumsum(self.spans)])

    @property
    def default_section(self) -> float:  # type: ignore[override]
        """Midpoint of the first span [m] (where deflection and sagging moment are read by default)."""
        return 0.5 * self.spans[0]

    @property
    def span_lengths(self) -> tuple[float, ...]:
        """Length [m] of every span (``spans``)."""
        return self.spans

    @cached_property
    def nodes(self) -> NDArray[np.float64]:
        """Node positions [m]: ``elements_per_span`` equal elements per span, plus the ends of damaged regions."""
        xs = self.support_x
        pts = [np.linspace(xs[k], xs[k + 1], self.elements_per_span + 1) for k in range(len(self.spans))]
        for d in active_damage(self.damage):
            pts.append(np.array([d.position, min(d.end, self.span)]))
        x = np.unique(np.concatenate(pts))
        keep = np.concatenate([[True], np.diff(x) > 1e-9 * self.span])
        return x[keep]

    def element_properties(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """EI [N·m²] and m [kg/m] of every element (damage included)."""
        x = self.nodes
        mid = 0.5 * (x[:-1] + x[1:])
        k = np.clip(np.searchsorted(self.support_x, mid, side="right") - 1, 0, len(self.spans) - 1)
        EI = np.asarray(self.EI)[k].astype(float)
        damage = active_damage(self.damage)
        if damage:
            EI = EI * np.array([stiffness_factor(damage, a, b) for a, b in zip(x[:-1], x[1:])])
        return EI, np.asarray(self.mass_per_length)[k].astype(float)

    # ------------------------------------------------------------------ FE model
    def _support_actions(self) -> list[tuple[str, int, float, float]]:
        """(kind "force" | "couple", DOF, stiffness (inf = rigid), x) of every support action."""
        node_of = np.searchsorted(self.nodes, self.support_x - 1e-9 * self.span)
        out = [("force", 2 * int(i), k, float(x)) for i, k, x in zip(node_of, self.support_stiffness, self.support_x)]
        for end, k in zip((0, -1), self.rotational_stiffness):
            if k > 0:
                out.append(("couple", 2 * int(node_of[end]) + 1, k, float(self.support_x[end])))
        return out

    def assemble(self) -> tuple[sp.csr_matrix, sp.csr_matrix, NDArray[np.intp]]:
        """K, M over all DOFs (w, θ per node; springs included) and the free DOFs (rigid supports removed)."""
        x = self.nodes
        EI, m = self.element_properties()
        n_dof = 2 * x.size
        rows, cols, kv, mv = [], [], [], []
        for e in range(x.size - 1):
            h = x[e + 1] - x[e]
            d = np.arange(2 * e, 2 * e + 4)
            r, c = np.meshgrid(d, d, indexing="ij")
            rows.append(r.ravel())
            cols.append(c.ravel())
            kv.append(beam_element_stiffness(EI[e], h).ravel())
            mv.append(beam_element_mass(m[e], h).ravel())
        fixed = []
        for _, dof, k, _ in self._support_actions():
            if math.isinf(k):
                fixed.append(dof)
            else:
                rows.append(np.array([dof]))
                cols.append(np.array([dof]))
                kv.append(np.array([k]))
                mv.append(np.array([0.0]))
        r, c = np.concatenate(rows), np.concatenate(cols)
        K = sp.coo_matrix((np.concatenate(kv), (r, c)), shape=(n_dof, n_dof)).tocsr()
        M = sp.coo_matrix((np.concatenate(mv), (r, c)), shape=(n_dof, n_dof)).tocsr()
        return K, M, np.setdiff1d(np.arange(n_dof), fixed)

    def _solve(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        K, M, free = self.assemble()
        Kf, Mf = K[free][:, free].tocsc(), M[free][:, free].tocsc()
        k = min(self.n_modes, free.size)
        lam, vec = lowest_modes(Kf, Mf, k)
        if np.any(lam <= 1e-9 * lam.max()):
            raise ValueError("the continuous beam has a mechanism (zero-frequency mode): check support_stiffness")
        vec = vec / np.sqrt(np.einsum("im,im->m", vec, Mf @ vec))
        full = np.zeros((K.shape[0], k))
        full[free] = vec
        w = full[0::2]
        sign = np.sign(w[np.argmax(np.abs(w), axis=0), np.arange(k)])
        return np.sqrt(lam), full * sign

    def _nodal(self, full: NDArray[np.float64]) -> NodalModes:
        n = self.nodes.size
        cols = full.shape[1]
        return NodalModes(self.nodes, np.array([0.0]), full[0::2].reshape(1, n, cols), full[1::2].reshape(1, n, cols),
                          np.zeros((1, n, cols)))

    @cached_property
    def _modes(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NodalModes]:
        omega, full = self._solve()
        return omega, full, self._nodal(full)

    @property
    def nodal_modes(self) -> NodalModes:
        """Mode shapes at the nodes (``NodalModes``, one line at y = 0)."""
        return self._modes[2]

    # ------------------------------------------------------------------ ModalBridge
    @property
    def omega(self) -> NDArray[np.float64]:
        return self._modes[0]

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        return np.full(self.omega.size, self.damping_ratio)

    @property
    def lateral_invariant(self) -> bool:
        return True  # φ(x): y is ignored

    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        x = np.atleast_1d(np.asarray(x, float)).ravel()
        return self.nodal_modes.evaluate(x, np.zeros_like(x), 0)

    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        x = np.atleast_1d(np.asarray(x, float)).ravel()
        return self.nodal_modes.evaluate(x, np.zeros_like(x), 1)

    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        x = np.atleast_1d(np.asarray(x, float)).ravel()
        return self.neutral_axis_depth * self.nodal_modes.curvatures(x, 0)

    # ------------------------------------------------------------------ statics
    def strain_per_moment(self, x: float) -> float | None:
        """c / EI(x) [1/(N·m)]: the bottom-fibre strain per unit sagging moment at section x [m]
        (ε = c·M/EI, Euler–Bernoulli), from the element holding x (damage included); None at a node
        where EI changes (a damage boundary, a support between spans of different EI: no one value)."""
        nodes = self.nodes
        EI, _ = self.element_properties()
        x = float(x)
        k = int(np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, EI.size - 1))
        j = int(np.argmin(np.abs(nodes - x)))
        if abs(nodes[j] - x) <= 1e-9 * self.span and 0 < j < EI.size and EI[j - 1] != EI[j]:
            return None
        return float(self.neutral_axis_depth / EI[k])

    def static_deflection(self, x: ArrayLike, loads_x: ArrayLike, loads: ArrayLike) -> NDArray[np.float64]:
        """Full-stiffness static deflection [m] at x under point forces ``loads`` [N] (z up) at ``loads_x`` [m]."""
        K, _, free = self.assemble()
        F = self._load_vector(np.atleast_1d(np.asarray(loads_x, float)), np.atleast_1d(np.asarray(loads, float)))
        u = np.zeros(K.shape[0])
        u[free] = spla.spsolve(K[free][:, free].tocsc(), F[free])
        x = np.atleast_1d(np.asarray(x, float)).ravel()
        return self._nodal(u[:, None]).evaluate(x, np.zeros_like(x))[:, 0]

    def _load_vector(self, xp: NDArray[np.float64], fp: NDArray[np.float64]) -> NDArray[np.float64]:
        x = self.nodes
        F = np.zeros(2 * x.size)
        for xx, f in zip(xp, fp):
            if not 0.0 <= xx <= self.span:
                continue
            e = int(np.clip(np.searchsorted(x, xx, side="right") - 1, 0, x.size - 2))
            h = x[e + 1] - x[e]
            n = hermite_basis(np.array((xx - x[e]) / h), h, 0)
            F[2 * e:2 * e + 4] += f * np.array([float(v) for v in n])
        return F

    @cached_property
    def _reaction_fields(self) -> tuple[list[tuple[str, int, float, float]], NDArray[np.float64], NDArray[np.float64]]:
        """Support actions, their influence fields z (n_dof, n_actions) — action = zᵀ F for a nodal
        load F — and their values per unit modal coordinate (n_actions, n_modes)."""
        K, M, free = self.assemble()
        actions = self._support_actions()
        Kff = K[free][:, free].tocsc()
        lu = spla.splu(Kff)
        pos = -np.ones(K.shape[0], int)
        pos[free] = np.arange(free.size)
        z = np.zeros((K.shape[0], len(actions)))
        omega, full, _ = self._modes
        modal = np.zeros((len(actions), omega.size))
        Kphi, Mphi = K @ full, M @ full
        for a, (_, dof, k, _) in enumerate(actions):
            if math.isinf(k):  # rigid: R = (K u)_d − F_d
                z[free, a] = lu.solve(np.asarray(K[free][:, [dof]].todense()).ravel())
                z[dof, a] = -1.0
                modal[a] = Kphi[dof] - omega**2 * Mphi[dof]
            else:  # spring: R = −k u_d
                e = np.zeros(free.size)
                e[pos[dof]] = 1.0
                z[free, a] = -k * lu.solve(e)
                modal[a] = -k * full[dof]
        return actions, z, modal

    def _inertia_integrals(self, s: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """∫₀ˢ m φ_i dx and ∫₀ˢ (s − x) m φ_i dx per mode (Gauss, exact for the Hermite shapes)."""
        x = self.nodes
        _, m = self.element_properties()
        force = np.zeros(self.omega.size)
        moment = np.zeros(self.omega.size)
        for e in range(x.size - 1):
            a, b = x[e], min(x[e + 1], s)
            if b <= a:
                break
            xq = a + (b - a) * _GAUSS_T
            phi = self.mode_shapes(xq)
            wq = (b - a) * _GAUSS_W * m[e]
            force += wq @ phi
            moment += (wq * (s - xq)) @ phi
        return force, moment

    # ------------------------------------------------------------------ load effects
    def load_effect(self, kind: str, x: Optional[float] = None, support: Optional[int] = None,
                    girder: Optional[int] = None) -> LoadEffect:
        """The load effect ``kind`` ("moment", "shear" at section x [m]; "reaction" of support index
        ``support``, 0 = entry) with its influence function and modal values (``vbikit.bridge.effects``)."""
        if girder is not None:
            raise ValueError("a beam has no girders: leave girder unset")
        if kind not in EFFECT_KINDS:
            raise ValueError(f"load effect must be one of {', '.join(EFFECT_KINDS)}, got {kind!r}")
        actions, z, modal_actions = self._reaction_fields
        omega = self.omega
        xs = self.support_x
        tol = 1e-9 * self.span
        spans = self.spans
        if kind == "reaction":
            if support is None or not 0 <= int(support) <= len(spans):
                raise ValueError(f"reaction: support must be 0 … {len(spans)}, got {support!r}")
            j = int(support)
            field_z = z[:, j]
            fields = self._nodal(field_z[:, None])

            def influence(xp, yp=None, fields=fields):
                return fields.evaluate(np.asarray(xp, float), 0.0)[:, 0]

            length = spans[0] if j == 0 else spans[-1] if j == len(spans) else 0.5 * (spans[j - 1] + spans[j])
            return LoadEffect("reaction", float(xs[j]), modal_actions[j].copy(), influence, float(length), support=j)
        if x is None or not -tol <= x <= self.span + tol:
            raise ValueError(f"{kind}: section x must be within 0 … {self.span:g} m, got {x!r}")
        s = float(np.clip(x, 0.0, self.span))
        force_int, moment_int = self._inertia_integrals(s)
        comb = np.zeros(len(actions))
        for a, (what, _, _, xa) in enumerate(actions):
            if kind == "moment":
                if what == "force" and xa < s - tol:
                    comb[a] = s - xa
                elif what == "couple" and xa < s - tol:
                    comb[a] = -1.0
            elif what == "force" and xa <= s + tol:
                comb[a] = 1.0
        fields = self._nodal((z @ comb)[:, None])
        if kind == "moment":
            modal = comb @ modal_actions + omega**2 * moment_int

            def influence(xp, yp=None, fields=fields, s=s):
                xp = np.atleast_1d(np.asarray(xp, float)).ravel()
                direct = np.where((xp >= 0.0) & (xp < s), s - xp, 0.0)
                return fields.evaluate(xp, 0.0)[:, 0] + direct
        else:
            modal = comb @ modal_actions + omega**2 * force_int

            def influence(xp, yp=None, fields=fields, s=s):
                xp = np.atleast_1d(np.asarray(xp, float)).ravel()
                direct = np.where((xp >= 0.0) & (xp <= s), 1.0, 0.0)
                return fields.evaluate(xp, 0.0)[:, 0] + direct
        at_support = np.min(np.abs(xs - s)) <= tol
        interior = at_support and 0 < int(np.argmin(np.abs(xs - s))) < len(spans)
        if kind == "moment" and interior:
            j = int(np.argmin(np.abs(xs - s)))
            length = 0.5 * (spans[j - 1] + spans[j])
        else:
            length = spans[self.span_index(s)]
        return LoadEffect(kind, s, modal, influence, float(length), hogging_region=bool(kind == "moment" and interior))

    def default_load_effects(self) -> list[LoadEffect]:
        """Sagging moment at the middle of every span, hogging moment over every interior support, shear
        just right of every support but the last, and every support reaction."""
        xs = self.support_x
        n = len(self.spans)
        effects = [self.load_effect("moment", 0.5 * (xs[k] + xs[k + 1])) for k in range(n)]
        effects += [self.load_effect("moment", float(xs[j])) for j in range(1, n)]
        effects += [self.load_effect("shear", float(xs[j])) for j in range(n)]
        effects += [self.load_effect("reaction", support=j) for j in range(n + 1)]
        return effects
