"""Bridge models reduced to modes (the modal-bridge interface and its optional capabilities, the
Euler–Bernoulli beam, the continuous beam, the slab-on-girder grillage deck, a stiffness-scaled
bridge, imported modes, presets)."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.bridge.base import DescribesModes, GirderDeck, HasLoadEffects, ModalBridge
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.bridge.continuous import ContinuousBeam
    from vbikit.bridge.girder_deck import SlabOnGirderBridge
    from vbikit.bridge.presets import BRIDGE_PRESETS, cypress_bayou, paper_beam, paper_deck
    from vbikit.bridge.scaled import ScaledBridge
    from vbikit.bridge.sections import (
        AASHTO_GIRDERS,
        GirderSection,
        composite_beam_properties,
    )

__all__ = [
    "AASHTO_GIRDERS",
    "BRIDGE_PRESETS",
    "ContinuousBeam",
    "DescribesModes",
    "EulerBernoulliBeam",
    "GirderDeck",
    "GirderSection",
    "HasLoadEffects",
    "ModalBridge",
    "ScaledBridge",
    "SlabOnGirderBridge",
    "composite_beam_properties",
    "cypress_bayou",
    "paper_beam",
    "paper_deck",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.bridge.base": ["DescribesModes", "GirderDeck", "HasLoadEffects", "ModalBridge"],
    "vbikit.bridge.beam": ["EulerBernoulliBeam"],
    "vbikit.bridge.continuous": ["ContinuousBeam"],
    "vbikit.bridge.girder_deck": ["SlabOnGirderBridge"],
    "vbikit.bridge.presets": ["BRIDGE_PRESETS", "cypress_bayou", "paper_beam", "paper_deck"],
    "vbikit.bridge.scaled": ["ScaledBridge"],
    "vbikit.bridge.sections": ["AASHTO_GIRDERS", "GirderSection", "composite_beam_properties"],
})
