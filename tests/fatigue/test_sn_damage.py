"""S-N curves and Miner damage against the formulas of EN 1993-1-9 and AASHTO LRFD, computed by hand."""
from __future__ import annotations

import math

import numpy as np
import pytest

from vbikit.fatigue import (FatigueError, damage_equivalent_range, en1993_curve, equivalent_stress_range, miner_damage,
                            rainflow, remaining_life, sn_curve)

MPA = 1e6
#: 1 ksi = 6.894757293168361 MPa (NIST SP 811, Appendix B: 1 lbf/in² = 6.894757293168361e3 Pa)
KSI = 6.894757293168361e6


def _constant_amplitude(delta: float, cycles: int) -> list[tuple[float, float]]:
    """Rainflow cycles of a constant-amplitude history 0, Δ, 0, Δ, …, 0 with ``cycles`` peaks."""
    history = np.zeros(2 * cycles + 1)
    history[1::2] = delta
    return rainflow(history)


def _damage_of_history(delta: float, cycles: int, curve) -> float:
    pairs = _constant_amplitude(delta, cycles)
    return miner_damage([r for r, _ in pairs], [n for _, n in pairs], curve)


# --- EN 1993-1-9 (7.1, Fig. 7.1): detail category 71 --------------------------------------------
DC = 71.0                                   # Δσ_C, MPa, at N_C = 2e6
DD = (2.0 / 5.0) ** (1.0 / 3.0) * DC        # Δσ_D = 52.3 MPa at N_D = 5e6
DL = (5.0 / 100.0) ** (1.0 / 5.0) * DD      # Δσ_L = 28.7 MPa at N_L = 1e8


def test_en_knees_match_the_standards_rounded_values():
    # EN 1993-1-9 Fig. 7.1 labels category 71 with Δσ_D = 52 and Δσ_L = 29 MPa (rounded)
    curve = sn_curve("EN 71")
    assert curve.threshold / MPA == pytest.approx(52.0, abs=0.5)
    assert curve.segments[-1].stress_min / MPA == pytest.approx(29.0, abs=0.5)
    n = curve.cycles_to_failure(np.array([DC, DD, DL]) * MPA)
    np.testing.assert_allclose(n, [2e6, 5e6, 1e8], rtol=1e-12)


@pytest.mark.parametrize("delta_mpa, expected_n", [
    (100.0, 2e6 * (DC / 100.0) ** 3),       # above Δσ_D: slope m = 3 → 705 830 cycles
    (40.0, math.inf),                       # below Δσ_D at constant amplitude: no damage (1.3.3.3)
    (20.0, math.inf),                       # below the cut-off Δσ_L: no damage
])
def test_miner_damage_of_constant_amplitude_histories_on_each_slope(delta_mpa, expected_n):
    cycles = 1000
    damage = _damage_of_history(delta_mpa * MPA, cycles, sn_curve("EN 71"))
    assert damage == pytest.approx(cycles / expected_n, rel=1e-12, abs=0.0)


def test_constant_amplitude_fatigue_limit_applies_to_the_whole_spectrum():
    # EN 1993-1-9:2005, 1.3.3.3: below Δσ_D no damage under constant amplitude; "under variable
    # amplitude conditions all stress ranges have to be below this limit for no fatigue damage".
    curve = sn_curve("EN 71")
    assert miner_damage([50 * MPA, 35 * MPA], [1e6, 1e7], curve) == 0.0     # both below Δσ_D = 52.3
    # one cycle above Δσ_D: the 35 MPa cycles count on the m = 5 slope (hand sum of n/N)
    expected = 1.0 / (2e6 * (DC / 60.0) ** 3) + 1e7 / (5e6 * (DD / 35.0) ** 5)
    assert miner_damage([60 * MPA, 35 * MPA], [1.0, 1e7], curve) == pytest.approx(expected, rel=1e-12)


def test_parts_of_a_longer_loading_add_up_to_the_whole():
    # A day whose ranges all stay below Δσ_D does damage when another day exceeds it (EN 1993-1-9
    # 1.3.3.3 judges the whole loading): as parts (whole_spectrum=False) the days add up to the
    # whole; judged alone the quiet day would wrongly count nothing.
    curve = sn_curve("EN 71")
    quiet, busy = ([35 * MPA], [1e7]), ([60 * MPA], [1.0])
    whole = miner_damage([60 * MPA, 35 * MPA], [1.0, 1e7], curve)
    parts = sum(miner_damage(r, n, curve, whole_spectrum=False) for r, n in (quiet, busy))
    assert parts == pytest.approx(whole, rel=1e-12)
    assert miner_damage(*quiet, curve) == 0.0
    assert miner_damage(*quiet, curve, whole_spectrum=False) == pytest.approx(1e7 / (5e6 * (DD / 35.0) ** 5), rel=1e-12)
    assert miner_damage([20 * MPA], [1e9], curve, whole_spectrum=False) == 0.0  # below the cut-off Δσ_L = 28.7 MPa


def test_partial_factor_divides_the_curve():
    # γ_Mf = 1.35: the design curve has Δσ_C / γ_Mf at 2e6 cycles; 100 MPa stays on the m = 3 slope
    curve = sn_curve("EN 71", gamma_mf=1.35)
    expected = 2e6 * (DC / 1.35 / 100.0) ** 3
    assert curve.cycles_to_failure(100.0 * MPA)[0] == pytest.approx(expected, rel=1e-12)


def test_two_level_spectrum_damage_unequal_ranges_and_counts():
    # 2 000 cycles at 90 MPa (m = 3) and 300 000 at 35 MPa (m = 5), hand sum of n/N
    n1, s1, n2, s2 = 2_000.0, 90.0, 300_000.0, 35.0
    expected = n1 / (2e6 * (DC / s1) ** 3) + n2 / (5e6 * (DD / s2) ** 5)
    ranges, counts = [s1 * MPA, s2 * MPA], [n1, n2]
    curve = sn_curve("EN 71")
    assert miner_damage(ranges, counts, curve) == pytest.approx(expected, rel=1e-12)
    # swapped arguments are a different (wrong) spectrum: the result must not match
    swapped = miner_damage(counts, ranges, curve)
    assert not math.isclose(swapped, expected, rel_tol=1e-3)
    with pytest.raises(FatigueError) as err:
        miner_damage(ranges, counts[:1], curve)
    assert err.value.key == "counts"
    with pytest.raises(FatigueError) as err:
        miner_damage([-1.0, 2.0], [1.0, 1.0], curve)
    assert err.value.key == "ranges"
    with pytest.raises(FatigueError) as err:
        miner_damage(ranges, counts, "EN 71")
    assert err.value.key == "curve"


# --- AASHTO LRFD 6.6.1.2.5: N = A / Δf³ ---------------------------------------------------------
@pytest.mark.parametrize("category, a_1e8_ksi3, delta_ksi", [
    ("C", 44.0, 12.0),      # Table 6.6.1.2.5-1: A = 44.0e8 ksi³
    ("E'", 3.9, 3.0),
    ("A", 250.0, 30.0),
    ("B'", 61.0, 15.0),
])
def test_aashto_cycles_against_the_formula(category, a_1e8_ksi3, delta_ksi):
    expected = a_1e8_ksi3 * 1e8 / delta_ksi**3
    curve = sn_curve(f"AASHTO {category}")
    assert curve.cycles_to_failure(delta_ksi * KSI)[0] == pytest.approx(expected, rel=1e-12)


def test_aashto_thresholds_match_the_si_values():
    # constant-amplitude thresholds, Table 6.6.1.2.5-3, in MPa as printed beside the ksi values
    # (A 165, B 110, C 69, D 48 MPa; the same values as AISC 360 Appendix 3 Table)
    for cat, mpa in (("A", 165.0), ("B", 110.0), ("C", 69.0), ("D", 48.0)):
        assert sn_curve(f"AASHTO {cat}").threshold / MPA == pytest.approx(mpa, rel=0.01)


def test_aashto_infinite_life_only_if_the_largest_range_is_below_the_threshold():
    curve = sn_curve("AASHTO C")                 # (ΔF)_TH = 10 ksi
    low = 5.0 * KSI
    assert miner_damage([9.0 * KSI, low], [1e6, 1e7], curve) == 0.0
    # one cycle above the threshold: every cycle counts on the straight line N = A/Δf³
    expected = 1.0 / (44e8 / 12.0**3) + 1e7 / (44e8 / 5.0**3)
    assert miner_damage([12.0 * KSI, low], [1.0, 1e7], curve) == pytest.approx(expected, rel=1e-12)


def test_curve_names():
    assert sn_curve("aashto c′").name == "AASHTO C'"
    assert sn_curve("EN 36").segments[0].stress_ref == pytest.approx(36e6)
    for bad in ("EN seventy", "BS 7608 F", "AASHTO G"):
        with pytest.raises(FatigueError):
            sn_curve(bad)


#: EN 1993-1-9:2005, Fig. 7.1 and Tables 8.1–8.10: the detail categories Δσ_C [MPa], written out here
EN_1993_1_9_FIG_7_1 = (160, 140, 125, 112, 100, 90, 80, 71, 63, 56, 50, 45, 40, 36)


def test_every_category_of_the_standard_has_its_curve():
    from vbikit.fatigue import EN_CATEGORIES, curve_name

    assert sorted(EN_CATEGORIES) == sorted(EN_1993_1_9_FIG_7_1)
    for c in EN_1993_1_9_FIG_7_1:
        for written in (f"EN {c}", f"en{c}", f" EN  {c}.0 "):
            assert curve_name(written) == f"EN {c}"
        assert sn_curve(f"EN {c}").cycles_to_failure(c * MPA)[0] == pytest.approx(2e6, rel=1e-12)  # N_C at Δσ_C
    for letter in ("A", "B", "B'", "C", "C'", "D", "E", "E'"):
        assert curve_name(f"aashto {letter.lower().replace(chr(39), '′')}") == f"AASHTO {letter}"


@pytest.mark.parametrize("name, near", [
    ("EN 37", 36),            # the issue: a typo of 36 gave a fatigue life
    ("EN 35", 36), ("EN 65", 63), ("EN 70", 71), ("EN 71.5", 71), ("EN 180", 160), ("EN 300", 160),
    ("EN -36", None), ("EN 1e2", None), ("EN-71", None), ("EN seventy", None), ("EN", None), ("AASHTO G", None),
    ("AASHTO", None), ("BS 7608 F", None), ("", None),
])
def test_a_category_the_standards_do_not_list_is_refused_with_the_list(name, near):
    from vbikit.fatigue import AASHTO_CATEGORIES, EN_CATEGORIES, curve_name

    for call in (lambda: curve_name(name), lambda: sn_curve(name), lambda: sn_curve(name, gamma_mf=1.35)):
        with pytest.raises(FatigueError) as err:
            call()
        msg = str(err.value)
        assert err.value.key == "curve"
        assert f"{name!r} is not a detail category" in msg
        assert ("EN " + ", ".join(map(str, EN_CATEGORIES))) in msg and ", ".join(AASHTO_CATEGORIES) in msg
        assert (f"the nearest EN category is {near})" in msg) == (near is not None)


def test_a_category_reduced_for_size_is_built_by_en1993_curve():
    """Δσ_C not in the list (k_s Δσ_C, EN 1993-1-9 Table 8.x) stays possible through the constructor:
    N = 2e6 at Δσ = Δσ_C (Eq. 7.2)."""
    assert en1993_curve(65.0).cycles_to_failure(65.0 * MPA)[0] == pytest.approx(2e6, rel=1e-12)


# --- equivalent ranges and remaining life -------------------------------------------------------
def test_equivalent_range_of_a_two_level_spectrum():
    # (1e5 · 80³ + 1e6 · 40³) / 2e6 = 57 600 MPa³ → Δσ_eq = 57 600^(1/3) = 38.620 MPa
    got = equivalent_stress_range([80 * MPA, 40 * MPA], [1e5, 1e6], m=3.0, n_ref=2e6)
    assert got / MPA == pytest.approx(57_600 ** (1 / 3), rel=1e-12)
    assert got / MPA == pytest.approx(38.620, abs=0.0005)


def test_damage_equivalent_range_inverts_the_curve_on_both_slopes():
    curve = sn_curve("EN 71")
    assert damage_equivalent_range([100 * MPA], [1e5], curve, n_ref=1e5) / MPA == pytest.approx(100.0, rel=1e-12)
    # one cycle of 60 MPa opens the spectrum (above Δσ_D), 1e5 cycles of 40 MPa on the m = 5 slope:
    # D by hand, then N_eq = n_ref / D = 1.91e7 lies between N_D and N_L: Δσ = Δσ_D (N_D / N_eq)^(1/5)
    d = 1.0 / (2e6 * (DC / 60.0) ** 3) + 1e5 / (5e6 * (DD / 40.0) ** 5)
    n_eq = 1e5 / d
    assert 5e6 < n_eq < 1e8
    got = damage_equivalent_range([60 * MPA, 40 * MPA], [1.0, 1e5], curve, n_ref=1e5) / MPA
    assert got == pytest.approx(DD * (5e6 / n_eq) ** 0.2, rel=1e-12)
    assert damage_equivalent_range([20 * MPA], [1e5], curve) == 0.0
    assert damage_equivalent_range([40 * MPA], [1e5], curve) == 0.0            # all below Δσ_D


def test_damage_equivalent_range_below_the_cut_off_names_n_ref():
    # 1e4 cycles of 60 MPa (m = 3 slope): D = 1e4 / (2e6 (71/60)^3) = 3.018e-3 by hand; 2e6 cycles of
    # any range at or above Δσ_L do at least 2e6 / 1e8 = 0.02, so no range answers: the error names
    # the argument the user gave (n_ref), not an internal one
    curve = sn_curve("EN 71")
    d = 1e4 / (2e6 * (DC / 60.0) ** 3)
    assert miner_damage([60 * MPA], [1e4], curve) == pytest.approx(d, rel=1e-12)
    with pytest.raises(FatigueError) as err:
        damage_equivalent_range([60 * MPA], [1e4], curve)
    assert err.value.key == "n_ref"
    # at n_ref = D · N_L the answer is the cut-off limit Δσ_L itself
    assert damage_equivalent_range([60 * MPA], [1e4], curve, n_ref=d * 1e8) / MPA == pytest.approx(DL, rel=1e-9)


def test_remaining_life_by_hand():
    assert remaining_life(0.02, damage_so_far=0.3) == pytest.approx(35.0)
    assert remaining_life(0.0) == math.inf
    assert remaining_life(0.5, damage_so_far=1.2) == 0.0
    with pytest.raises(FatigueError) as err:
        remaining_life(-0.1)
    assert err.value.key == "damage_per_year"


def test_non_numbers_raise_fatigue_errors_naming_the_argument():
    for call, key in ((lambda: remaining_life("abc"), "damage_per_year"),
                      (lambda: remaining_life(0.1, damage_so_far=None), "damage_so_far")):
        with pytest.raises(FatigueError) as err:
            call()
        assert err.value.key == key
    # a category given as a numeric string is the same curve (it was refused by the name's format)
    assert en1993_curve("71").name == "EN 71"
    assert en1993_curve("71", gamma_mf="1.35").cycles_to_failure(100 * MPA)[0] == pytest.approx(
        2e6 * (DC / 1.35 / 100.0) ** 3, rel=1e-12)
