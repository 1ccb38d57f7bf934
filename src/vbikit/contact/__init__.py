"""Tire contact models (single-point and the paper's multi-point) and vehicle contact points."""
from vbikit.contact.points import ContactPoints, contact_points
from vbikit.contact.tires import AASHTO_CONTACT_LENGTH, MultiPointTire, PointTire, TireModel

__all__ = ["AASHTO_CONTACT_LENGTH", "ContactPoints", "MultiPointTire", "PointTire", "TireModel", "contact_points"]
