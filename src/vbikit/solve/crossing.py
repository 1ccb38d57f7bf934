"""A crossing: one vehicle with one tire model driving over one bridge on one road.

The vehicle drives in +x.  At t = 0 its front axle is at x = −approach (on the approach
road) and it is in static equilibrium on the road (and deck, if any contact point is already
on it).  The crossing ends ``free_vibration`` seconds after the last contact point has left
the bridge (x = span).  Speed: v(t) = speed + acceleration · t (acceleration < 0 brakes); a
vehicle that comes to rest during the free vibration stays at rest.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from vbikit.bridge.base import ModalBridge
from vbikit.contact.points import ContactPoints, contact_points
from vbikit.contact.tires import PointTire, TireModel
from vbikit.road.profile import RoadProfile
from vbikit.vehicle.model import Vehicle

Integrator = Literal["rk4", "newmark"]
INTEGRATORS: tuple[str, ...] = ("rk4", "newmark")


@dataclass(frozen=True)
class Crossing:
    """Everything one coupled simulation needs.

    Parameters
    ----------
    bridge, vehicle, tire, road
        The composed models; ``road=None`` is a smooth road.
    road_right : RoadProfile, optional
        Profile under the contact points right of the vehicle centreline (lateral y < 0, the
        right wheel line); None = ``road`` under every wheel (the paper's assumption).
    speed : float
        Speed at t = 0 [m/s], > 0.
    acceleration : float
        Constant longitudinal acceleration [m/s²] (negative = braking); the vehicle must
        still move when its last axle leaves the bridge.
    approach : float
        Distance [m] the front axle travels before it reaches the bridge (≥ 0).
    free_vibration : float, optional
        Time [s] simulated after the last axle leaves; default one period of the first
        bridge mode.
    lateral_offset : float, optional
        y [m] of the vehicle centreline from the deck centreline (irrelevant for a beam); default
        the bridge's ``default_lateral_offset`` (as in scenarios; 0 for a beam).
    dt : float, optional
        Time step [s]; default chosen by :func:`vbikit.solve.timestep.choose_time_step`.
    integrator : {"rk4", "newmark"}
        The paper's classical Runge–Kutta or Newmark average acceleration.
    loss_of_contact : bool
        Tires cannot pull (default True, as real tires): a contact point whose spring would be
        in tension carries no force.  False gives the classical bilateral linear tire.  Disk
        tires are always unilateral (their patch is where they penetrate).
    """

    bridge: ModalBridge
    vehicle: Vehicle
    tire: TireModel = PointTire()
    road: RoadProfile | None = None
    speed: float = 20.0
    acceleration: float = 0.0
    approach: float = 10.0
    free_vibration: float | None = None
    lateral_offset: float | None = None
    dt: float | None = None
    integrator: Integrator = "rk4"
    loss_of_contact: bool = True
    road_right: RoadProfile | None = None

    def __post_init__(self) -> None:
        if self.lateral_offset is None:
            object.__setattr__(self, "lateral_offset", float(getattr(self.bridge, "default_lateral_offset", 0.0)))
        if not np.isfinite(self.lateral_offset):
            raise ValueError(f"crossing.lateral_offset must be finite, got {self.lateral_offset!r}")
        if not (np.isfinite(self.speed) and self.speed > 0):
            raise ValueError(f"crossing.speed must be > 0 m/s, got {self.speed!r}")
        if not np.isfinite(self.acceleration):
            raise ValueError("crossing.acceleration must be finite")
        if not (np.isfinite(self.approach) and self.approach >= 0):
            raise ValueError(f"crossing.approach must be >= 0 m, got {self.approach!r}")
        if self.free_vibration is not None and not (np.isfinite(self.free_vibration) and self.free_vibration >= 0):
            raise ValueError(f"crossing.free_vibration must be >= 0 s, got {self.free_vibration!r}")
        if self.dt is not None and not (np.isfinite(self.dt) and self.dt > 0):
            raise ValueError(f"crossing.dt must be > 0 s, got {self.dt!r}")
        if self.integrator not in INTEGRATORS:
            raise ValueError(f"crossing.integrator must be one of {INTEGRATORS}, got {self.integrator!r}")
        self._check_roads()

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
                    f"but this crossing needs x = {lo:.2f} … {hi:.2f} m (approach, vehicle length, span, free vibration)"
                )

    def with_road(self, road: RoadProfile | None, road_right: RoadProfile | None = None) -> "Crossing":
        """This crossing on other road profiles (checked like the constructor's; the contact
        points already computed are kept, which makes it cheap for a batch of roads)."""
        new = copy.copy(self)
        object.__setattr__(new, "road", road)
        object.__setattr__(new, "road_right", road_right)
        new._check_roads()
        return new

    # ------------------------------------------------------------ geometry & time
    @cached_property
    def contact(self) -> ContactPoints:
        """The tire model's contact points under every wheel."""
        return contact_points(self.vehicle, self.tire)

    @property
    def free_vibration_time(self) -> float:
        if self.free_vibration is not None:
            return float(self.free_vibration)
        return float(2 * np.pi / self.bridge.omega[0])

    @property
    def stop_time(self) -> float:
        """Time [s] at which a braking vehicle comes to rest (inf if it does not brake)."""
        return -self.speed / self.acceleration if self.acceleration < 0 else math.inf

    def front_position(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """x of the front axle [m] at time t [s] (a braking vehicle stays where it stopped)."""
        t = np.minimum(np.asarray(t, float), self.stop_time)
        return -self.approach + self.speed * t + 0.5 * self.acceleration * t**2

    def velocity(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """Vehicle speed [m/s] at time t [s] (zero once a braking vehicle has stopped)."""
        t = np.minimum(np.asarray(t, float), self.stop_time)
        return self.speed + self.acceleration * t

    def exit_time(self) -> float:
        """Time [s] when the rearmost contact point passes x = span."""
        distance = self.approach + self.bridge.span + float(self.contact.setback.max())
        a, v = self.acceleration, self.speed
        if abs(a) < 1e-12:
            return distance / v
        disc = v * v + 2 * a * distance
        if disc <= 0:
            stop = -v * v / (2 * a)
            raise ValueError(
                f"with crossing.acceleration = {a} m/s² the vehicle stops after {stop:.1f} m, before its last axle "
                f"leaves the bridge ({distance:.1f} m); use a smaller braking rate or a higher speed"
            )
        return (-v + math.sqrt(disc)) / a

    @property
    def duration(self) -> float:
        return self.exit_time() + self.free_vibration_time

    def road_extent(self) -> tuple[float, float]:
        """Range of x [m] the contact points touch during the crossing."""
        cp = self.contact
        t_end = self.duration
        x_end = float(self.front_position(t_end))  # motion is monotone: speed stays > 0 until t_end
        return -self.approach - float(cp.setback.max()), x_end - float(cp.setback.min())
