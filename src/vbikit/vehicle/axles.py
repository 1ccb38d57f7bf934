"""Trucks from axle loads and spacings (weigh-in-motion records), and the five-axle 3-S2.

A truck is a 3D multibody (conventions of ``vbikit.vehicle.model``): one rigid body, or a
tractor and a semitrailer pinned together at the fifth wheel; under them axle *groups*:

* ``"single"``: one axle with its own suspension;
* ``"tandem"`` / ``"tridem"``: 2 / 3 consecutive axles, each with its own suspension;
* ``"walking-beam"``: a load-equalising tandem: a rigid bogie (heave, pitch, roll) hung from the
  body by one suspension per side at its pivot, the tires on its axles (the group model of
  VBI-2D, ``Vehicle_3A2_G_1_2_2``, extended to left and right wheels).

Every axle has bounce and roll (roll inertia m·b², as the other presets) and a suspension and
a tire spring–damper per side at ±b.  A bogie owns heave, pitch and roll; its axles are rigid
on it.

Static loads as given ([`axle_truck`][vbikit.vehicle.axle_truck]).  A rigid body on three or more spring supports is
statically indeterminate: the loads follow the springs.  The defaults make any given split
exact: every tire compresses by the same static deflection δ_t and every suspension by the same
δ_s, i.e. tire stiffness ∝ its static wheel load and suspension stiffness ∝ the load it carries
(k = F/δ, the way real axles are sized to their rated loads).  Then every body rests level, the
equilibrium of each body fixes its mass and centre of gravity (the load centroid of its
supports), a bogie's pivot is the load centroid of its axles, and the tandem loads come out as
given whatever their ratio.  The fifth-wheel load is the one that puts the tractor body's
centre of gravity at ``TRACTOR_CG_FRACTION`` of its wheelbase.

Default properties [substitute], sources:

* static tire deflection δ_t = 0.019 m and suspension deflection δ_s = 0.033 m: those of the
  paper's HS20-44 (Table 1: drive and trailer tires 3.50e6 N/m per side at ≈ 67 kN, 0.019 m;
  their suspensions 1.90e6 / 1.97e6 N/m at ≈ 63 / 65 kN, 0.033 m);
* unsprung mass 700 kg on the first axle, 1100 kg on every other (the field-test dump truck
  of ``vbikit.vehicle.presets.dump_truck`` and VBI-2D's five-axle vehicle of
  ``A01_VBI_input_and_run.m``);
* dampers from damping ratios: suspension c = 2·0.10·√(k·F/g) per side (F its static load;
  the paper's HS20 has 0.04–0.06, the dump-truck substitute 0.15), tire c = 2·0.03·√(k·m_u/2)
  (HS20: 0.027);
* half-track b = 0.9 m (AASHTO wheel lines 1.83 m apart); body pitch and roll inertias
  m(L² + h²)/12 and m(w² + h²)/12 of a box L long (its supports' extent + 2 m), w = h = 2.5 m
  (as the dump truck's body);
* resulting frequencies (on rigid ground): body modes ≈ 1.2–4 Hz (body heave ≈ √(g/(δ_s + δ_t))/2π
  ≈ 2 Hz), axle and bogie hop and roll ≈ 8–16 Hz;
* consecutive axles at most ``GROUP_SPACING`` apart form a group when ``groups`` is not
  given; a truck of four or more axles in three or more groups is a tractor (its first two
  groups) with a semitrailer, its fifth wheel 0.5 m ahead of the centre of the tractor's last
  group (as in [`semitrailer_3s2`][vbikit.vehicle.semitrailer_3s2]).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Optional, Sequence

import numpy as np

from vbikit.vehicle.builder import Body, VehicleBuilder, assemble
from vbikit.vehicle.model import GRAVITY, Vehicle

#: axle-group kinds and their number of axles
GROUP_KINDS: dict[str, int] = {"single": 1, "tandem": 2, "tridem": 3, "walking-beam": 2}
#: [substitute] consecutive axles at most this far apart [m] form a group (tandem, tridem)
GROUP_SPACING = 2.0
#: [substitute] the tractor body's centre of gravity sits this fraction of the wheelbase (first
#: axle to the centre of the tractor's last group) behind the first axle: 1 m of 4.5 m in VBI-2D's
#: five-axle vehicle (:func:`semitrailer_3s2`); it fixes the fifth-wheel load
TRACTOR_CG_FRACTION = 1.0 / 4.5
#: [substitute] the fifth wheel sits this far [m] ahead of the centre of the tractor's last group
FIFTH_WHEEL_LEAD = 0.5

TIRE_DEFLECTION = 0.019
SUSPENSION_DEFLECTION = 0.033
SUSPENSION_DAMPING_RATIO = 0.10
TIRE_DAMPING_RATIO = 0.03
HALF_TRACK = 0.9
#: largest half-track [m] (a 4 m wide vehicle; road vehicles are at most 2.6 m wide)
MAX_HALF_TRACK = 2.0
#: largest axle load [N] a truck is built with (1,000 t: far beyond any legal or crane load; a unit slip
#: such as kg·m/s² given as N·1e3 is refused rather than run)
MAX_AXLE_LOAD = 1e7
#: largest static tire or suspension deflection [m]: refuses a slip of units (mm given as m) while
#: leaving room for the very soft suspensions that isolate the axle-hop modes in studies
MAX_DEFLECTION = 5.0
#: largest static tire deflection [m]: 10 cm, beyond a flat truck tire (a loaded truck tire deflects 2–4 cm);
#: 0.5 m (a unit slip) is refused
MAX_TIRE_DEFLECTION = 0.1
STEER_UNSPRUNG_MASS = 700.0
UNSPRUNG_MASS = 1100.0
BODY_HEIGHT = 2.5
BODY_WIDTH = 2.5
BODY_OVERHANG = 1.0


@dataclass(frozen=True)
class AxleSpec:
    """One axle: position s [m] behind the front axle, unsprung mass [kg], per-side suspension
    and tire stiffness [N/m] and damping [N·s/m]."""

    s: float
    mass: float
    suspension_stiffness: float
    suspension_damping: float
    tire_stiffness: float
    tire_damping: float


@dataclass(frozen=True)
class GroupSpec:
    """Axles of one group; ``bogie`` = (pivot s [m], pitch inertia [kg·m²], per-side suspension
    k [N/m] and c [N·s/m] at the pivot) for a load-equalising group, None for independent axles."""

    axles: tuple[AxleSpec, ...]
    body: int
    bogie: Optional[tuple[float, float, float, float]] = None


@dataclass(frozen=True)
class BodySpec:
    """A sprung body: mass [kg], CG s [m], pitch and roll inertias [kg·m²]; ``hinge``: s [m] of
    the pin to the previous body (a semitrailer's fifth wheel), None for the first body."""

    mass: float
    s_cg: float
    pitch_inertia: float
    roll_inertia: float
    hinge: Optional[float] = None


def build_truck(name: str, bodies: Sequence[BodySpec], groups: Sequence[GroupSpec], half_track: float,
                description: str, parameters: dict | None = None) -> Vehicle:
    """Assemble bodies, axle groups, suspensions and tires into a [`Vehicle`][vbikit.vehicle.Vehicle].

    DOFs: heave, pitch, roll of the first body; pitch, roll of each hinged body (its heave
    follows the hinge); heave, pitch, roll of each bogie; bounce and roll of each independent
    axle.  Wheels are named ``axle<i>_left`` / ``axle<i>_right`` (i from 1, front to rear).

    The trucks of one layout (bodies and hinges, groups and their axles: ``_TruckLayout``) share
    their DOFs and which entry of which displacement row holds which difference of positions; the
    layout is worked out once (``_truck_layout``) and each truck's rows are then filled in a few
    array operations: the same numbers as ``VehicleBuilder`` (``_build_truck_with_builder``), bit for
    bit (tests/unit/test_vehicle_assembly.py), at a fraction of its cost (a traffic stream builds
    every truck of every event).
    """
    key = _layout_key(bodies, groups)
    if key is None:  # (a trailer hinged to a trailer: the builder's own bookkeeping)
        return _build_truck_with_builder(name, bodies, groups, half_track, description, parameters)
    return _truck_layout(key).build(name, bodies, groups, half_track, description, parameters)


def _build_truck_with_builder(name: str, bodies: Sequence[BodySpec], groups: Sequence[GroupSpec], half_track: float,
                              description: str, parameters: dict | None = None) -> Vehicle:
    """``build_truck`` through ``VehicleBuilder`` (the reference of ``_TruckLayout``)."""
    b = half_track
    vb = VehicleBuilder(name)
    made: list[Body] = []
    for i, body in enumerate(bodies):
        label = "body" if len(bodies) == 1 else ("tractor" if i == 0 else f"trailer{i}" if len(bodies) > 2 else "trailer")
        if body.hinge is None:
            made.append(vb.body(label, body.mass, body.s_cg, pitch_inertia=body.pitch_inertia,
                                roll_inertia=body.roll_inertia, pitch=True, roll=True))
        else:
            made.append(vb.hinged_body(label, body.mass, body.s_cg, made[-1], body.hinge,
                                       pitch_inertia=body.pitch_inertia, roll_inertia=body.roll_inertia, roll=True))
    n = 0
    for g, group in enumerate(groups):
        carrier = made[group.body]
        if group.bogie is None:
            for ax in group.axles:
                n += 1
                axle = vb.body(f"axle{n}", ax.mass, ax.s, roll_inertia=ax.mass * b**2, roll=True)
                for side, y in (("left", b), ("right", -b)):
                    vb.spring(carrier.point(ax.s, y), axle.point(ax.s, y), ax.suspension_stiffness, ax.suspension_damping)
                    vb.wheel(f"axle{n}_{side}", axle.point(ax.s, y), ax.s, y, ax.tire_stiffness, ax.tire_damping)
            continue
        pivot, pitch_inertia, k_s, c_s = group.bogie
        mass = sum(ax.mass for ax in group.axles)
        bogie = vb.body(f"bogie{g + 1}", mass, pivot, pitch_inertia=pitch_inertia, roll_inertia=mass * b**2,
                        pitch=True, roll=True)
        for side, y in (("left", b), ("right", -b)):
            vb.spring(carrier.point(pivot, y), bogie.point(pivot, y), k_s, c_s)
        for ax in group.axles:
            n += 1
            for side, y in (("left", b), ("right", -b)):
                vb.wheel(f"axle{n}_{side}", bogie.point(ax.s, y), ax.s, y, ax.tire_stiffness, ax.tire_damping)
    return vb.build(description, parameters)



def _layout_key(bodies: Sequence[BodySpec], groups: Sequence[GroupSpec]) -> tuple | None:
    """The layout of a truck: per body whether it is hinged, per group its axles, body and whether it
    is a bogie; None when a hinged body hangs from another hinged one (not laid out: ``_TruckLayout``)."""
    hinged = tuple(body.hinge is not None for body in bodies)
    if any(hinged[i] and (i == 0 or hinged[i - 1]) for i in range(len(hinged))):
        return None
    return hinged, tuple((len(g.axles), int(g.body), g.bogie is not None) for g in groups)


#: kinds of the entries of a truck's displacement rows, in the parameters P (``_TruckLayout``):
#: P[a]; P[a] − P[b]; −(P[a] − P[b]); −(P[a] − P[b]) + (P[a] − P[c])
_VALUE, _DIFF, _NEG_DIFF, _HINGED = 0, 1, 2, 3


class _TruckLayout:
    """What the trucks of one layout (``_layout_key``) share: their DOF names, body and wheel names, and
    the entries of their dense displacement rows (``vbikit.vehicle.builder.assemble``'s ``every``), each
    one of the kinds above of the parameters P = (1, 0, b, −b, each body's s_cg, each body's hinge s,
    each axle's s, each group's pivot s) — worked out by the same steps as ``VehicleBuilder`` on
    symbols: a body point (s, y) moves by heave + (s_cg − s)·pitch + y·roll; a hinged body's heave is its
    parent's point at the hinge less (s_cg − s_hinge)·pitch.  Filling them adds each entry to zero, as
    ``VehicleBuilder``'s dense rows do, so the rows are the builder's bit for bit."""

    def __init__(self, key: tuple) -> None:
        hinged, groups = key
        n_bodies, n_axles = len(hinged), sum(n for n, _, _ in groups)
        one, zero, left, right = 0, 1, 2, 3
        cg0, hinge0, axle0, pivot0 = 4, 4 + n_bodies, 4 + 2 * n_bodies, 4 + 2 * n_bodies + n_axles
        self.n_parameters = pivot0 + len(groups)
        dofs: list[str] = []

        def dof(name: str) -> int:
            dofs.append(name)
            return len(dofs) - 1

        # a symbolic row: {DOF: (kind, a, b, c)}; a body: (heave, pitch, roll rows, its s_cg parameter)
        heaves, pitches, rolls = [], [], []

        def body(label: str, cg: int, pitch: bool, heave: dict | None = None) -> list:
            h = {dof(f"{label}_heave"): (_VALUE, one, 0, 0)} if heave is None else heave
            p = {dof(f"{label}_pitch"): (_VALUE, one, 0, 0)} if pitch else {}
            r = {dof(f"{label}_roll"): (_VALUE, one, 0, 0)}
            made = [h, p, r, cg, None]
            heaves.append(h)
            pitches.append(p)
            rolls.append(r)
            return made

        def point(b: list, s: int, y: int) -> dict:
            h, p, r, cg, hinge = b
            out = dict(h)
            if hinge is not None:  # the hinged body's own pitch entry in its heave row, plus (s_cg − s)·pitch
                (i,) = p
                out[i] = (_HINGED, cg, hinge, s)
            else:
                out.update({i: (_DIFF, cg, s, 0) for i in p})
            out.update({i: (_VALUE, y, 0, 0) for i in r})
            return out

        names = []
        made: list[list] = []
        for i, is_hinged in enumerate(hinged):
            label = "body" if n_bodies == 1 else ("tractor" if i == 0 else f"trailer{i}" if n_bodies > 2 else "trailer")
            names.append(label)
            if not is_hinged:
                made.append(body(label, cg0 + i, True))
                continue
            parent = made[-1]
            b = body(label, cg0 + i, True, heave={})
            (own,) = b[1]
            b[0].update(point(parent, hinge0 + i, zero))  # the parent's point at the hinge (y = 0)
            b[0][own] = (_NEG_DIFF, cg0 + i, hinge0 + i, 0)
            b[4] = hinge0 + i
            made.append(b)
        springs_a, springs_b, wheels = [], [], []
        wheel_names = []
        n = 0
        for g, (count, carrier_index, bogie) in enumerate(groups):
            carrier = made[carrier_index]
            if not bogie:
                for _ in range(count):
                    n += 1
                    names.append(f"axle{n}")
                    axle = body(f"axle{n}", axle0 + n - 1, False)
                    for side, y in (("left", left), ("right", right)):
                        springs_a.append(point(carrier, axle0 + n - 1, y))
                        springs_b.append(point(axle, axle0 + n - 1, y))
                        wheels.append(point(axle, axle0 + n - 1, y))
                        wheel_names.append(f"axle{n}_{side}")
                continue
            names.append(f"bogie{g + 1}")
            beam = body(f"bogie{g + 1}", pivot0 + g, True)
            for side, y in (("left", left), ("right", right)):
                springs_a.append(point(carrier, pivot0 + g, y))
                springs_b.append(point(beam, pivot0 + g, y))
            for _ in range(count):
                n += 1
                for side, y in (("left", left), ("right", right)):
                    wheels.append(point(beam, axle0 + n - 1, y))
                    wheel_names.append(f"axle{n}_{side}")
        rows = heaves + pitches + rolls + springs_a + springs_b + wheels
        self.dofs = tuple(dofs)
        self.body_names = tuple(names)
        self.wheel_names = tuple(wheel_names)
        self.n_rows = len(rows)
        width = len(dofs)
        entries = [(k * width + i, *f) for k, row in enumerate(rows) for i, f in row.items()]
        flat, kind, a, b_, c = (np.array(col, np.int64) for col in zip(*entries))
        self.kinds = tuple((flat[kind == k], a[kind == k], b_[kind == k], c[kind == k]) for k in range(4))

    def rows(self, parameters: np.ndarray) -> np.ndarray:
        """The dense rows (``assemble``'s ``every``) for the parameters P (a fresh array)."""
        every = np.zeros(self.n_rows * len(self.dofs))
        (f0, a0, _, _), (f1, a1, b1, _), (f2, a2, b2, _), (f3, a3, b3, c3) = self.kinds
        p = parameters
        every[f0] = p[a0] + 0.0
        every[f1] = (p[a1] - p[b1]) + 0.0
        every[f2] = -(p[a2] - p[b2]) + 0.0
        every[f3] = ((-(p[a3] - p[b3]) + 0.0) + (p[a3] - p[c3])) + 0.0
        return every.reshape(self.n_rows, len(self.dofs))

    def build(self, name: str, bodies: Sequence[BodySpec], groups: Sequence[GroupSpec], half_track: float,
              description: str, parameters: dict | None) -> Vehicle:
        """The truck of these specs (``build_truck``)."""
        b = half_track
        p = np.full(self.n_parameters, np.nan)
        p[:4] = (1.0, 0.0, b, -b)
        n_bodies = len(bodies)
        p[4:4 + n_bodies] = [body.s_cg for body in bodies]
        p[4 + n_bodies:4 + 2 * n_bodies] = [math.nan if body.hinge is None else body.hinge for body in bodies]
        axles = [ax for group in groups for ax in group.axles]
        p[4 + 2 * n_bodies:4 + 2 * n_bodies + len(axles)] = [ax.s for ax in axles]
        p[4 + 2 * n_bodies + len(axles):] = [math.nan if g.bogie is None else g.bogie[0] for g in groups]
        body_specs = [(label, body.mass, body.s_cg, body.pitch_inertia, body.roll_inertia)
                      for label, body in zip(self.body_names, bodies)]
        springs: list[tuple[float, float]] = []
        wheel_specs = []
        names = iter(self.body_names[n_bodies:])
        wheel_names = iter(self.wheel_names)
        for g, group in enumerate(groups):
            if group.bogie is None:
                for ax in group.axles:
                    body_specs.append((next(names), ax.mass, ax.s, 0.0, ax.mass * b**2))
                    springs += [(ax.suspension_stiffness, ax.suspension_damping)] * 2
                    wheel_specs += [(next(wheel_names), ax.s, y, ax.tire_stiffness, ax.tire_damping, 0.0) for y in (b, -b)]
                continue
            pivot, pitch_inertia, k_s, c_s = group.bogie
            mass = sum(ax.mass for ax in group.axles)
            body_specs.append((next(names), mass, pivot, pitch_inertia, mass * b**2))
            springs += [(k_s, c_s)] * 2
            wheel_specs += [(next(wheel_names), ax.s, y, ax.tire_stiffness, ax.tire_damping, 0.0)
                            for ax in group.axles for y in (b, -b)]
        return assemble(name, self.dofs, self.rows(p), body_specs, springs, wheel_specs, description, parameters)


@lru_cache(maxsize=256)
def _truck_layout(key: tuple) -> _TruckLayout:
    """The ``_TruckLayout`` of ``key`` (worked out once per layout in a process; shared, read only)."""
    return _TruckLayout(key)

def _box_inertias(mass: float, length: float) -> tuple[float, float]:
    return (mass * (length**2 + BODY_HEIGHT**2) / 12.0, mass * (BODY_WIDTH**2 + BODY_HEIGHT**2) / 12.0)


def default_groups(axle_spacings: Sequence[float]) -> list[str]:
    """Axle groups from the spacings: runs of axles at most ``GROUP_SPACING`` apart
    (2 → ``tandem``, 3 → ``tridem``; longer runs are split into tridems and tandems)."""
    runs, size = [], 1
    for s in axle_spacings:
        if s <= GROUP_SPACING:
            size += 1
        else:
            runs.append(size)
            size = 1
    runs.append(size)
    names = {1: "single", 2: "tandem", 3: "tridem"}
    out: list[str] = []
    for r in runs:
        while r > 3:
            take = 3 if r != 4 else 2
            out.append(names[take])
            r -= take
        out.append(names[r])
    return out


def axle_truck(
    axle_loads: Sequence[float],
    axle_spacings: Sequence[float],
    groups: Optional[Sequence[str]] = None,
    tractor_groups: Optional[int] = None,
    unsprung_masses: Optional[Sequence[float]] = None,
    half_track: float = HALF_TRACK,
    tire_deflection: float = TIRE_DEFLECTION,
    suspension_deflection: float = SUSPENSION_DEFLECTION,
    suspension_damping_ratio: float = SUSPENSION_DAMPING_RATIO,
    tire_damping_ratio: float = TIRE_DAMPING_RATIO,
) -> Vehicle:
    """A truck whose static axle loads are exactly ``axle_loads`` (see the module docstring).

    Parameters
    ----------
    axle_loads : sequence of float
        Static load of each axle [N], front to rear (both wheels together), > 0; at least two
        axles (one rigid body on one axle would pitch freely).
    axle_spacings : sequence of float
        Distance [m] from each axle to the next (len(axle_loads) − 1 values), > 0.
    groups : sequence of str, optional
        Axle groups front to rear, from ``GROUP_KINDS``; their axles must add up to the
        number of axles.  Default: ``default_groups``.
    tractor_groups : int, optional
        Number of groups under the tractor of an articulated truck (0 = one rigid body).
        Default: 2 when there are ≥ 3 groups and ≥ 4 axles, else 0.
    unsprung_masses : sequence of float, optional
        Mass [kg] of each axle; default 700 kg for the first, 1100 kg for the others.
    half_track : float
        b [m]: wheels at y = ±b.
    tire_deflection, suspension_deflection : float
        Static deflections δ_t, δ_s [m] that size the springs.
    suspension_damping_ratio, tire_damping_ratio : float
        ζ of the suspension and tire dampers [-].
    """
    loads = np.asarray(axle_loads, float)
    spacings = np.asarray(axle_spacings, float)
    n_ax = loads.size
    if n_ax < 2 or loads.ndim != 1:
        raise ValueError("axle_loads must be a list of at least two axle loads [N] (a body on one axle has no "
                         "stiffness against pitch: its static equilibrium is singular)")
    if spacings.size != n_ax - 1:
        raise ValueError(f"axle_spacings needs {n_ax - 1} value(s) for {n_ax} axles, got {spacings.size}")
    if not all(0 < x <= MAX_AXLE_LOAD for x in loads.tolist()):  # (NaN and ±inf fail a comparison)
        raise ValueError(f"axle_loads must be in (0, {MAX_AXLE_LOAD:g}] N, got {[float(x) for x in loads]}")
    if not all(0 < x <= 30 for x in spacings.ravel().tolist()):
        raise ValueError(f"axle_spacings must be in (0, 30] m, got {[float(x) for x in spacings]}")
    for key, v, hi in (("half_track", half_track, MAX_HALF_TRACK), ("tire_deflection", tire_deflection, MAX_TIRE_DEFLECTION),
                       ("suspension_deflection", suspension_deflection, MAX_DEFLECTION)):
        if not (math.isfinite(v) and 0 < v <= hi):
            raise ValueError(f"{key} must be in (0, {hi:g}] m, got {v!r}")
    for key, v in (("suspension_damping_ratio", suspension_damping_ratio), ("tire_damping_ratio", tire_damping_ratio)):
        if not (math.isfinite(v) and 0 <= v < 1):
            raise ValueError(f"{key} must be in [0, 1), got {v!r}")
    kinds = list(groups) if groups is not None else default_groups(spacings.tolist())
    for k in kinds:
        if k not in GROUP_KINDS:
            raise ValueError(f"groups: unknown axle group {k!r}; allowed: {', '.join(GROUP_KINDS)}")
    if sum(GROUP_KINDS[k] for k in kinds) != n_ax:
        raise ValueError(f"groups: {kinds} hold {sum(GROUP_KINDS[k] for k in kinds)} axles, the truck has {n_ax}")
    if tractor_groups is None:
        tractor_groups = 2 if (len(kinds) >= 3 and n_ax >= 4) else 0
    if not 0 <= tractor_groups < len(kinds):
        raise ValueError(f"tractor_groups must be 0 (rigid) or 1 … {len(kinds) - 1}, got {tractor_groups}")
    masses = np.array([STEER_UNSPRUNG_MASS] + [UNSPRUNG_MASS] * (n_ax - 1)) if unsprung_masses is None \
        else np.asarray(unsprung_masses, float)
    if masses.size != n_ax or not all(0 < x < math.inf for x in masses.ravel().tolist()):
        raise ValueError(f"unsprung_masses needs {n_ax} value(s) > 0 kg, got {list(np.atleast_1d(masses))}")
    sprung = loads - masses * GRAVITY  # load through the suspension of each axle [N]
    if np.any(sprung < 0.25 * loads):
        i = int(np.argmax(sprung < 0.25 * loads))
        raise ValueError(f"axle_loads: axle {i + 1}: load {loads[i]:.0f} N is too small for its unsprung mass {masses[i]:.0f} kg "
                         "(the suspension must carry at least a quarter of the axle load); give smaller unsprung_masses")
    s_axle = np.concatenate([[0.0], np.cumsum(spacings)])

    # tires and suspensions sized by the static deflections (per side: half the axle)
    # (as Python floats: the same IEEE arithmetic as on numpy's scalars, without their overhead)
    load_of, mass_of, sprung_of, s_of = loads.tolist(), masses.tolist(), sprung.tolist(), s_axle.tolist()

    def axle_spec(i: int, suspension: bool) -> AxleSpec:
        k_t = 0.5 * load_of[i] / tire_deflection
        c_t = 2 * tire_damping_ratio * math.sqrt(k_t * 0.5 * mass_of[i])
        k_s = 0.5 * sprung_of[i] / suspension_deflection if suspension else 0.0
        c_s = 2 * suspension_damping_ratio * math.sqrt(k_s * 0.5 * sprung_of[i] / GRAVITY) if suspension else 0.0
        return AxleSpec(s_of[i], mass_of[i], k_s, c_s, k_t, c_t)

    # groups, with their supports on the bodies: (s [m], load [N]) of each suspension
    first = np.cumsum([0] + [GROUP_KINDS[k] for k in kinds])[:-1]
    body_of = [0 if (tractor_groups == 0 or g < tractor_groups) else 1 for g in range(len(kinds))]
    group_specs: list[GroupSpec] = []
    supports: list[list[tuple[float, float]]] = [[], []]
    for g, kind in enumerate(kinds):
        idx = list(range(first[g], first[g] + GROUP_KINDS[kind]))
        if kind != "walking-beam":
            group_specs.append(GroupSpec(tuple(axle_spec(i, True) for i in idx), body_of[g]))
            supports[body_of[g]] += [(s_of[i], sprung_of[i]) for i in idx]
            continue
        p = float(sprung[idx].sum())  # the bogie carries its axles' sprung loads at its pivot
        pivot = float((loads[idx] * s_axle[idx]).sum() / loads[idx].sum())  # tire-load centroid
        k_s = 0.5 * p / suspension_deflection
        c_s = 2 * suspension_damping_ratio * math.sqrt(k_s * 0.5 * p / GRAVITY)
        pitch_inertia = float((masses[idx] * (s_axle[idx] - pivot) ** 2).sum())  # axles as point masses
        group_specs.append(GroupSpec(tuple(axle_spec(i, False) for i in idx), body_of[g], (pivot, pitch_inertia, k_s, c_s)))
        supports[body_of[g]].append((pivot, p))

    def body_from(sup: list[tuple[float, float]], extra: list[tuple[float, float]], hinge=None) -> BodySpec:
        weight = sum(f for _, f in sup) + sum(f for _, f in extra)
        s_cg = (sum(s * f for s, f in sup) + sum(s * f for s, f in extra)) / weight
        xs = [s for s, _ in sup] + [s for s, _ in extra]
        mass = weight / GRAVITY
        j_pitch, j_roll = _box_inertias(mass, max(xs) - min(xs) + 2 * BODY_OVERHANG)
        return BodySpec(mass, s_cg, j_pitch, j_roll, hinge)

    if tractor_groups == 0:
        bodies = [body_from(supports[0], [])]
    else:
        last = group_specs[tractor_groups - 1].axles
        wheelbase = 0.5 * (last[0].s + last[-1].s)
        s5 = wheelbase - FIFTH_WHEEL_LEAD
        # kingpin load R [N] that puts the tractor body's CG at c: (ΣP − R)·c = Σ P s − R·s5
        p_sum = sum(f for _, f in supports[0])
        moment = sum(s * f for s, f in supports[0])
        c = TRACTOR_CG_FRACTION * wheelbase
        r = (moment - p_sum * c) / (s5 - c)
        if not 0 < r < p_sum:
            raise ValueError(f"tractor_groups: with these axle loads the tractor's first {tractor_groups} group(s) cannot "
                             "carry a semitrailer (its centre of gravity would leave the wheelbase); give "
                             "tractor_groups = 0 (a rigid truck) or check the loads")
        bodies = [body_from(supports[0], [(s5, -r)]), body_from(supports[1], [(s5, r)], hinge=s5)]
    params = {"gross_weight": float(loads.sum()), "n_axles": float(n_ax)}
    return build_truck("axles", bodies, group_specs, half_track,
                       f"{n_ax}-axle truck from axle loads ({', '.join(kinds)}"
                       f"{'; articulated after group ' + str(tractor_groups) if tractor_groups else ''})", params)


def semitrailer_3s2() -> Vehicle:
    """Five-axle tractor–semitrailer (3-S2, FHWA class 9): steer axle and load-equalising
    tandem under the tractor, load-equalising tandem under the semitrailer, hinged at the fifth
    wheel; 13 DOF.

    Topology: VBI-2D's "typical 5-axle articulated truck" ``Vehicle_3A2_G_1_2_2`` (Cantero,
    VBI-2D user guide, §2.1: body 1 with 3 axles, articulation, body 2 with 2 axles; groups of
    1, 2, 2 axles, each group on one suspension), extended to left and right wheels.
    Numbers [public], from VBI-2D's five-axle vehicle (``E01_Example.m``, ``Vehicle_2A3``:
    DanielCanteroNTNU/VBI-2D, GPL-3.0), whole-axle values (per side: half):

    * tractor body 3100 kg, pitch inertia 5000 kg·m²; semitrailer body 20000 kg, 120000 kg·m²;
    * fifth wheel b1 = 3 m behind the tractor CG, semitrailer CG a2 = 5 m behind the fifth
      wheel; steer axle d1 = −1 m, drive group centre 3.5 m from the tractor CG; trailer group
      centre 3.2 m behind the semitrailer CG; axles 1.2 m apart within a group (VBI-2D's
      axles 3–5): axles at s = 0, 3.9, 5.1, 11.6, 12.8 m;
    * steer and drive axles: 750 kg, suspension 6e6 N/m and 1e4 N·s/m, tire 1.75e6 N/m
      (VBI-2D's axles 1–2); trailer axles: 1100 kg, 1e7 N/m, 2e4 N·s/m, tire 3.5e6 N/m (its
      axles 3–5); tire damping 0 (as VBI-2D).  A group's suspension is the sum of its axles'
      (as VBI-2D's grouped ``Vehicle_2A3_G_1_1_3``).

    [substitute]: bogie pitch inertia Σ m_axle·e² (axles as point masses at ±0.6 m);
    half-track 0.9 m; body roll inertias m(w² + h²)/12 with w = h = 2.5 m; axle and bogie roll
    inertia m·b².  Static axle loads (equilibrium, statically determinate) ≈ 39.5 / 44.8 /
    44.8 / 70.6 / 70.6 kN, gross 270.3 kN (27.55 t).  The length (12.8 m) is that of VBI-2D's
    vehicle, shorter than a typical US 3-S2 (≈ 17 m between the first and last axle).
    """
    s_tractor_cg = 1.0  # steer axle d1 = −1 m ahead of the tractor CG
    s5 = s_tractor_cg + 3.0
    s_trailer_cg = s5 + 5.0
    drive_c, trail_c = s_tractor_cg + 3.5, s_trailer_cg + 3.2
    e = 0.6

    def axle(s: float, mass: float, k_s: float, c_s: float, k_t: float) -> AxleSpec:
        return AxleSpec(s, mass, 0.5 * k_s, 0.5 * c_s, 0.5 * k_t, 0.0)

    steer = axle(0.0, 750.0, 6e6, 1e4, 1.75e6)
    drive = tuple(axle(drive_c + d, 750.0, 6e6, 1e4, 1.75e6) for d in (-e, e))
    trail = tuple(axle(trail_c + d, 1100.0, 1e7, 2e4, 3.5e6) for d in (-e, e))
    roll = (BODY_WIDTH**2 + BODY_HEIGHT**2) / 12.0  # roll inertia per kg [m²]
    bodies = [BodySpec(3100.0, s_tractor_cg, 5000.0, 3100.0 * roll),
              BodySpec(20000.0, s_trailer_cg, 120000.0, 20000.0 * roll, hinge=s5)]
    groups = [
        GroupSpec((steer,), 0),
        GroupSpec(drive, 0, (drive_c, 2 * 750.0 * e**2, 0.5 * 2 * 6e6, 0.5 * 2 * 1e4)),
        GroupSpec(trail, 1, (trail_c, 2 * 1100.0 * e**2, 0.5 * 2 * 1e7, 0.5 * 2 * 2e4)),
    ]
    return build_truck("3s2", bodies, groups, HALF_TRACK,
                       "five-axle tractor-semitrailer 3-S2 (VBI-2D's five-axle vehicle, Vehicle_3A2_G_1_2_2 layout)")
