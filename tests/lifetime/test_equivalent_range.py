"""The damage-equivalent stress range of the design life (EN 1993-1-9 Δσ_E,2) by hand.

EN 1993-1-9:2005 Fig. 7.1 for category 36: N = 2e6 (36/Δσ)³ above Δσ_D = (2/5)^(1/3)·36 =
26.525 MPa, N = 5e6 (Δσ_D/Δσ)⁵ down to the cut-off Δσ_L = (5/100)^(1/5)·Δσ_D = 14.570 MPa.  The
range whose 2e6 cycles do the damage D has N(Δσ) = 2e6 / D, so it is at most Δσ_C exactly when
D ≤ 1: the check γFf Δσ_E,2 ≤ Δσ_C/γMf of EN 1993-1-9 8(2) needs the design life's damage, not a
year's (a year's range, which the lifetime report printed as "Δσ_E,2", is 100^(1/3) = 4.6 times
lower on the m = 3 line for a 100-year life)."""
import math

import pytest

from vbikit.fatigue import sn_curve
from vbikit.lifetime.results import _equivalent_range

MPA = 1e6


def test_equivalent_range_on_both_slopes_and_below_the_cut_off():
    curve = sn_curve("EN 36")
    # D = 1.26 over the design life (the red-team run's EN 36 detail): N = 1.587e6 < 2e6, m = 3
    assert _equivalent_range(curve, 1.26) == pytest.approx(36 * MPA * 1.26 ** (1 / 3), rel=1e-12)
    assert _equivalent_range(curve, 1.26) > 36 * MPA  # the design life's damage above 1: above Δσ_C
    # D = 0.1: N = 2e7 on the m = 5 slope: Δσ_D (5e6 / 2e7)^(1/5)
    dd = (2 / 5) ** (1 / 3) * 36 * MPA
    assert _equivalent_range(curve, 0.1) == pytest.approx(dd * 0.25 ** 0.2, rel=1e-12)
    # a year's D = 0.0126: N = 1.59e8 beyond N_L = 1e8, below the cut-off: no range
    assert math.isnan(_equivalent_range(curve, 0.0126))
    assert _equivalent_range(curve, 0.0) == 0.0
