"""Tire contact models (single-point, the paper's multi-point, disks) by name, and vehicle contact points.

The tire models register themselves by scenario name (:data:`TIRE_MODELS`) when their module
is imported; a new model is one module (class + :func:`register_tire`) and one import line here.
"""
from vbikit.contact.points import ContactPoints, contact_points
from vbikit.contact.registry import TIRE_MODELS, register_tire, tire_catalogue, tire_from_parameters, tire_model
from vbikit.contact.tires import (
    AASHTO_CONTACT_LENGTH,
    DEFAULT_TIRE_RADIUS,
    ContactLayout,
    DiskTire,
    MultiPointTire,
    PointTire,
    RigidDiskTire,
    TireModel,
    TireParameters,
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
