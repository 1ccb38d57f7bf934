"""Railway bridges: speed sweeps of trains (the trains themselves: vbikit.vehicle.trains), EN 1991-2 / EN 1990 dynamic checks."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.rail.codes import (
        ACCELERATION_LIMITS,
        DECK_DAMPING,
        additional_damping,
        code_damping,
        frequency_limit,
        lm71_peak,
        phi2,
        phi3,
        phi_irregularity,
        resonance_speeds,
    )
    from vbikit.rail.figures import plot_acceleration_envelopes
    from vbikit.rail.run import RailBudgetError, RailResult, run_rail
    from vbikit.rail.spec import RailSpec, RailSpecError, load_rail_spec, parse_rail_spec
    from vbikit.rail.sweep import speed_grid

__all__ = [
    "ACCELERATION_LIMITS",
    "DECK_DAMPING",
    "RailBudgetError",
    "RailResult",
    "RailSpec",
    "RailSpecError",
    "additional_damping",
    "code_damping",
    "frequency_limit",
    "lm71_peak",
    "load_rail_spec",
    "parse_rail_spec",
    "phi2",
    "phi3",
    "phi_irregularity",
    "plot_acceleration_envelopes",
    "resonance_speeds",
    "run_rail",
    "speed_grid",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.rail.codes": ["ACCELERATION_LIMITS", "DECK_DAMPING", "additional_damping", "code_damping", "frequency_limit",
                          "lm71_peak", "phi2", "phi3", "phi_irregularity", "resonance_speeds"],
    "vbikit.rail.figures": ["plot_acceleration_envelopes"],
    "vbikit.rail.run": ["RailBudgetError", "RailResult", "run_rail"],
    "vbikit.rail.spec": ["RailSpec", "RailSpecError", "load_rail_spec", "parse_rail_spec"],
    "vbikit.rail.sweep": ["speed_grid"],
})
