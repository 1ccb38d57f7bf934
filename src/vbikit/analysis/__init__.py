"""Impact factor, static reference, response extraction, response plans."""
from vbikit.analysis.impact import ImpactFactor, impact_factor, static_modal_history
from vbikit.analysis.plan import ResponsePlan, ResponsePoint
from vbikit.analysis.response import (
    PointResponse,
    contact_loss,
    girder_responses,
    girder_summary,
    histories,
    history_table,
    plan_responses,
    point_entries,
    point_response,
    summary,
    summary_keys,
    summary_units,
)

__all__ = ["ImpactFactor", "PointResponse", "ResponsePlan", "ResponsePoint", "contact_loss",
           "girder_responses", "girder_summary", "histories", "history_table", "impact_factor", "plan_responses",
           "point_entries", "point_response", "static_modal_history", "summary", "summary_keys", "summary_units"]
