"""Comparison metrics between a measured and a simulated channel on a common time base.

For measured m(t) and simulated s(t) at the same N instants (SI units):

* peak error      (max|s| − max|m|) / max|m|                         [-]
* RMS error       √(mean (s − m)²)                                    [SI]
* normalised RMS  RMS error / √(mean m²)                              [-]
* correlation     Pearson r of s and m                                [-]
* PSD band ratio  √(∫_band P_s df / ∫_band P_m df) per band, P from Welch's method
                  (``scipy.signal.welch``, Hann windows of ``nperseg`` samples, 50 % overlap):
                  the ratio of the band RMS amplitudes, 1 = same energy in that band.
* dominant frequency of each (peak of the PSD above ``f_min``).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import signal as sps


def channel_metrics(meas: NDArray[np.float64], sim: NDArray[np.float64], fs: float,
                    bands: tuple[tuple[float, float], ...] = ((0.0, 5.0), (5.0, 15.0), (15.0, 30.0)),
                    f_min: float = 1.0, nperseg_seconds: float = 1.0) -> dict[str, Any]:
    """Metrics of ``sim`` against ``meas`` (same length, sampled at ``fs`` [Hz]); see the module docstring."""
    meas = np.asarray(meas, float)
    sim = np.asarray(sim, float)
    if meas.shape != sim.shape or meas.size < 8:
        raise ValueError("channel_metrics needs two equally long signals of at least 8 samples")
    pm, ps = float(np.max(np.abs(meas))), float(np.max(np.abs(sim)))
    err = sim - meas
    rms_m = float(np.sqrt(np.mean(meas**2)))
    rms_e = float(np.sqrt(np.mean(err**2)))
    corr = float(np.corrcoef(meas, sim)[0, 1]) if np.std(meas) > 0 and np.std(sim) > 0 else float("nan")
    nper = int(min(meas.size, max(8, round(nperseg_seconds * fs))))
    f, p_m = sps.welch(meas, fs=fs, nperseg=nper)
    _, p_s = sps.welch(sim, fs=fs, nperseg=nper)
    band_out = []
    for lo, hi in bands:
        sel = (f >= lo) & (f < hi)
        if hi > fs / 2 or sel.sum() < 1:
            band_out.append({"band_hz": [lo, hi], "amplitude_ratio": None})
            continue
        df = float(f[1] - f[0])
        em, es = float(p_m[sel].sum() * df), float(p_s[sel].sum() * df)  # rectangle rule on the Welch grid
        band_out.append({"band_hz": [lo, hi], "amplitude_ratio": float(np.sqrt(es / em)) if em > 0 else None})
    hi_sel = f >= f_min
    dom_m = float(f[hi_sel][np.argmax(p_m[hi_sel])]) if hi_sel.any() else float("nan")
    dom_s = float(f[hi_sel][np.argmax(p_s[hi_sel])]) if hi_sel.any() else float("nan")
    return {
        "peak_measured": pm,
        "peak_simulated": ps,
        "peak_error": (ps - pm) / pm if pm > 0 else float("nan"),
        "rms_error": rms_e,
        "normalised_rms_error": rms_e / rms_m if rms_m > 0 else float("nan"),
        "correlation": corr,
        "dominant_frequency_measured_hz": dom_m,
        "dominant_frequency_simulated_hz": dom_s,
        "psd_bands": band_out,
    }
