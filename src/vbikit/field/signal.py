"""Signal handling for measured records: low-pass, resampling, time alignment, offset/drift removal.

Time bases: a measured record has its own clock t_m [s].  The simulation starts (t = 0) with the
front axle ``approach`` metres before the bridge entry, so it reaches the entry at
t_entry = approach / speed.  A trigger time t_trig (the instant, on the record's clock, at which
the front axle reaches the bridge entry) maps t_sim = t_m − t_trig + t_entry; the shift is
``shift = t_entry − t_trig`` [s].
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import signal as sps
from scipy.interpolate import CubicSpline

log = logging.getLogger(__name__)


def lowpass(x: NDArray[np.float64], fs: float, cutoff: float, order: int = 4) -> NDArray[np.float64]:
    """Zero-phase Butterworth low-pass (``scipy.signal.sosfiltfilt``): ``order`` poles, −3 dB at ``cutoff`` [Hz]
    applied forward and backward (so −6 dB at the cut-off, no phase shift)."""
    if not 0 < cutoff < fs / 2:
        raise ValueError(f"signal.lowpass_hz must be between 0 and the Nyquist frequency {fs / 2:g} Hz, got {cutoff:g}")
    sos = sps.butter(order, cutoff, btype="low", fs=fs, output="sos")
    return sps.sosfiltfilt(sos, x)


def resample(t_src: NDArray[np.float64], x: NDArray[np.float64], t_dst: NDArray[np.float64]) -> NDArray[np.float64]:
    """Cubic-spline interpolation of x(t_src) at t_dst; NaN outside the source range.

    Meant for up-sampling a record onto the (finer) simulation time base; a record sampled
    faster than the target must be low-passed below the target Nyquist frequency first
    (``prepare`` does that).  Error for a sinusoid of frequency f sampled at fs is
    O((2π f / fs)⁴).
    """
    out = np.full(t_dst.shape, np.nan)
    inside = (t_dst >= t_src[0]) & (t_dst <= t_src[-1])
    out[inside] = CubicSpline(t_src, x)(t_dst[inside])
    return out


def xcorr_shift(t_sim: NDArray[np.float64], sim: NDArray[np.float64], t_meas: NDArray[np.float64],
                meas: NDArray[np.float64], max_shift: float) -> float:
    """Time shift s [s] maximising the correlation of sim(t) with meas(t − s) (t_sim = t_meas + s).

    Both signals are put on a uniform grid of the simulation step, mean-removed and
    cross-correlated over |s| ≤ max_shift; the peak is refined by a parabola through its three
    neighbouring samples (sub-sample accuracy).
    """
    dt = float(np.median(np.diff(t_sim)))
    grid = np.arange(t_meas[0], t_meas[-1], dt)
    m = CubicSpline(t_meas, meas)(grid)
    s = np.interp(np.arange(t_sim[0], t_sim[-1], dt), t_sim, sim)
    m = m - m.mean()
    s = s - s.mean()
    # c[k] = Σ s[n + k] m[n]: lag k samples means t_sim = t_meas_grid + k dt
    c = sps.correlate(s, m, mode="full", method="fft")
    lags = sps.correlation_lags(s.size, m.size, mode="full")
    shifts = lags * dt + (t_sim[0] - grid[0])  # sim sample n + k at t_sim[0] + (n + k) dt ↔ meas grid[0] + n dt
    ok = np.abs(shifts) <= max_shift
    if not ok.any():
        raise ValueError("cross-correlation: no admissible shift; check the record length and trigger")
    idx = np.flatnonzero(ok)[np.argmax(c[ok])]
    frac = 0.0
    if 0 < idx < c.size - 1:
        y0, y1, y2 = c[idx - 1], c[idx], c[idx + 1]
        den = y0 - 2 * y1 + y2
        if den != 0:
            frac = 0.5 * (y0 - y2) / den
    return float(shifts[idx] + frac * dt)


@dataclass(frozen=True)
class DriftFit:
    """A linear error model e(t) = offset + drift · (t − t_ref) removed from one channel [SI, SI/s]."""

    offset: float
    drift: float
    t_ref: float
    method: str
    samples: int


def quiet_drift(t: NDArray[np.float64], x: NDArray[np.float64], quiet: NDArray[np.bool_], t_ref: float) -> DriftFit:
    """Least-squares line through the samples where the bridge is at rest (``quiet`` mask).

    Model-free: before the truck arrives and after the vibration has decayed the true
    acceleration is ≈ 0, so a + b (t − t_ref) fitted there is the sensor's offset and drift.
    """
    n = int(quiet.sum())
    if n < 10:
        raise ValueError(f"offset/drift removal needs at least 10 quiet samples (bridge at rest), found {n}; "
                         "record longer before the truck arrives / after it leaves or set signal.quiet_tail")
    a = np.column_stack([np.ones(n), t[quiet] - t_ref])
    (off, dr), *_ = np.linalg.lstsq(a, x[quiet], rcond=None)
    return DriftFit(float(off), float(dr), t_ref, "quiet", n)


def model_drift(t: NDArray[np.float64], meas: NDArray[np.float64], sim: NDArray[np.float64], t_ref: float) -> DriftFit:
    """Least-squares line through meas − sim over the whole overlap (uses the model; for short records)."""
    ok = np.isfinite(meas) & np.isfinite(sim)
    a = np.column_stack([np.ones(int(ok.sum())), t[ok] - t_ref])
    (off, dr), *_ = np.linalg.lstsq(a, meas[ok] - sim[ok], rcond=None)
    return DriftFit(float(off), float(dr), t_ref, "model", int(ok.sum()))
