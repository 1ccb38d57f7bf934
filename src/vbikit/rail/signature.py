"""Resonance wavelengths of any train from its axle chain: the train spectrum and its dominant wavelength.

A train of loads P_k at a_k crossing a bridge at speed v excites a mode of frequency n0 at the
wavelength λ = v / n0.  The forced response left behind by the k-th load reaches the mode with
the phase 2π a_k / λ, so the loads add up (resonance) where the train spectrum

    S(λ) = |Σ_k P_k exp(2π i a_k / λ)| / Σ_k P_k          (0 ≤ S ≤ 1)

has a peak: for a train of coaches of length D at λ = D / i, i = 1, 2, … — the resonance speeds
v_i = n0 D / i of EN 1991-2:2003 6.4.6 — and, for any other train, at the wavelengths of its
repeated axle spacings.  S is the excitation term (without damping) of the "dynamic signature"
by which the DER and LIR methods rank trains (the signature adds a damping and a span factor to
it); here it only places the resonances.

The dominant wavelength of a train without a documented coach length (a table file) is its
dominant repeated axle spacing: among the distances between two axles that occur at least
``MIN_REPEATS`` times (within ``LAG_TOL``) in ``WAVELENGTH_RANGE``, the one where S is largest
(for a train of coaches of length D: D, where every coach adds in phase; S at D / i is lowered by
the bogie factor |cos(π d / λ)|).  A train without such a repeated spacing takes the highest peak
of S in the range.  The spacing itself, not the peak of S, is used because the peak of a finite
train is pulled off D by its ends (HSLM-A10: 26.82 m for D = 27 m).
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: wavelengths [m] searched for a train's dominant one: real coaches are 10 … 27 m long (EN 1991-2:2003
#: Annex E, Table E.1, for trains that HSLM covers); the range leaves room on both sides
WAVELENGTH_RANGE = (5.0, 40.0)
#: a spacing between two axles is a repeated one when it occurs at least this often …
MIN_REPEATS = 3
#: … within this tolerance [m]
LAG_TOL = 1e-3
#: wavenumber samples [1/m] of the coarse search (refined to ``REFINE_TOL`` around each peak)
_SAMPLES = 20000
REFINE_TOL = 1e-7


def train_spectrum(axle_positions: ArrayLike, axle_loads: ArrayLike, wavelengths: ArrayLike) -> NDArray[np.float64]:
    """S(λ) = |Σ P_k exp(2π i a_k / λ)| / Σ P_k at each wavelength λ [m] (module docstring)."""
    a = np.asarray(axle_positions, float)
    p = np.asarray(axle_loads, float)
    k = 2.0 * np.pi / np.atleast_1d(np.asarray(wavelengths, float))
    phase = k[:, None] * a[None, :]
    return np.hypot(np.cos(phase) @ p, np.sin(phase) @ p) / float(p.sum())


def spectrum_peaks(axle_positions: ArrayLike, axle_loads: ArrayLike, lo: float, hi: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The local maxima of S(λ) for λ in [lo, hi] [m]: (wavelengths [m], heights), located on a fine
    grid in wavenumber and refined by a bounded scalar search."""
    from scipy.optimize import minimize_scalar

    kappa = np.linspace(1.0 / hi, 1.0 / lo, _SAMPLES)          # wavenumbers [1/m]
    s = train_spectrum(axle_positions, axle_loads, 1.0 / kappa)
    inner = np.nonzero((s[1:-1] >= s[:-2]) & (s[1:-1] > s[2:]))[0] + 1
    lam, height = [], []
    for j in inner:
        res = minimize_scalar(lambda q: -float(train_spectrum(axle_positions, axle_loads, [1.0 / q])[0]),
                              bounds=(kappa[j - 1], kappa[j + 1]), method="bounded", options={"xatol": REFINE_TOL / hi**2})
        lam.append(1.0 / float(res.x))
        height.append(-float(res.fun))
    order = np.argsort(lam)
    return np.asarray(lam)[order], np.asarray(height)[order]


def repeated_spacings(axle_positions: ArrayLike, lo: float, hi: float) -> NDArray[np.float64]:
    """The distances [m] in [lo, hi] between two axles that occur at least ``MIN_REPEATS`` times
    (within ``LAG_TOL``; each the mean of its group)."""
    a = np.asarray(axle_positions, float)
    lags = np.sort((a[None, :] - a[:, None])[np.triu_indices(a.size, 1)])
    lags = lags[(lags >= lo - LAG_TOL) & (lags <= hi + LAG_TOL)]
    if lags.size == 0:
        return lags
    groups = np.split(lags, np.nonzero(np.diff(lags) > LAG_TOL)[0] + 1)
    return np.array([float(g.mean()) for g in groups if g.size >= MIN_REPEATS])


def dominant_wavelength(axle_positions: ArrayLike, axle_loads: ArrayLike,
                        search: tuple[float, float] = WAVELENGTH_RANGE) -> Optional[float]:
    """The train's dominant wavelength [m] (module docstring); None for a single axle or a train
    with neither a repeated spacing nor a peak of S in the range."""
    a = np.asarray(axle_positions, float)
    if a.size < 2 or not math.isfinite(float(a[-1])) or a[-1] <= 0:
        return None
    lags = repeated_spacings(a, *search)
    if lags.size:
        return float(lags[int(np.argmax(train_spectrum(a, axle_loads, lags)))])
    lam, height = spectrum_peaks(a, axle_loads, *search)
    return float(lam[int(np.argmax(height))]) if lam.size else None
