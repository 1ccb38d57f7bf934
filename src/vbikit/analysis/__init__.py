"""Impact factor, static reference, response extraction."""
from vbikit.analysis.impact import ImpactFactor, impact_factor, static_modal_history
from vbikit.analysis.response import (
    SUMMARY_KEYS,
    PointResponse,
    contact_loss,
    girder_responses,
    girder_summary,
    histories,
    history_units,
    point_response,
    summary,
    summary_units,
)

__all__ = ["SUMMARY_KEYS", "ImpactFactor", "PointResponse", "contact_loss", "girder_responses", "girder_summary", "histories", "history_units", "impact_factor",
           "point_response", "static_modal_history", "summary", "summary_units"]
