"""Impact factor, static reference, response extraction."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
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

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.analysis.impact": ["ImpactFactor", "impact_factor", "static_modal_history"],
    "vbikit.analysis.response": ["SUMMARY_KEYS", "PointResponse", "contact_loss", "girder_responses", "girder_summary", "histories", "history_units", "point_response", "summary", "summary_units"],
})
