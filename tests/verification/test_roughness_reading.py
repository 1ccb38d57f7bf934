"""The two readings of the paper's good / average / poor roads (docs/reproduction.md, "Road
roughness").  References: ISO 8608:1995 (classes as Gd(n0) at n0 = 0.1 cycle/m and as Φ(Ω0) at
Ω0 = 1 rad/m; Gd(n) = 2π Φ(Ω) at Ω = 2πn), and Eq. 7 of the paper: with the same phases θ_k, a PSD
c·φ gives the profile √c·r — so the alternative reading's profiles are vbikit's ISO ones scaled
by a constant, and the study of examples/studies/fig6_roughness_reading.toml is paired with
``vbikit study paper-fig6`` profile by profile."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vbikit.road import ISO_CLASSES, PAPER_CLASSES, RoadPSD, random_profile
from vbikit.study import load_study

ROOT = Path(__file__).resolve().parents[2]
N0_HW = 1 / (2 * math.pi)  # cycle/m
HW = {"good": 5e-6, "average": 20e-6, "poor": 80e-6}  # m³/cycle at N0_HW


def test_iso_classes_in_both_units():
    # ISO 8608 Table 1 (geometric means): Gd(0.1 cycle/m) = 16, 64, 256, 1024 × 1e-6 m³ for A–D and
    # Φ(1 rad/m) = 1, 4, 16, 64 × 1e-6 m³; with w = 2, Φ(Ω0) = Gd(n0)·(2π n0)² / (2π)
    for cls, phi_omega in zip("ABCD", (1e-6, 4e-6, 16e-6, 64e-6)):
        gd = ISO_CLASSES[cls]
        assert gd * (2 * math.pi * 0.1) ** 2 / (2 * math.pi) == pytest.approx(phi_omega, rel=6e-3)  # Gd/15.9
    assert PAPER_CLASSES == {"good": "B", "average": "C", "poor": "D"}  # the default reading


def test_alternative_reading_converted_to_iso_units():
    # φ(n) = φ(N0)(n/N0)^-2: the Huang–Wang levels at n0 = 0.1 cycle/m are 12.7 / 50.7 / 203 × 1e-6,
    # a fifth of ISO B / C / D (the readings differ by the unit: per cycle vs per rad)
    at_iso_n0 = {k: v * (N0_HW / 0.1) ** 2 for k, v in HW.items()}
    assert [round(v * 1e6, 1) for v in at_iso_n0.values()] == [12.7, 50.7, 202.6]
    for name, cls in PAPER_CLASSES.items():
        assert ISO_CLASSES[cls] / at_iso_n0[name] == pytest.approx(5.05, abs=0.01)
        # read as Φ(Ω0) [m³/rad] the same numbers fall inside ISO's band of that class (limits ×2 / ÷2)
        centre = ISO_CLASSES[cls] * (2 * math.pi * 0.1) ** 2 / (2 * math.pi)
        assert centre / 2 <= HW[name] <= centre * 2


def test_the_alternative_study_pairs_with_the_iso_one():
    study = load_study(ROOT / "examples" / "studies" / "fig6_roughness_reading.toml")
    assert study.size == 1440  # 8 n × 3 speeds × 3 levels × 20 profiles, as paper-fig6
    iso = random_profile(RoadPSD.iso("B"), seed=7, length=200.0)
    hw = random_profile(RoadPSD(HW["good"], N0_HW, 2.0), seed=7, length=200.0)
    scale = math.sqrt(HW["good"] * N0_HW**2 / (ISO_CLASSES["B"] * 0.1**2))  # 0.445
    np.testing.assert_allclose(hw.z, scale * iso.z, rtol=1e-12, atol=1e-15)
    assert scale == pytest.approx(0.445, abs=1e-3)
