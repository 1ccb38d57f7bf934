"""Multibody vehicle models (mass, damping, stiffness, wheels) and presets."""
from vbikit.vehicle.builder import VehicleBuilder
from vbikit.vehicle.model import GRAVITY, Vehicle, Wheel
from vbikit.vehicle.presets import (
    VEHICLE_PRESETS,
    hs20_44,
    moving_force,
    quarter_car,
    sprung_mass,
    two_axle_truck,
)

__all__ = [
    "GRAVITY",
    "VEHICLE_PRESETS",
    "Vehicle",
    "VehicleBuilder",
    "Wheel",
    "hs20_44",
    "moving_force",
    "quarter_car",
    "sprung_mass",
    "two_axle_truck",
]
