"""A drive-by pass over several continuous spans: the first mode is several half-waves along the
deck, so the contact point sees the shifted pair f_b ± n v / (2 L) resolved, about n / T apart,
not merged into one lobe at f_b (docs/driveby.md, How accurate is this;
``quality.mode_envelope_offset``).  And a peak while the mode sought lies outside the search band
is not that mode.

Independent numbers: the first mode of n equal continuous spans of length l (internal supports
free to rotate) is the simply supported span's, sin(π x / l) along the whole deck, with
f = (π / (2 l²)) √(EI / m) (the interior supports sit at its nodes; Blevins, *Formulas for natural
frequency and mode shape*, equal-span continuous beams).  For two 20 m spans, EI = 2.4e10 N m²,
m = 4800 kg/m: f_b = π / 800 · √5e6 = 8.7810 Hz.  Before this check such a pass was reported
reliable with 9.153 Hz at 15 m/s (+4.2 %, on the component f_b + v / (2 l) = 9.156 Hz).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from vbikit.bridge import ContinuousBeam
from vbikit.driveby.identify import identify_frequency
from vbikit.driveby.quality import mode_envelope_offset
from vbikit.driveby.study import first_mode_envelope_offset

EI, MASS = 2.4e10, 4800.0


def _f_simply_supported(span: float) -> float:
    return math.pi / (2.0 * span**2) * math.sqrt(EI / MASS)


def _peak_of_fourier_transform(shape, length: float) -> float:
    """k L maximising |∫₀ᴸ φ(x) e^(−2πikx) dx|, by quadrature and a bounded search (brute force)."""
    def minus_magnitude(kl: float) -> float:
        k = kl / length
        re = quad(lambda x: shape(x) * math.cos(2 * math.pi * k * x), 0.0, length, limit=200)[0]
        im = quad(lambda x: shape(x) * math.sin(2 * math.pi * k * x), 0.0, length, limit=200)[0]
        return -math.hypot(re, im)
    grid = np.linspace(0.0, 3.0, 61)
    start = grid[int(np.argmin([minus_magnitude(g) for g in grid]))]
    return float(minimize_scalar(minus_magnitude, bounds=(max(start - 0.05, 0.0), start + 0.05), method="bounded").x)


def test_the_envelope_offset_is_where_the_shapes_fourier_transform_peaks():
    x = np.linspace(0.0, 40.0, 2001)
    assert mode_envelope_offset(np.sin(np.pi * x / 40.0), "boxcar") == 0.0  # one half-wave: the lobe at f_b
    for n in (2, 3):  # n half-waves: by quadrature
        expected = _peak_of_fourier_transform(lambda s: math.sin(n * math.pi * s / 40.0), 40.0)
        # within the zero-padded FFT's line spacing, 2000 / 2**17 = 0.015 cycles per span
        assert abs(mode_envelope_offset(np.sin(n * math.pi * x / 40.0), "boxcar") - expected) < 0.01
        assert expected > 0.5


def test_equal_continuous_spans_are_flagged_and_a_dominant_span_is_not():
    for spans in ((25.0,), (20.0, 20.0), (10.0, 10.0, 10.0)):
        bridge = ContinuousBeam(spans=spans, EI=EI, mass_per_length=MASS, n_modes=2)
        assert abs(bridge.frequencies_hz[0] / _f_simply_supported(spans[0]) - 1.0) < 1e-4  # the closed form's premise
        offset = first_mode_envelope_offset(bridge, None, "hann")
        assert (offset > 0.5) == (len(spans) > 1), (spans, offset)
    dominant = ContinuousBeam(spans=(30.0, 10.0), EI=EI, mass_per_length=MASS, n_modes=2)
    assert first_mode_envelope_offset(dominant, None, "hann") < 0.5  # measured error 0.04-0.11/T at 5-15 m/s


def test_a_pass_over_two_spans_is_flagged(tmp_path):
    import xarray as xr

    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby.study import run_driveby

    spec = parse_driveby({
        "seed": 1, "road": {"class": "none"},
        "bridge": {"model": "continuous-beam", "spans": [20.0, 20.0], "EI": EI, "mass_per_length": MASS, "n_modes": 6},
        "vehicle": {"model": "test-cart"}, "crossing": {"speed": 15.0, "approach": 5.0}, "sampling": {"rate": 200.0},
        "sensors": [{"name": "acc", "body": "body"}], "identification": {"method": "contact"},
        "sweep": {"speed": [15.0]}})
    run_driveby(spec, tmp_path, workers=1, figures=False)
    ds = xr.open_dataset(tmp_path / "driveby.nc")
    fb = _f_simply_supported(20.0)
    f, resolution = float(ds["identified_frequency_hz"][0]), float(ds["resolution_hz"][0])
    assert abs(resolution - 15.0 / 40.0) < 1e-2  # 1/T = v / L
    assert abs(f - fb) > 0.5 * resolution  # the pass is off f_b by a component of the pair ...
    assert int(ds["identified_frequency_reliable"][0]) == 0  # ... and says so
    assert "not one half-wave along the deck" in str(ds["identified_frequency_reason"].values[0])


def test_a_peak_while_the_mode_sought_lies_outside_the_band_is_flagged():
    """A tone at 19 Hz searched in [1, 20] Hz (T = 5 s, 5/T from the edge), the model's mode 1 at
    22 Hz: within the label's ± 20 % (19 / 22 = 0.86) but the mode itself is outside the band, so the
    peak cannot be it (before: reliable, labelled bridge_1)."""
    t = np.arange(1000) / 200.0
    x = np.sin(2 * np.pi * 19.0 * t) + 0.01 * np.random.default_rng(0).standard_normal(t.size)
    ident = identify_frequency(x, 200.0, 5.0, 25.0, (1.0, 20.0), bridge_hz=[22.0])
    assert not ident.reliable and "outside the search band" in ident.quality.reason
    inside = identify_frequency(x, 200.0, 5.0, 25.0, (1.0, 20.0), bridge_hz=[19.5])
    assert inside.reliable, inside.quality.reason
