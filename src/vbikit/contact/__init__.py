"""Tire contact models (single-point and the paper's multi-point) and vehicle contact points."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
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

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.contact.points": ["ContactPoints", "contact_points"],
    "vbikit.contact.tires": ["AASHTO_CONTACT_LENGTH", "DEFAULT_TIRE_RADIUS", "ContactLayout", "DiskTire", "MultiPointTire", "PointTire", "RigidDiskTire", "TireModel"],
})
