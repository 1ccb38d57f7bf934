"""Bridge models reduced to modes (the modal-bridge interface, the Euler–Bernoulli beam, presets)."""
from vbikit.bridge.base import ModalBridge
from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.bridge.presets import BRIDGE_PRESETS, paper_beam
from vbikit.bridge.sections import AASHTO_GIRDERS, GirderSection, composite_beam_properties

__all__ = [
    "AASHTO_GIRDERS",
    "BRIDGE_PRESETS",
    "EulerBernoulliBeam",
    "GirderSection",
    "ModalBridge",
    "composite_beam_properties",
    "paper_beam",
]
