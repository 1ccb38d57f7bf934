"""Design-code reference lines of study figures: the values for the study's own bridge and vehicle
(AASHTO Standard 50/(L+125) with L = 16.76 m = 55 ft → 0.278, domain data; CSA S6 two axles 0.30;
JTG D60 0.1767 ln f − 0.0157 at the beam's f₁ = (π/2L²)√(EI/m), worked here)."""
from __future__ import annotations

import math

import pytest

from vbikit.bridge.presets import paper_beam
from vbikit.study.figures import design_code_lines


def test_code_lines_follow_the_base_scenario():
    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "vehicle": {"model": "two-axle"},
            "crossing": {"speed_kmh": 80}}
    c = design_code_lines(base)
    beam = paper_beam(16.76, "II")
    f1 = math.pi / (2 * 16.76**2) * math.sqrt(beam.EI / beam.mass_per_length)
    assert c["aashto_lrfd"] == 0.33 and round(c["aashto_standard"], 3) == 0.278 and c["csa_s6"] == 0.30
    assert c["jtg_d60_2015"] == pytest.approx(0.1767 * math.log(f1) - 0.0157, rel=1e-9)
    assert c["ohbdc_1983"] == 0.20  # f1 = 7.3 Hz > 6 Hz
    cont = dict(base, bridge={"model": "continuous-beam", "spans": [20.0, 30.0], "EI": 1.286e10,
                              "mass_per_length": 7537.0}, response={"x": 35.0})
    assert round(design_code_lines(cont)["aashto_standard"], 4) == round(50 / (30.0 / 0.3048 + 125), 4)
