"""Test vehicles for drive-by monitoring (instrumented vehicles; the sensors are separate,
[`Sensor`][vbikit.driveby.Sensor]).

* ``test-cart``: the single-axle test vehicle of contact-point methods — one mass on one
  spring–dashpot standing on the surface (the ``sprung-mass`` preset with other defaults).
  [substitute] m = 120 kg, f_v = 3.2 Hz, undamped: a light towed cart, so that its mass ratio to a
  short-span bridge (25 m, 120 t) is 1e-3, the light-vehicle regime of Yang, Lin & Yau (2004),
  where the vehicle hardly changes the bridge's frequencies.
* ``two-axle-car``: a planar half-car (body heave and pitch, two axles with a tire each):
  [substitute] body 1200 kg, pitch inertia 1800 kg·m², centre of gravity 1.1 m behind the
  front axle, wheelbase 2.6 m; axles 40 kg; suspensions 30 / 35 kN/m with 2 / 2.5 kN·s/m;
  tires 200 kN/m, 100 N·s/m (two wheels lumped per axle).  Body heave ≈ 1.1 Hz, axle hop ≈ 12 Hz,
  typical passenger-car values.
* the tractor–semitrailers of ``vbikit.vehicle.presets`` (``hs20-44``, ``3s2``) as they are.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable

from vbikit.vehicle.builder import VehicleBuilder
from vbikit.vehicle.model import Vehicle
from vbikit.vehicle.presets import VEHICLE_PRESETS, sprung_mass


def sensor_cart(mass: float = 120.0, frequency_hz: float = 3.2, damping_ratio: float = 0.0) -> Vehicle:
    """Single-axle test cart (module docstring): k = m (2π f_v)², c = 2 ζ √(k m); named
    ``test-cart``, as the drive-by file names it (messages about its bodies and axles say so)."""
    k = mass * (2 * math.pi * frequency_hz) ** 2
    return dataclasses.replace(sprung_mass(mass, k, 2 * damping_ratio * math.sqrt(k * mass)), name="test-cart",
                               description="test cart: sprung mass (1 DOF)")


def two_axle_car() -> Vehicle:
    """Planar two-axle passenger car (module docstring); bodies ``body``, ``axle1``, ``axle2``."""
    vb = VehicleBuilder("two-axle-car")
    body = vb.body("body", 1200.0, 1.1, pitch_inertia=1800.0, pitch=True)
    for i, (s, ks, cs) in enumerate(((0.0, 30e3, 2e3), (2.6, 35e3, 2.5e3)), start=1):
        axle = vb.body(f"axle{i}", 40.0, s)
        vb.spring(body.point(s), axle.heave, ks, cs)
        vb.wheel(f"axle{i}", axle.heave, s, 0.0, 200e3, 100.0)
    return vb.build("two-axle passenger car, planar (substitute parameters)")


#: instrumented-vehicle models by name (besides every vehicle preset): name -> builder
DRIVEBY_VEHICLES: dict[str, Callable[..., Vehicle]] = {
    "test-cart": sensor_cart,
    "two-axle-car": two_axle_car,
}


def driveby_vehicle(name: str, **parameters) -> Vehicle:
    """A drive-by vehicle by name: ``DRIVEBY_VEHICLES`` or a ``vbikit.vehicle.presets`` preset."""
    if name in DRIVEBY_VEHICLES:
        return DRIVEBY_VEHICLES[name](**parameters)
    return VEHICLE_PRESETS[name].build(**parameters)
