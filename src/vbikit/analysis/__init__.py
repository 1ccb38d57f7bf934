"""Impact factor, static reference, response extraction, response plans."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
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
        reduce_crossing,
        summary,
        summary_keys,
        summary_units,
    )

__all__ = ["ImpactFactor", "PointResponse", "ResponsePlan", "ResponsePoint", "contact_loss", "girder_responses",
           "girder_summary", "histories", "history_table", "impact_factor", "plan_responses", "point_entries",
           "point_response", "reduce_crossing", "static_modal_history", "summary", "summary_keys", "summary_units"]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.analysis.impact": ["ImpactFactor", "impact_factor", "static_modal_history"],
    "vbikit.analysis.plan": ["ResponsePlan", "ResponsePoint"],
    "vbikit.analysis.response": ["PointResponse", "contact_loss", "girder_responses", "girder_summary", "histories",
                                 "history_table", "plan_responses", "point_entries", "point_response", "reduce_crossing",
                                 "summary", "summary_keys", "summary_units"],
})
