"""Impact factor, static reference, response extraction."""
from vbikit.analysis.impact import ImpactFactor, impact_factor, static_modal_history
from vbikit.analysis.response import (
    PointResponse,
    contact_loss,
    girder_responses,
    girder_summary,
    histories,
    point_response,
    summary,
)

__all__ = ["ImpactFactor", "PointResponse", "contact_loss", "girder_responses", "girder_summary", "histories", "impact_factor",
           "point_response", "static_modal_history", "summary"]
