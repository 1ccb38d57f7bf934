"""Tire contact models (single-point, the paper's multi-point, disks) by name, and vehicle contact points.

The tire models register themselves by scenario name ([`TIRE_MODELS`][vbikit.contact.registry.TIRE_MODELS]) when their module
is imported; a new model is one module (class + [`register_tire`][vbikit.contact.register_tire]) and one import line in
``vbikit.contact.registry``'s list of built-in modules (or, for a user's model, its own import).
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports
from vbikit.contact import tires as _builtin_tires  # noqa: F401  (registers the built-in tire models)

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.contact.base import ContactLayout, TireModel, TireParameters
    from vbikit.contact.points import ContactPoints, contact_points
    from vbikit.contact.registry import TIRE_MODELS, register_tire, tire_catalogue, tire_from_parameters, tire_model
    from vbikit.contact.tires import (
        AASHTO_CONTACT_LENGTH,
        DEFAULT_TIRE_RADIUS,
        DiskTire,
        MultiPointTire,
        PointTire,
        RigidDiskTire,
    )

__all__ = [
    "AASHTO_CONTACT_LENGTH",
    "DEFAULT_TIRE_RADIUS",
    "TIRE_MODELS",
    "ContactLayout",
    "ContactPoints",
    "DiskTire",
    "MultiPointTire",
    "PointTire",
    "RigidDiskTire",
    "TireModel",
    "TireParameters",
    "contact_points",
    "register_tire",
    "tire_catalogue",
    "tire_from_parameters",
    "tire_model",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.contact.points": ["ContactPoints", "contact_points"],
    "vbikit.contact.registry": ["TIRE_MODELS", "register_tire", "tire_catalogue", "tire_from_parameters", "tire_model"],
    "vbikit.contact.base": ["ContactLayout", "TireModel", "TireParameters"],
    "vbikit.contact.tires": ["AASHTO_CONTACT_LENGTH", "DEFAULT_TIRE_RADIUS", "DiskTire", "MultiPointTire", "PointTire",
                             "RigidDiskTire"],
})
