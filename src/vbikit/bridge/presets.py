"""Bridge presets: the paper's bridges as 3D slab-on-girder decks, and as beam stand-ins.

``paper-bridge-1/2/3`` and ``cypress-bayou`` are [`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge]
grillage models (see [`paper_deck`][vbikit.bridge.paper_deck], [`cypress_bayou`][vbikit.bridge.cypress_bayou]).  The ``*-beam`` presets are
single Euler–Bernoulli beams with the whole cross-section lumped (full composite action).
Labels of the beam presets:

* [paper] span 9.16 / 16.76 / 39.62 m; roadway 9.75 m; deck 0.20 m; five girders at 2.13 m.
* [substitute] girder types (II for Bridges 1–2, VI for Bridge 3), E = 33 GPa for deck and
  girders (the composite estimate of model data §1), ρ = 2400 kg/m³, 2 % damping,
  no haunch, no diaphragms.  A beam cannot carry load to one girder: IM here is for the
  whole cross-section, not for Girder 4.
* [computed] f₁ ≈ 24.6 / 7.3 / 2.7 Hz (model data §1); tests check these.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from vbikit.bridge.base import DEFAULT_DAMPING_RATIO, ModalBridge
from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.bridge.girder_deck import SlabOnGirderBridge
from vbikit.bridge.sections import AASHTO_GIRDERS, composite_beam_properties

#: [substitute] concrete modulus used for the lumped composite beams [Pa]
E_CONCRETE = 33e9
#: [substitute] concrete density [kg/m³]
RHO_CONCRETE = 2400.0
#: [substitute] default modal damping ratio [-]
DEFAULT_DAMPING = DEFAULT_DAMPING_RATIO


def paper_beam(span: float, girder_type: str, n_modes: int = 10, damping_ratio: float = DEFAULT_DAMPING) -> EulerBernoulliBeam:
    """Whole-bridge composite beam of the paper's five-girder cross-section.

    [paper] roadway 9.75 m, deck 0.20 m, five girders; [substitute] AASHTO ``girder_type``,
    E = 33 GPa, ρ = 2400 kg/m³.
    """
    if girder_type not in AASHTO_GIRDERS:
        raise ValueError(f"girder_type: unknown {girder_type!r}; allowed: {', '.join(AASHTO_GIRDERS)}")
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


#: [substitute] girder concrete modulus of the 3D decks [Pa] (model data §1: ≈ 36 GPa girders, ≈ 33 GPa deck)
E_GIRDER_3D = 36e9

#: [substitute] default vehicle centreline y [m] of each paper bridge: the centre (rounded to 0.05 m)
#: of the range of offsets for which Girder 4 has the largest static midspan deflection under the
#: HS20-44's two wheel lines (track 2.2 m) in this model — the range is 1.05–2.8 m (Bridge 1),
#: 0.9–1.95 m (Bridge 2) and 0.3–0.6 m (Bridge 3); ``tests/verification/test_girder_deck.py`` checks it.
PAPER_LATERAL_OFFSET = {1: 1.95, 2: 1.4, 3: 0.45}


def paper_deck(bridge: int, n_modes: int = 10, damping_ratio: float = DEFAULT_DAMPING, **overrides: Any) -> SlabOnGirderBridge:
    """Bridge 1, 2 or 3 of the paper as a 3D slab-on-girder deck (grillage).

    * [paper] span 9.16 / 16.76 / 39.62 m; five prestressed girders at 2.13 m; roadway 9.75 m;
      deck 0.20 m; the impact factor is read at the midspan of Girder 4 (``default_girder`` = 4).
    * [substitute] (model data §1) AASHTO Type II girders (Bridges 1, 2), Type VI (Bridge 3);
      E = 36 GPa girders, 33 GPa deck, ν = 0.2, ρ = 2400 kg/m³; overhang 0.615 m each side (deck
      = roadway, 9.75 m); end diaphragms, plus a midspan diaphragm on Bridges 2 and 3 (0.25 m thick,
      0.75 × girder depth deep); rigid bearings; no haunch, parapet or wearing surface; 2 % modal
      damping; girder St Venant J from ``approximate_torsion_constant``.
    * [substitute] default lateral offset ``PAPER_LATERAL_OFFSET`` (Girder 4 most loaded).
    * Girder 1 is at the most negative y (right-hand edge for a driver in +x), Girder 4 at y = +2.13 m.
    """
    span, girder = {1: (9.16, "II"), 2: (16.76, "II"), 3: (39.62, "VI")}[bridge]
    diaphragms = (0.0, span) if bridge == 1 else (0.0, span / 2, span)
    if overrides.get("spans") is not None:  # several spans: diaphragms at every support (and midspan on Bridges 2, 3)
        edges = np.concatenate([[0.0], np.cumsum(overrides["spans"])])
        if overrides.get("span") is not None:
            edges[-1] = float(overrides["span"])  # the spans' sum may differ from the given span by round-off
        mids = [] if bridge == 1 else list(0.5 * (edges[1:] + edges[:-1]))
        diaphragms = tuple(sorted([float(v) for v in edges] + [float(v) for v in mids]))
        overrides.setdefault("span", float(edges[-1]))
    params: dict[str, Any] = dict(
        span=span, n_girders=5, girder_spacing=2.13, overhang=0.615, girder=girder, deck_thickness=0.20,
        E_girder=E_GIRDER_3D, E_deck=E_CONCRETE, poisson=0.2, density=RHO_CONCRETE, diaphragms=diaphragms,
        damping_ratio=damping_ratio, n_modes=n_modes, default_lateral_offset=PAPER_LATERAL_OFFSET[bridge],
        default_girder=4, name=f"paper-bridge-{bridge}",
    )
    params.update(overrides)
    return SlabOnGirderBridge(**params)


def cypress_bayou(n_modes: int = 10, damping_ratio: float = DEFAULT_DAMPING, **overrides: Any) -> SlabOnGirderBridge:
    """The field-test span (Cypress Bayou, Louisiana) as a 3D slab-on-girder deck.

    * [paper] 16.76 m simple span; seven AASHTO Type II girders at 2.13 m; midspan sensors on every girder;
      Girder 5 (loading case 1) and Girder 3 (case 2) are the most loaded.
    * [substitute] deck 14.01 m wide = 6 × 2.13 m + 2 × 0.615 m overhangs, 0.20 m thick; other data as
      Bridge 2 (E 36 / 33 GPa, ν = 0.2, ρ = 2400 kg/m³, end and midspan diaphragms, rigid bearings,
      2 % damping).  The paper's updated ANSYS model also had shoulders, railings and rubber bearings:
      use ``parapet_EI``, ``parapet_mass`` and ``bearing_stiffness`` to add them.
    * [substitute] default lateral offset +2.0 m (case 1: wheel lines straddling Girder 5, which is then
      the most loaded for offsets 1.1–2.95 m; −2.0 m is case 2 with Girder 3); default response girder 5.
    """
    params: dict[str, Any] = dict(
        span=16.76, n_girders=7, girder_spacing=2.13, overhang=0.615, girder="II", deck_thickness=0.20,
        E_girder=E_GIRDER_3D, E_deck=E_CONCRETE, poisson=0.2, density=RHO_CONCRETE, diaphragms=(0.0, 8.38, 16.76),
        damping_ratio=damping_ratio, n_modes=n_modes, default_lateral_offset=2.0, default_girder=5,
        name="cypress-bayou",
    )
    params.update(overrides)
    return SlabOnGirderBridge(**params)


def cypress_bayou_series(n_modes: int = 10, damping_ratio: float = DEFAULT_DAMPING_RATIO, rigid_approach_spans: bool = False,
                         **overrides: Any) -> ModalBridge:
    """The whole Cypress Bayou bridge: three simply supported 16.76 m spans in a row, span 3 tested.

    * [paper] the tested span is the third of three simple spans; the truck crosses spans 1–2 first.
    * [substitute] spans 1 and 2 are copies of the tested span's model ([`cypress_bayou`][vbikit.bridge.cypress_bayou], same
      ``overrides``), each with its own bearings and nothing connecting the spans
      (``SpanSeries``); ``n_modes`` per span.  With
      ``rigid_approach_spans`` spans 1–2 are rigid road: the approach model of [`cypress_bayou`][vbikit.bridge.cypress_bayou].
    * Responses, the default girder (5) and lateral offset (+2.0 m) are those of span 3.
    """
    from vbikit.bridge.series import SpanSeries

    if overrides.get("damage"):
        raise ValueError("bridge.damage: give the damage to a single-span deck; the span series does not place it")
    deck = cypress_bayou(n_modes=n_modes, damping_ratio=damping_ratio, **overrides)
    spans = (None, None, deck) if rigid_approach_spans else (deck, deck, deck)
    return SpanSeries(spans, (deck.span,) * 3, instrumented=2, name="cypress-bayou-3span")


@dataclass(frozen=True)
class BridgePreset:
    """A named bridge; ``build(n_modes=, damping_ratio=)`` returns the model."""

    name: str
    description: str
    build: Callable[..., ModalBridge]
    #: "beam" (build(n_modes=, damping_ratio=)) or "slab-on-girder" (build also takes any
    #: :class:`SlabOnGirderBridge` parameter as a keyword override)
    kind: str = "beam"


BRIDGE_PRESETS: dict[str, BridgePreset] = {
    p.name: p
    for p in (
        BridgePreset(
            "paper-bridge-1",
            "Bridge 1 of the paper: 9.16 m, five Type II girders at 2.13 m, 9.75 m deck (3D grillage)",
            lambda **kw: paper_deck(1, **kw),
            "slab-on-girder",
        ),
        BridgePreset(
            "paper-bridge-2",
            "Bridge 2 of the paper: 16.76 m, five Type II girders at 2.13 m, 9.75 m deck (3D grillage)",
            lambda **kw: paper_deck(2, **kw),
            "slab-on-girder",
        ),
        BridgePreset(
            "paper-bridge-3",
            "Bridge 3 of the paper: 39.62 m, five Type VI girders at 2.13 m, 9.75 m deck (3D grillage)",
            lambda **kw: paper_deck(3, **kw),
            "slab-on-girder",
        ),
        BridgePreset(
            "cypress-bayou",
            "Field bridge: 16.76 m, seven Type II girders at 2.13 m, 14.01 m deck (3D grillage)",
            lambda **kw: cypress_bayou(**kw),
            "slab-on-girder",
        ),
        BridgePreset(
            "cypress-bayou-3span",
            "Field bridge, all three 16.76 m simple spans in a row, span 3 tested (3D grillages)",
            lambda **kw: cypress_bayou_series(**kw),
            "slab-on-girder",
        ),
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
