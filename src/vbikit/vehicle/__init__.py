"""Multibody vehicle models (mass, damping, stiffness, wheels) and presets."""
from vbikit.vehicle.axles import GROUP_KINDS, axle_truck, semitrailer_3s2
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
    "GROUP_KINDS",
    "VEHICLE_PRESETS",
    "Vehicle",
    "VehicleBuilder",
    "Wheel",
    "axle_truck",
    "hs20_44",
    "moving_force",
    "quarter_car",
    "semitrailer_3s2",
    "sprung_mass",
    "two_axle_truck",
]
