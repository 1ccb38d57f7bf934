"""Girder sections and the composite slab-on-girder beam section.

AASHTO standard I-girder properties [public] (PCI Bridge Design Manual section tables),
converted from in/in²/in⁴ to SI.  ``composite_beam_properties`` lumps a whole slab-on-girder
cross-section into one Euler–Bernoulli beam (full composite action, transformed section).
"""
from __future__ import annotations

from dataclasses import dataclass

IN = 0.0254  # m per inch


@dataclass(frozen=True)
class GirderSection:
    """Prismatic girder section.

    Parameters
    ----------
    area : float
        Area A [m²].
    inertia : float
        Second moment I [m⁴] about its own centroid.
    y_bottom : float
        Centroid height above the bottom y_b [m].
    depth : float
        Overall depth h [m].
    """

    area: float
    inertia: float
    y_bottom: float
    depth: float


def _aashto(area_in2: float, y_b_in: float, h_in: float, inertia_in4: float) -> GirderSection:
    return GirderSection(area_in2 * IN**2, inertia_in4 * IN**4, y_b_in * IN, h_in * IN)


#: AASHTO I-girders types I–VI [public] (A in², y_b in, h in, I in⁴ from the PCI tables).
AASHTO_GIRDERS: dict[str, GirderSection] = {
    "I": _aashto(276.0, 12.59, 28, 22_744),
    "II": _aashto(369.0, 15.83, 36, 50_979),
    "III": _aashto(559.5, 20.27, 45, 125_390),
    "IV": _aashto(789.0, 24.73, 54, 260_741),
    "V": _aashto(1013.0, 31.96, 63, 521_163),
    "VI": _aashto(1085.0, 36.38, 72, 733_320),
}


@dataclass(frozen=True)
class CompositeBeam:
    """Lumped properties of a composite deck + girders cross-section.

    EI [N·m²], mass_per_length [kg/m], neutral_axis_depth [m] = height of the composite
    neutral axis above the girders' bottom fibre (the strain lever arm c).
    """

    EI: float
    mass_per_length: float
    neutral_axis_depth: float


def composite_beam_properties(
    girder: GirderSection,
    n_girders: int,
    deck_width: float,
    deck_thickness: float,
    E_girder: float,
    E_deck: float,
    density: float,
) -> CompositeBeam:
    """Transformed-section properties of ``n_girders`` girders acting fully composite with a deck.

    The deck (width × thickness) sits directly on the girder tops (no haunch); its area is
    transformed to girder concrete by n = E_deck / E_girder.  Mass uses the gross areas and
    one density [kg/m³].  Returns EI referred to E_girder.
    """
    n_ratio = E_deck / E_girder
    a_g = n_girders * girder.area
    a_d = n_ratio * deck_width * deck_thickness
    y_d = girder.depth + deck_thickness / 2.0
    y_na = (a_g * girder.y_bottom + a_d * y_d) / (a_g + a_d)
    inertia = (
        n_girders * girder.inertia
        + a_g * (y_na - girder.y_bottom) ** 2
        + n_ratio * deck_width * deck_thickness**3 / 12.0
        + a_d * (y_d - y_na) ** 2
    )
    mass = density * (a_g + deck_width * deck_thickness)
    return CompositeBeam(EI=E_girder * inertia, mass_per_length=mass, neutral_axis_depth=y_na)
