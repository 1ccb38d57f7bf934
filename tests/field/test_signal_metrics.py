"""Signal handling and metrics on analytic signals."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.field.metrics import channel_metrics
from vbikit.field.signal import lowpass, quiet_drift, resample, xcorr_shift


def test_xcorr_recovers_a_known_shift():
    t_sim = np.arange(0, 6, 1e-3)
    pulse = lambda t: np.exp(-((t - 3.0) / 0.3) ** 2) * np.sin(2 * np.pi * 2 * t)
    t_meas = np.arange(0, 5, 1 / 200)
    true_shift = 0.8473  # t_sim = t_meas + shift
    s = xcorr_shift(t_sim, pulse(t_sim), t_meas, pulse(t_meas + true_shift), 3.0)
    assert s == pytest.approx(true_shift, abs=2e-4)


def test_lowpass_is_zero_phase_and_minus_6_db_at_cutoff():
    fs, fc = 500.0, 20.0
    t = np.arange(0, 20, 1 / fs)
    x = np.sin(2 * np.pi * fc * t)
    y = lowpass(x, fs, fc)
    mid = slice(len(t) // 4, 3 * len(t) // 4)
    assert np.max(np.abs(y[mid])) == pytest.approx(0.5, rel=0.01)  # |H|² of a forward–backward Butterworth
    low = np.sin(2 * np.pi * 2.0 * t)
    assert np.max(np.abs(lowpass(low, fs, fc)[mid] - low[mid])) < 1e-3  # pass band, no phase shift
    with pytest.raises(ValueError, match="lowpass_hz"):
        lowpass(x, fs, 300.0)


def test_cubic_resampling_accuracy():
    t = np.arange(0, 2, 1 / 200)
    f = 10.0
    t2 = np.arange(0.1, 1.9, 1e-3)
    err = resample(t, np.sin(2 * np.pi * f * t), t2) - np.sin(2 * np.pi * f * t2)
    assert np.max(np.abs(err)) < 2 * (2 * np.pi * f / 200) ** 4  # O((ω h)⁴)
    assert np.isnan(resample(t, t, np.array([-1.0]))[0])


def test_quiet_drift_exact_on_a_line():
    t = np.linspace(0, 10, 1001)
    x = 0.3 + 0.02 * (t - 4.0)
    quiet = (t < 2) | (t > 9)
    fit = quiet_drift(t, x, quiet, 4.0)
    assert fit.offset == pytest.approx(0.3, abs=1e-12)
    assert fit.drift == pytest.approx(0.02, abs=1e-12)
    with pytest.raises(ValueError, match="quiet samples"):
        quiet_drift(t, x, t < 0.01, 4.0)


def test_metrics_of_a_scaled_signal():
    fs = 200.0
    t = np.arange(0, 10, 1 / fs)
    m = np.sin(2 * np.pi * 3 * t) + 0.3 * np.sin(2 * np.pi * 20 * t)
    out = channel_metrics(m, 1.1 * m, fs, bands=((0.0, 10.0), (10.0, 40.0)))
    assert out["peak_error"] == pytest.approx(0.1)
    assert out["correlation"] == pytest.approx(1.0)
    assert out["normalised_rms_error"] == pytest.approx(0.1)
    assert [b["amplitude_ratio"] for b in out["psd_bands"]] == pytest.approx([1.1, 1.1])
    assert out["dominant_frequency_measured_hz"] == pytest.approx(3.0)
