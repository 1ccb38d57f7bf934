"""The direction a lifetime load effect is reported in: a two-signed influence line (a moment near
an interior support) whose other part has the larger area is flagged, and ``direction`` reports
either side; the screening's amplification check reads each event only for the effects it is
heavy for."""
import numpy as np
import pytest

from vbikit.analysis.checks import FLAG_CODES
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.lifetime.influence import effect_line
from vbikit.lifetime.report import OPPOSITE_AREA_LIMIT, _direction_flags
from vbikit.lifetime.screening import heavy_amplifications

L = 20.0  # two equal spans
X = 16.5  # the section in span 1


def _two_span_line(a):
    """Moment at X of a two-span continuous beam (equal spans L) under a unit downward load at a,
    by the three-moment equation (hand): the support moment M_B = −b (L² − b²)/(4 L²) with b the
    load's distance from its span's outer support, M(X) = simple-span moment + M_B X / L."""
    a = np.asarray(a, float)
    in1 = a <= L
    b = np.where(in1, a, 2 * L - a)
    mb = -b * (L**2 - b**2) / (4 * L**2)
    simple = np.where(in1, np.where(a <= X, a * (L - X) / L, X * (L - a) / L), 0.0)
    return simple + mb * X / L


def test_two_signed_moment_line_areas_and_directions():
    """At 16.5 m of a 20 + 20 m continuous beam the largest ordinate is sagging (+1.80 m against
    −1.59 m, hand: three-moment equation) but the hogging part has 2.42 times the area: a 5-axle
    truck of 400 kN gives a hogging peak 66 % above its sagging one there (brute force over its
    positions on this closed-form line, 1 cm steps; checked below).  auto keeps the sign of the largest ordinate and gives the area ratio; a given
    direction sets the sign and inverts the ratio."""
    beam = ContinuousBeam((L, L), 1.286e10, 7537.0, 0.02, n_modes=4)
    a = np.linspace(0.0, 2 * L, 400001)
    g = _two_span_line(a)
    positive, negative = np.trapezoid(np.maximum(g, 0), a), np.trapezoid(np.maximum(-g, 0), a)
    assert g.max() > -g.min()  # the largest ordinate is sagging
    axles, loads = np.cumsum([0, 5.5, 1.3, 9.3, 1.3]), np.array([50, 90, 90, 85, 85.0]) * 1e3
    on = lambda p: (p >= 0) & (p <= 2 * L)  # noqa: E731
    truck = np.array([loads @ (_two_span_line(f - axles) * on(f - axles)) for f in np.arange(0.0, 2 * L + axles[-1], 0.01)])
    assert -truck.min() > 1.6 * truck.max()  # hogging governs for a truck
    auto = effect_line(beam, beam.load_effect("moment", x=X))
    assert auto.sign == 1.0 and auto.direction == "auto"
    assert auto.opposite_area == pytest.approx(negative / positive, rel=2e-3)  # 2001-point line vs closed form
    assert auto.opposite_area > OPPOSITE_AREA_LIMIT
    hog = effect_line(beam, beam.load_effect("moment", x=X), direction="negative")
    assert hog.sign == -1.0 and hog.opposite_area == pytest.approx(positive / negative, rel=2e-3)


def test_direction_the_line_never_takes_is_refused():
    """A simply supported midspan moment is never negative (statics): direction = "negative" is
    refused naming why; "positive" gives a one-signed line (ratio 0)."""
    beam = ContinuousBeam((L,), 1.286e10, 7537.0, 0.02, n_modes=3)
    line = effect_line(beam, beam.load_effect("moment", x=L / 2), direction="positive")
    assert line.sign == 1.0 and line.opposite_area == 0.0
    with pytest.raises(ValueError, match="never negative"):
        effect_line(beam, beam.load_effect("moment", x=L / 2), direction="negative")


@pytest.mark.parametrize("source, area, largest, other, value", [
    ("auto", 2.42, None, None, 2.42),      # the line's areas alone (the run kept no other direction)
    ("auto", 0.5, 100.0, -150.0, 1.5),     # the traffic reached more the other way
    ("auto", 2.42, 100.0, -80.0, 2.42),    # not this traffic, but long or several vehicles may
    ("auto", 0.5, 100.0, -80.0, None),     # neither
    ("positive", 2.42, 100.0, -150.0, None),  # the user chose the direction
    ("auto", None, None, None, None)])     # nothing known
def test_opposite_direction_flag(source, area, largest, other, value):
    """The flag when the direction was chosen by the largest ordinate and the other direction may
    govern: the run's own largest static value the other way is larger (value: their ratio), or the
    other part of the line has the larger area (value: the area ratio); none when the user gave the
    direction or neither holds."""
    e = {"units": "N m", "direction": {"sign": 1.0, "source": source, "opposite_area": area, "largest": largest,
                                       "largest_opposite": other}}
    flags = _direction_flags("M", e)
    assert [f.code for f in flags] == (["opposite_direction_unreported"] if value is not None else [])
    if value is not None:
        f = flags[0]
        assert "opposite_direction_unreported" in FLAG_CODES
        assert f.value == pytest.approx(value) and f.threshold == 1.0 and 'direction = "negative"' in f.message
        assert ("negative direction governs" in f.message) == (value == 1.5)
        if largest is not None:
            assert f"reached {other:.4g} N m negative against {largest:.4g} N m positive" in f.message


def test_heavy_amplification_reads_each_effect_only_where_the_event_is_heavy():
    """Two events of one day, two effects (hand): event 0 governs effect 0 (static 100, dynamic 120:
    0.2) and is light for effect 1 (static 1, dynamic 5: 4.0, far below the day's 100 there); event 1
    governs effect 1 (100 → 130: 0.3) and is light for effect 0 (2 → 9).  The amplifications the
    screening checks are 0.2 and 0.3 — not the light pairs' 4.0 and 3.5, which raised A to 5 before."""
    static = np.array([[100.0, 1.0], [2.0, 100.0]])
    dyn = np.array([[120.0, 5.0], [9.0, 130.0]])
    amp = heavy_amplifications(dyn, static, np.array([1.0, 1.0]), np.array([0, 0]), 1, np.array([True, True]), 0.5)
    assert sorted(amp.tolist()) == pytest.approx([0.2, 0.3])
