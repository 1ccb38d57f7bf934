"""A crossing: one or several vehicles, each with its tire model and motion, driving over one
bridge on one road.

Every vehicle is a [`VehicleMotion`][vbikit.solve.VehicleMotion]: its tire, lateral offset, direction (+x or −x), speed,
acceleration and entry time T_v, the time its front axle passes its entry support (x = 0 driving
+x, x = span driving −x).  Its travel s_v(t) [m] is the distance its front axle has driven past
that support, s_v = v_v τ + a_v τ²/2 with τ = t − T_v (v_v: its speed at entry; a braking
vehicle stays where it stopped), so a contact point at ``setback`` behind its front axle is at
x = s_v − setback (+x) or x = span − s_v + setback (−x).  The run starts at the latest time
every vehicle is at least ``approach`` before its entry (each in static equilibrium there) and
ends ``free_vibration`` after the last contact point has left the bridge (x = span; on a skew
deck the far end of its own wheel track, span + y tan θ); times are on the vehicles' clock
(t = 0 when ``entry_time`` = 0), so the run may start at t < 0.  The vehicles' degrees of
freedom sit side by side (``vbikit.vehicle.CombinedVehicle``): they interact only through the
bridge.

One vehicle (``Crossing(bridge, vehicle, …)``) is the same: ``crossing.vehicles`` is one
VehicleMotion driving +x whose front axle is at x = −approach at t = 0, when the run starts,
with speed ``speed`` + ``acceleration`` · t; ``crossing.vehicle`` is that vehicle itself (its
own wheel and DOF names) and [`Crossing.single`][vbikit.solve.Crossing.single] is True.
"""
from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable, Hashable, Optional, TypeVar

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import Kept
from vbikit._limits import MAX_RUN_IN
from vbikit.bridge.base import ModalBridge
from vbikit.contact.points import ContactPoints, contact_points, stack_contact_points
from vbikit.contact.tires import PointTire, TireModel
from vbikit.road.profile import RoadProfile
from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR, get_integrator
from vbikit.vehicle.model import CombinedVehicle, Vehicle, combine_vehicles

DIRECTIONS: tuple[str, ...] = ("+x", "-x")
#: what a crossing's automatic step must resolve (``Crossing.resolve``): "effects" (every result) or "deflections"
#: (deflections and tire forces only: the exact integrator's coarser first-period term,
#: ``vbikit.solve.timestep.EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD``)
RESOLVES: tuple[str, ...] = ("effects", "deflections")


def require_every_result(resolve: str, why: str, error: type[ValueError] = ValueError, where: str = "") -> None:
    """Refuse a step for deflections only (``resolve`` ≠ "effects", ``Crossing.resolve``) where a run needs
    the step for every result, ``why`` saying what needs it: ``error`` (a ValueError) naming the key, its value
    and what to do (leave the key out, ``where``: of which file or table)."""
    if resolve != "effects":
        raise error(f'crossing.resolve = "{resolve}": {why}; leave crossing.resolve out{where}')
T = TypeVar("T")

#: values a crossing keeps of its own (``Crossing.kept``): at most this many
KEPT_PER_CROSSING = 16
#: the kinds of kept values that do not depend on the road (``Crossing.with_road`` keeps them)
ROAD_FREE_KINDS = frozenset({"grid", "kernel_data", "shapes"})


#: contact points per (vehicle, tire) object pair, each entry holding the pair (so that its ids stay
#: its own): the crossings of one vehicle on one tire model share them (vehicles and tires are
#: immutable); shared, not to be written
_CONTACTS: "Kept[tuple[int, int], tuple[Vehicle, TireModel, ContactPoints]]" = Kept(64)


def _contact_points(vehicle: Vehicle, tire: TireModel) -> ContactPoints:
    """``contact_points(vehicle, tire)``, made once per vehicle and tire object (``_CONTACTS``)."""
    return _CONTACTS.get((id(vehicle), id(tire)), lambda: (vehicle, tire, contact_points(vehicle, tire)))[2]


@dataclass(frozen=True)
class VehicleMotion:
    """One vehicle of a crossing and its motion (module docstring).

    Parameters
    ----------
    vehicle : Vehicle
    speed : float
        Speed [m/s] when its front axle passes its entry support, > 0.
    acceleration : float
        Constant acceleration [m/s²] (negative brakes); it must still move when its last axle
        leaves the bridge, and have moved from the start of the run.
    direction : {"+x", "-x"}
    entry_time : float
        Time [s] its front axle passes its entry support (x = 0 for +x, x = span for −x).
    lateral_offset : float, optional
        y [m] of its centreline from the deck centreline (positive left of +x); default the
        bridge's ``default_lateral_offset`` (0 for a beam).  A vehicle driving −x has its own
        left wheels at y = lateral_offset − (their y on the vehicle).
    tire : TireModel, optional
        Its tire model (default: the crossing's ``tire``).
    reference : tuple of float, optional
        The state the motion is evaluated from, (t_ref [s], s_ref [m], v_ref [m/s]):
        s = s_ref + v_ref τ + a τ²/2 with τ = t − t_ref; default the entry
        (``entry_time``, 0, ``speed``).  A one-vehicle crossing refers its motion to its start
        (0, −approach, speed at t = 0), so that it is that of its own inputs.
    """

    vehicle: Vehicle
    speed: float = 20.0
    acceleration: float = 0.0
    direction: str = "+x"
    entry_time: float = 0.0
    lateral_offset: Optional[float] = None
    tire: Optional[TireModel] = None
    reference: Optional[tuple[float, float, float]] = field(default=None, repr=False)

    @property
    def _ref(self) -> tuple[float, float, float]:
        return (self.entry_time, 0.0, self.speed) if self.reference is None else self.reference

    @property
    def sign(self) -> float:
        """+1 driving +x, −1 driving −x."""
        return 1.0 if self.direction == "+x" else -1.0

    @property
    def stop_time(self) -> float:
        """τ [s] after the reference time at which a braking vehicle comes to rest (inf if it does
        not brake; after entry unless a reference state is given)."""
        return -self._ref[2] / self.acceleration if self.acceleration < 0 else math.inf

    def travel(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """s_v [m]: distance of the front axle past its entry support at time t [s]."""
        t_ref, s_ref, v_ref = self._ref
        tau = np.minimum(np.asarray(t, float) - t_ref, self.stop_time)
        return s_ref + v_ref * tau + 0.5 * self.acceleration * tau**2

    def velocity(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """Speed [m/s] at time t [s] (zero once a braking vehicle has stopped)."""
        t_ref, _, v_ref = self._ref
        tau = np.minimum(np.asarray(t, float) - t_ref, self.stop_time)
        return v_ref + self.acceleration * tau

    def _travel_at(self, t: float) -> float:
        """``travel`` at one time t [s], as a float (the same arithmetic: τ² as τ·τ, as numpy squares)."""
        t_ref, s_ref, v_ref = self._ref
        tau = min(float(t) - t_ref, self.stop_time)
        return s_ref + v_ref * tau + 0.5 * self.acceleration * (tau * tau)

    def _speed_at(self, t: float) -> float:
        """``velocity`` at one time t [s], as a float (the same arithmetic)."""
        t_ref, _, v_ref = self._ref
        return v_ref + self.acceleration * min(float(t) - t_ref, self.stop_time)

    def time_at(self, travel: float) -> float:
        """Time [s] its front axle has travel ``travel`` [m] (NaN if it never gets there)."""
        t_ref, s_ref, v = self._ref
        a, distance = self.acceleration, travel - s_ref
        if abs(a) < 1e-12:
            return t_ref + distance / v
        disc = v * v + 2 * a * distance
        if disc < 0:
            return math.nan
        return t_ref + (-v + math.sqrt(disc)) / a

    def times_at(self, travel: NDArray[np.float64]) -> NDArray[np.float64]:
        """``time_at`` of every travel in an array [m] (the same arithmetic element by element)."""
        t_ref, s_ref, v = self._ref
        travel = np.asarray(travel, float)
        return _times_at(*np.broadcast_arrays(t_ref, s_ref, v, self.acceleration, travel))


def _times_at(t_ref, s_ref, v, a, travel) -> NDArray[np.float64]:
    """``VehicleMotion.time_at`` element by element for arrays that broadcast together (each element its own
    reference state (t_ref [s], s_ref [m], v [m/s]), acceleration a [m/s²] and travel [m]): the
    same arithmetic, t_ref + (s − s_ref)/v where |a| < 1e-12, else the root of
    s = s_ref + v τ + a τ²/2, t_ref + (−v + √(v² + 2a(s − s_ref)))/a (NaN where it never gets there);
    a None: every |a| < 1e-12."""
    distance = travel - s_ref
    out = np.asarray(t_ref + distance / v)
    if a is None:  # known: every |a| < 1e-12
        return out
    bent = np.abs(a) >= 1e-12
    if bent.any():
        t_ref, v, a, bent = (np.broadcast_to(z, out.shape) for z in (t_ref, v, a, bent))
        d, vb, ab = distance[bent], v[bent], a[bent]
        disc = vb * vb + 2 * ab * d
        with np.errstate(invalid="ignore"):
            out[bent] = np.where(disc < 0, np.nan, t_ref[bent] + (-vb + np.sqrt(disc)) / ab)
    return out


@dataclass(frozen=True)
class Crossing:
    """Everything one coupled simulation needs.

    Parameters
    ----------
    bridge : ModalBridge
        The bridge, reduced to modes.
    vehicle : Vehicle, optional
        One vehicle (or give ``vehicles`` instead).
    tire : TireModel
        The tire model of ``vehicle`` (default a point tire).
    road : RoadProfile, optional
        The road profile; None is a smooth road.
    road_right : RoadProfile, optional
        Profile under the contact points right of the vehicle centreline (lateral y < 0, the
        right wheel line); None = ``road`` under every wheel (the paper's assumption).
    speed : float
        One vehicle: its speed at t = 0 [m/s], > 0.
    acceleration : float
        One vehicle: its constant longitudinal acceleration [m/s²] (negative = braking); the
        vehicle must still move when its last axle leaves the bridge.
    approach : float
        Distance [m] every front axle travels before it reaches the bridge (≥ 0).
    free_vibration : float, optional
        Time [s] simulated after the last axle leaves; default one period of the first
        bridge mode.
    lateral_offset : float, optional
        One vehicle: y [m] of its centreline from the deck centreline (irrelevant for a beam);
        default the bridge's ``default_lateral_offset`` (as in scenarios; 0 for a beam).
    dt : float, optional
        Time step [s]; default chosen by [`vbikit.solve.timestep.choose_time_step`][vbikit.solve.choose_time_step].
    integrator : str
        A registered integrator's name ([`vbikit.solve.integrators.INTEGRATORS`][vbikit.solve.integrators.INTEGRATORS]).  "exact"
        (default): every bridge mode stepped by its exact transition with the modal load linear
        over the step, the vehicle by Newmark average acceleration, coupled through the
        contact forces at the end of each step (docs/theory.md); "rk4": the paper's classical
        Runge–Kutta; "newmark": Newmark average acceleration for bridge and vehicle alike.
    loss_of_contact : bool
        Tires cannot pull (default True, as real tires): a contact point whose spring would be
        in tension carries no force.  False gives the classical bilateral linear tire.  Disk
        tires are always unilateral (their patch is where they penetrate).
    vehicles : tuple of VehicleMotion
        Several vehicles with their motion (instead of ``vehicle``); for one ``vehicle`` it
        becomes that vehicle's motion from ``speed``, ``acceleration``, ``approach``,
        ``lateral_offset`` and ``tire``.
    run_in : float
        Road [m] the vehicles drive alone before the run starts (``vbikit.solve.run_in``; ≥ 0, default
        0: the run starts them at rest): they start from the state reached over it from rest, as if
        the approach were that much longer, without the coupled steps over it (any integrator; no
        contact point may be on the deck at the start).
    resolve : str
        What the automatic step must resolve (``RESOLVES``; a given ``dt`` is taken as it is): "effects"
        (default) every result — deflections, velocities, accelerations, strains, moments, shears,
        reactions — within the automatic step's accuracy bound; "deflections" only the deck's deflections
        and the tire forces (not accelerations, the vehicles' included): the exact integrator then takes 50
        steps per first bridge period instead of 100 where it holds the wheel loads quadratic (its other
        terms unchanged; ``vbikit.solve.timestep.implicit_time_step``).  A study whose outputs are all
        deflections sets it (``vbikit.outputs.outputs_resolve``); a random-vibration run refuses it.
    """

    bridge: ModalBridge
    vehicle: Optional[Vehicle] = None
    tire: TireModel = PointTire()
    road: RoadProfile | None = None
    speed: float = 20.0
    acceleration: float = 0.0
    approach: float = 10.0
    free_vibration: float | None = None
    lateral_offset: float | None = None
    dt: float | None = None
    integrator: str = DEFAULT_INTEGRATOR
    loss_of_contact: bool = True
    road_right: RoadProfile | None = None
    vehicles: tuple[VehicleMotion, ...] = ()
    run_in: float = 0.0
    resolve: str = "effects"

    def __post_init__(self) -> None:
        if self.lateral_offset is None:
            object.__setattr__(self, "lateral_offset", float(self.bridge.default_lateral_offset))
        if not math.isfinite(self.lateral_offset):
            raise ValueError(f"crossing.lateral_offset must be finite, got {self.lateral_offset!r}")
        if not self.vehicles and self.vehicle is None:
            raise ValueError("a crossing needs a vehicle (or vehicles=(VehicleMotion(…), …))")
        if not (math.isfinite(self.speed) and self.speed > 0):
            raise ValueError(f"crossing.speed must be > 0 m/s, got {self.speed!r}")
        if not math.isfinite(self.acceleration):
            raise ValueError("crossing.acceleration must be finite")
        if not (math.isfinite(self.approach) and self.approach >= 0):
            raise ValueError(f"crossing.approach must be >= 0 m, got {self.approach!r}")
        if not (math.isfinite(self.run_in) and 0 <= self.run_in <= MAX_RUN_IN):
            raise ValueError(f"crossing.run_in must be 0 … {MAX_RUN_IN:g} m, got {self.run_in!r}")
        if self.free_vibration is not None and not (np.isfinite(self.free_vibration) and self.free_vibration >= 0):
            raise ValueError(f"crossing.free_vibration must be >= 0 s, got {self.free_vibration!r}")
        if self.dt is not None and not (np.isfinite(self.dt) and self.dt > 0):
            raise ValueError(f"crossing.dt must be > 0 s, got {self.dt!r}")
        get_integrator(self.integrator)  # ValueError listing the registered names
        if self.resolve not in RESOLVES:
            raise ValueError(f"crossing.resolve must be one of {', '.join(map(repr, RESOLVES))}, got {self.resolve!r}")
        if self.vehicle is not None and not isinstance(self.vehicle, CombinedVehicle):
            self._init_single()
        else:
            self._init_vehicles()
        self._check_roads()

    def _init_single(self) -> None:
        """One vehicle: its motion from the crossing's own speed, acceleration, approach and
        lateral offset, referred to t = 0 (front axle at x = −approach)."""
        if any(m.reference is None for m in self.vehicles):  # the motion a copy of this crossing carries is rebuilt
            raise ValueError("give vehicle (one vehicle) or vehicles (several, with their motion), not both")
        a, v, d = self.acceleration, self.speed, self.approach
        motion = VehicleMotion(self.vehicle, v, a, "+x", 0.0, self.lateral_offset, None, (0.0, -d, v))
        entry = motion.time_at(0.0)
        if not math.isnan(entry):  # its entry (it may stop before: exit_time, duration and simulate raise)
            motion = dataclasses.replace(motion, speed=motion._speed_at(entry), entry_time=entry)
        object.__setattr__(self, "vehicles", (motion,))

    def _init_vehicles(self) -> None:
        default = float(self.bridge.default_lateral_offset)
        object.__setattr__(self, "vehicles", tuple(
            dataclasses.replace(m, lateral_offset=default) if isinstance(m, VehicleMotion) and m.lateral_offset is None
            else m for m in self.vehicles))
        for i, m in enumerate(self.vehicles):
            if not isinstance(m, VehicleMotion):
                raise ValueError(f"vehicles[{i + 1}]: expected a VehicleMotion, got {type(m).__name__}")
            if not (math.isfinite(m.speed) and m.speed > 0):
                raise ValueError(f"vehicles[{i + 1}].speed must be > 0 m/s, got {m.speed!r}")
            if not math.isfinite(m.acceleration):
                raise ValueError(f"vehicles[{i + 1}].acceleration must be finite")
            if m.direction not in DIRECTIONS:
                raise ValueError(f"vehicles[{i + 1}].direction must be +x or -x, got {m.direction!r}")
            if not math.isfinite(m.entry_time) or not math.isfinite(m.lateral_offset):
                raise ValueError(f"vehicles[{i + 1}]: entry_time and lateral_offset must be finite")
        object.__setattr__(self, "vehicle", combine_vehicles([m.vehicle for m in self.vehicles]))
        start = self.start_time
        for i, m in enumerate(self.vehicles):
            if math.isnan(m.time_at(-self.approach)) or m._speed_at(start) <= 0:
                raise ValueError(f"vehicles[{i + 1}].acceleration: accelerating at {m.acceleration} m/s² to "
                                 f"{m.speed} m/s at its entry, the vehicle would not be moving {self.approach} m "
                                 "before its entry at the start of the run; use a smaller acceleration or entry speed")
        self.exit_time()  # raises for a vehicle that stops on the bridge

    @property
    def single(self) -> bool:
        """True for a crossing built with ``vehicle=`` (one vehicle; reports keep its own layout:
        its own wheel names, top-level speed and lateral offset), False with ``vehicles=``."""
        return not isinstance(self.vehicle, CombinedVehicle)

    @property
    def n_vehicles(self) -> int:
        return len(self.vehicles)

    def _check_roads(self) -> None:
        if self.road_right is not None and self.road is None:
            raise ValueError("a right wheel-line profile (road_right) needs a road profile for the left line")
        for road in (self.road, self.road_right):
            if road is None:
                continue
            lo, hi = self.road_extent()
            if not road.covers(lo, hi):
                raise ValueError(
                    f"road profile '{road.label}' covers x = {road.x[0]:.2f} … {road.x[-1]:.2f} m "
                    f"but this crossing needs x = {lo:.2f} … {hi:.2f} m (approach, {'run-in, ' if self.run_in > 0 else ''}"
                    "vehicle length, span, free vibration): give a longer road (road.length for a random one)"
                )

    def with_road(self, road: RoadProfile | None, road_right: RoadProfile | None = None) -> "Crossing":
        """This crossing on other road profiles (checked like the constructor's; the contact
        points already computed and the kept values that do not depend on the road
        (``ROAD_FREE_KINDS``: time grids, kernel data) are kept, which makes it cheap for a batch
        of roads)."""
        new = copy.copy(self)  # without the kept values (__getstate__)
        object.__setattr__(new, "road", road)
        object.__setattr__(new, "road_right", road_right)
        new._check_roads()
        old = self.__dict__.get("_kept")
        if old is not None:
            for key, value in old.items():
                if key[0] in ROAD_FREE_KINDS:
                    new.kept(key[0], key[1], lambda v=value: v)
        return new

    def kept(self, kind: str, key: Hashable, make: Callable[[], T]) -> T:
        """The value of ``kind`` for ``key`` derived from this crossing, made by ``make()`` the
        first time and kept with the crossing (``KEPT_PER_CROSSING`` at most): a crossing is
        immutable, so a run of the same crossing again reuses its plan, time grid, kernel data and
        static start (``vbikit.solve.simulate``).  A crossing with any other input is another
        object, with nothing kept; ``with_road`` keeps only the ``ROAD_FREE_KINDS``; copies and
        pickles carry nothing kept.  Kept values are shared by every later run: not to be written."""
        store = self.__dict__.get("_kept")
        if store is None:
            store = Kept(KEPT_PER_CROSSING)
            object.__setattr__(self, "_kept", store)
        return store.get((kind, key), make)

    def __getstate__(self) -> dict:
        """The crossing's state for copies and pickles, without its kept values (``kept``)."""
        state = dict(self.__dict__)
        state.pop("_kept", None)
        return state

    # ------------------------------------------------------------ geometry & time
    @cached_property
    def contact(self) -> ContactPoints:
        """The tire model's contact points under every wheel (several vehicles: each with its
        own tire, stacked in vehicle order)."""
        parts = [_contact_points(m.vehicle, m.tire or self.tire) for m in self.vehicles]
        # one vehicle: its own points (stacking one part gives the same arrays: no shift, no padding)
        return parts[0] if len(parts) == 1 else stack_contact_points(parts, self.vehicle.dof_offsets)

    @cached_property
    def point_vehicle(self) -> NDArray[np.int64]:
        """Index of the vehicle of every contact point."""
        wheels = [len(m.vehicle.wheels) for m in self.vehicles]
        wheel_vehicle = np.repeat(np.arange(len(self.vehicles)), wheels)
        return wheel_vehicle[self.contact.wheel].astype(np.int64)

    def point_kinematics(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Per contact point: ``origin`` [m] and ``direction`` (±1) of x_p = origin + direction·s_v,
        and its deck y [m] (the vehicle's lateral offset plus its own y, mirrored driving −x)
        (computed once; fresh copies)."""
        return tuple(a.copy() for a in self._kinematics)  # type: ignore[return-value]

    @cached_property
    def _kinematics(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """``point_kinematics`` (kept: not to be written)."""
        cp = self.contact
        veh = self.point_vehicle
        sign = np.array([m.sign for m in self.vehicles])[veh]
        offset = np.array([m.lateral_offset for m in self.vehicles])[veh]
        origin = np.where(sign > 0, -cp.setback, self.bridge.span + cp.setback)
        return origin, sign, offset + sign * cp.lateral

    def times_at(self, travel: NDArray[np.float64], vehicle: NDArray[np.int64]) -> NDArray[np.float64]:
        """Time [s] vehicle ``vehicle[i]``'s front axle has travel ``travel[i]`` [m] past its entry
        support (NaN if it never gets there; ``vehicle`` broadcasts against ``travel``):
        ``VehicleMotion.times_at`` of all vehicles in one pass (the same arithmetic element by element)."""
        t_ref, s_ref, v, a, _ = self._motion_refs
        curved = any(abs(m.acceleration) >= 1e-12 for m in self.vehicles)
        return _times_at(t_ref[vehicle], s_ref[vehicle], v[vehicle], a[vehicle] if curved else None,
                         np.asarray(travel, float))

    @cached_property
    def _motion_refs(self) -> NDArray[np.float64]:
        """Per vehicle (columns): t_ref [s], s_ref [m], v_ref [m/s] of its reference state, its
        acceleration [m/s²] and ``stop_time`` [s] (rows)."""
        return np.array([(*m._ref, m.acceleration, m.stop_time) for m in self.vehicles], float).T

    def travel(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """s_v(t) [m]: every vehicle's travel past its entry support, shape (n_t, n_vehicles)
        (``VehicleMotion.travel`` of every vehicle at once: the same arithmetic element by element)."""
        t = np.atleast_1d(np.asarray(t, float))
        if t.ndim != 1:
            return np.stack([m.travel(t) for m in self.vehicles], axis=1)
        t_ref, s_ref, v_ref, a, stop = self._motion_refs
        tau = np.minimum(t[:, None] - t_ref, stop)
        return s_ref + v_ref * tau + 0.5 * a * tau**2

    def travel_speed(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """ds_v/dt [m/s] of every vehicle, shape (n_t, n_vehicles)."""
        t = np.atleast_1d(np.asarray(t, float))
        if t.ndim != 1:
            return np.stack([m.velocity(t) for m in self.vehicles], axis=1)
        t_ref, _, v_ref, a, stop = self._motion_refs  # (every vehicle's ``velocity`` at once: the same arithmetic)
        return v_ref + a * np.minimum(t[:, None] - t_ref, stop)

    def front_positions(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """x [m] of every vehicle's front axle, shape (n_t, n_vehicles)."""
        s = self.travel(t)
        sign = np.array([m.sign for m in self.vehicles])
        return np.where(sign > 0, s, self.bridge.span - s)

    @property
    def start_time(self) -> float:
        """Time [s] the run starts: the latest time every vehicle is at least ``approach`` before
        its entry support (0 for one vehicle; computed once, like ``exit_time``)."""
        known = self.__dict__.get("_start_time")
        if known is None:
            known = float(min(m.time_at(-self.approach) for m in self.vehicles)) + 0.0
            object.__setattr__(self, "_start_time", known)
        return known

    @property
    def max_speed(self) -> float:
        """Highest speed [m/s] of any vehicle during the run (computed once, like ``exit_time``)."""
        known = self.__dict__.get("_max_speed")
        if known is None:  # constant accelerations: each vehicle's top speed is at the start or the end
            start = self.start_time
            end = start + self.duration
            known = max(max(m._speed_at(start), m._speed_at(end)) for m in self.vehicles)
            object.__setattr__(self, "_max_speed", known)
        return known

    @property
    def free_vibration_time(self) -> float:
        if self.free_vibration is not None:
            return float(self.free_vibration)
        return float(2 * np.pi / self.bridge.omega[0])

    def exit_time(self) -> float:
        """Time [s] when the last contact point leaves the deck: each passes x = span (on a skew deck
        the far end of its own wheel track, at least the deck's far corner) driving +x, x = 0 driving −x
        (computed once: a crossing is immutable, and ``with_road`` keeps its vehicles)."""
        known = self.__dict__.get("_exit_time")
        if known is None:
            known = self._exit_time_of_points()
            object.__setattr__(self, "_exit_time", known)
        return known

    def _exit_time_of_points(self) -> float:
        last = -math.inf
        for i, (m, distance) in enumerate(zip(self.vehicles, self._leaving_distances())):
            t = m.time_at(distance)
            if math.isnan(t) or (m.acceleration < 0 and t - m._ref[0] >= m.stop_time):
                t_ref, s_ref, v_ref = m._ref
                stop = v_ref**2 / (-2 * m.acceleration)
                if self.single:
                    raise ValueError(
                        f"with crossing.acceleration = {m.acceleration} m/s² the vehicle stops after {stop:.1f} m, before "
                        f"its last axle leaves the bridge ({distance - s_ref:.1f} m); use a smaller braking rate or a "
                        "higher speed")
                raise ValueError(
                    f"vehicles[{i + 1}].acceleration: with {m.acceleration} m/s² the vehicle stops {stop:.1f} m after its "
                    f"entry, before its last axle leaves the bridge ({distance:.1f} m); use a smaller braking rate "
                    "or a higher speed")
            last = max(last, t)
        return last

    def _leaving_distances(self) -> list[float]:
        """``leaving_distance`` of every vehicle (its own points and direction), all points in one pass (the
        same numbers: each point's reach as there, the largest of each vehicle's)."""
        veh = self.point_vehicle
        counts = np.bincount(veh, minlength=len(self.vehicles))
        if veh.size == 0 or not counts.all() or np.any(np.diff(veh) < 0):  # (a vehicle without points; unsorted)
            return [self.leaving_distance(np.flatnonzero(veh == i), m.sign) for i, m in enumerate(self.vehicles)]
        first = np.concatenate([[0], np.cumsum(counts)[:-1]])
        return [float(d) for d in np.maximum.reduceat(self._reaches(np.arange(veh.size), self._kinematics[1]), first)]

    def leaving_distance(self, points: NDArray[np.int64], sign: float) -> float:
        """Travel [m] from the entry support (x = 0 driving +x, x = span driving −x) until the contact
        points ``points`` of a vehicle have all left the deck: each its own track's far end (span +
        y tan θ driving +x, y tan θ driving −x, y its deck y), and at least the deck's far corner
        (``deck_extent``), plus its setback."""
        return float(np.max(self._reaches(points, sign)))

    def _reaches(self, points: NDArray[np.int64], sign: float | NDArray[np.float64]) -> NDArray[np.float64]:
        """Each of the contact points ``points``' travel [m] until it has left the deck driving ``sign``
        (one, or one per point): its own track's far end, at least the deck's far corner, plus its setback
        (``leaving_distance``)."""
        _, _, y = self._kinematics
        span = self.bridge.span
        start = -self.bridge.span_coordinate(np.zeros(len(points)), y[points])  # x of each track's entry support
        near, far = self.bridge.deck_extent
        reach = np.where(np.asarray(sign) > 0, np.maximum(start + span, far), np.maximum(span - start, span - near))
        return reach + self.contact.setback[points]

    @property
    def duration(self) -> float:
        """Length [s] of the run (from ``start_time``)."""
        return self.exit_time() + self.free_vibration_time - self.start_time

    def road_extent(self) -> tuple[float, float]:
        """Range of x [m] the contact points touch during the crossing (computed once, like ``exit_time``)."""
        known = self.__dict__.get("_road_extent")
        if known is None:
            origin, sign, _ = self._kinematics
            ends = (self.start_time, self.start_time + self.duration)
            s = np.array([[m._travel_at(t) for m in self.vehicles] for t in ends])[:, self.point_vehicle]
            if self.run_in > 0 and any(m.vehicle.n_dof for m in self.vehicles):  # the run-in's road behind the
                # start (moving forces have none to drive): each vehicle at its start speed (run_in)
                v0 = np.array([m._speed_at(ends[0]) for m in self.vehicles])
                back = (self.run_in + 1.0) * v0 / v0.min()  # (the slowest drives run_in; a step's margin)
                s = np.vstack([s, s[0] - back[self.point_vehicle]])
            x = origin + sign * s  # travel is monotone: the extremes are at the start and the end
            known = (float(x.min()), float(x.max()))
            object.__setattr__(self, "_road_extent", known)
        return known
