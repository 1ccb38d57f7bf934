"""A drive-by pass over several continuous spans: the first mode is several half-waves along the
deck, so the contact point sees the shifted pair f_b ± n v / (2 L) resolved, n / T apart, not
merged into one lobe at f_b (docs/driveby.md, How accurate is this; ``quality.mode_half_waves``).
And a peak while the mode sought lies outside the search band is not that mode.

Independent numbers: the first mode of n equal continuous spans of length l (internal supports
free to rotate) is the simply supported span's, sin(π x / l) along the whole deck, n half-waves,
with f = (π / (2 l²)) √(EI / m) (the interior supports sit at its nodes; Blevins, *Formulas for
natural frequency and mode shape*, table 8-1, case of equal spans).  For two 20 m spans,
EI = 2.4e10 N m², m = 4800 kg/m: f_b = π / 800 · √5e6 = 8.7810 Hz.  Before this check such a pass
was reported reliable with 9.153 Hz at 15 m/s (+4.2 %, on the component f_b + v / (2 l) = 9.156 Hz).
"""
from __future__ import annotations

import math

import numpy as np

from vbikit.bridge import ContinuousBeam
from vbikit.driveby.identify import identify_frequency
from vbikit.driveby.quality import mode_half_waves
from vbikit.driveby.study import first_mode_half_waves

EI, MASS = 2.4e10, 4800.0


def _f_simply_supported(span: float) -> float:
    return math.pi / (2.0 * span**2) * math.sqrt(EI / MASS)


def test_the_first_mode_has_one_half_wave_per_equal_span():
    for spans in ((25.0,), (20.0, 20.0), (10.0, 10.0, 10.0)):
        bridge = ContinuousBeam(spans=spans, EI=EI, mass_per_length=MASS, n_modes=2)
        assert first_mode_half_waves(bridge, None) == len(spans)
        assert abs(bridge.frequencies_hz[0] / _f_simply_supported(spans[0]) - 1.0) < 1e-4
    x = np.linspace(0.0, 40.0, 401)
    assert mode_half_waves(np.sin(np.pi * x / 20.0)) == 2  # the closed-form shape itself
    assert mode_half_waves(np.sin(np.pi * x / 40.0)) == 1


def test_a_resolved_shifted_pair_is_not_reliable():
    """sin(2π v t / L) sin(ω_b t) over T = L / v: the pair f_b ± v / L, 2/T apart."""
    fs, speed, length, fb = 200.0, 15.0, 40.0, 8.781
    t = np.arange(0.0, length / speed, 1.0 / fs)
    x = np.sin(2.0 * np.pi * speed * t / length) * np.sin(2.0 * np.pi * fb * t)
    one = identify_frequency(x, fs, speed, length, (1.5, 20.0), bridge_hz=[fb], half_waves=1)
    two = identify_frequency(x, fs, speed, length, (1.5, 20.0), bridge_hz=[fb], half_waves=2)
    assert abs(abs(one.frequency_hz - fb) - speed / length) < 0.1 * speed / length  # on a component, not f_b
    assert "half-waves" not in one.quality.reason  # (here also flagged: the two components are equal peaks)
    assert not two.reliable and "2 half-waves along the deck" in two.quality.reason


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
    assert "2 half-waves along the deck" in str(ds["identified_frequency_reason"].values[0])


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
