"""Bridge models reduced to modes (the modal-bridge interface, the Euler–Bernoulli beam,
the slab-on-girder grillage deck, imported modes, presets)."""
from vbikit.bridge.base import ModalBridge
from vbikit.bridge.beam import EulerBernoulliBeam
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
    "EulerBernoulliBeam",
    "GirderSection",
    "ModalBridge",
    "ScaledBridge",
    "SlabOnGirderBridge",
    "composite_beam_properties",
    "cypress_bayou",
    "paper_beam",
    "paper_deck",
]
