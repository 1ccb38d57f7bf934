"""Bridge presets: parameter sets from the paper, as beam stand-ins.

Until the 3D slab-on-girder model exists, the paper's bridges are available as single
Euler–Bernoulli beams with the whole cross-section lumped (full composite action).  Labels:

* [paper] span 9.16 / 16.76 / 39.62 m; roadway 9.75 m; deck 0.20 m; five girders at 2.13 m.
* [substitute] girder types (II for Bridges 1–2, VI for Bridge 3), E = 33 GPa for deck and
  girders (the composite estimate of domain-data §1), ρ = 2400 kg/m³, 2 % damping,
  no haunch, no diaphragms.  A beam cannot carry load to one girder: IM here is for the
  whole cross-section, not for Girder 4.
* [computed] f₁ ≈ 24.6 / 7.3 / 2.7 Hz (domain-data §1); tests check these.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.bridge.sections import AASHTO_GIRDERS, composite_beam_properties

#: [substitute] concrete modulus used for the lumped composite beams [Pa]
E_CONCRETE = 33e9
#: [substitute] concrete density [kg/m³]
RHO_CONCRETE = 2400.0
#: [substitute] default modal damping ratio [-]
DEFAULT_DAMPING = 0.02


def paper_beam(span: float, girder_type: str, n_modes: int = 10, damping_ratio: float = DEFAULT_DAMPING) -> EulerBernoulliBeam:
    """Whole-bridge composite beam of the paper's five-girder cross-section.

    [paper] roadway 9.75 m, deck 0.20 m, five girders; [substitute] AASHTO ``girder_type``,
    E = 33 GPa, ρ = 2400 kg/m³.
    """
    props = composite_beam_properties(
        AASHTO_GIRDERS[girder_type],
        n_girders=5,
        deck_width=9.75,
        deck_thickness=0.20,
        E_girder=E_CONCRETE,
        E_deck=E_CONCRETE,
        density=RHO_CONCRETE,
    )
    return EulerBernoulliBeam(
        span=span,
        EI=props.EI,
        mass_per_length=props.mass_per_length,
        damping_ratio=damping_ratio,
        n_modes=n_modes,
        neutral_axis_depth=props.neutral_axis_depth,
    )


@dataclass(frozen=True)
class BridgePreset:
    name: str
    description: str
    build: Callable[..., EulerBernoulliBeam]


BRIDGE_PRESETS: dict[str, BridgePreset] = {
    p.name: p
    for p in (
        BridgePreset(
            "paper-bridge-1-beam",
            "Bridge 1 of the paper (9.16 m [paper]) as one composite beam, Type II girders [substitute]",
            lambda **kw: paper_beam(9.16, "II", **kw),
        ),
        BridgePreset(
            "paper-bridge-2-beam",
            "Bridge 2 of the paper (16.76 m [paper]) as one composite beam, Type II girders [substitute]",
            lambda **kw: paper_beam(16.76, "II", **kw),
        ),
        BridgePreset(
            "paper-bridge-3-beam",
            "Bridge 3 of the paper (39.62 m [paper]) as one composite beam, Type VI girders [substitute]",
            lambda **kw: paper_beam(39.62, "VI", **kw),
        ),
    )
}
