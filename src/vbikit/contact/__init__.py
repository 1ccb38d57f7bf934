"""Tire contact models (single-point and the paper's multi-point) and vehicle contact points."""
from vbikit.contact.points import ContactPoints, contact_points
from vbikit.contact.tires import (
    AASHTO_CONTACT_LENGTH,
    DEFAULT_TIRE_RADIUS,
    ContactLayout,
    DiskTire,
    MultiPointTire,
    PointTire,
    RigidDiskTire,
    TireModel,
)

__all__ = [
    "AASHTO_CONTACT_LENGTH",
    "DEFAULT_TIRE_RADIUS",
    "ContactLayout",
    "ContactPoints",
    "DiskTire",
    "MultiPointTire",
    "PointTire",
    "RigidDiskTire",
    "TireModel",
    "contact_points",
]
