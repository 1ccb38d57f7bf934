"""Random road profiles from a power spectral density (paper Eq. 7; ISO 8608 classes).

    r(X) = Σ_k √(2 φ(n_k) Δn) · cos(2π n_k X + θ_k),   θ_k ~ U[0, 2π)          (Eq. 7)
    φ(n) = φ(n₀) · (n / n₀)^(−w)                                                 (ISO 8608)

with n the wavenumber [cycle/m], φ the displacement PSD [m³/cycle].  The wavenumbers are
n_k = k·Δn inside the band [n_min, n_max], Δn = 1/P, and the profile is sampled at spacing Δx
over one period P = N·Δx (N a power of two), so the sum is evaluated exactly by one inverse
FFT.  P, Δx and the band do not depend on the vehicle or speed, so the same seed gives the
same road at the same x in every crossing of a study.

A crossing touches only some 50 m of the 1.3 km period.  With ``window = (x_lo, x_hi)`` the same
sum is evaluated only at the stations covering that range (the same stations and, up to round-off,
the same elevations as the whole period's inverse FFT): the band's M coefficients go to the m
stations by Bluestein's chirp-z identity k·l = (k² + l² − (l − k)²)/2, one circular convolution of
length ≥ M + m − 1 instead of an FFT of the whole period (L. I. Bluestein, "A linear filtering
approach to the computation of the discrete Fourier transform", IEEE Trans. Audio Electroacoust.
18, 1970, 451–455).  The shift to the window's first station is in the coefficients' phase, so the
convolution's factors depend on the window's length only and are kept for the few lengths a
stream's events ask for; the coefficients and the convolution are computed in place in one buffer.  Every phase 2π·q/N is reduced modulo N in integers first, so the window agrees
with the whole-period profile to ≈ 1e-12 of its rms (``tests/unit/test_road_window.py``).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.fft as sp_fft
from numpy.typing import NDArray

from vbikit.road.profile import RoadOrigin, RoadProfile

#: [substitute] stations added on each side of a requested window (the profile still covers it
#: after the crossing's own round-off)
WINDOW_MARGIN_SAMPLES = 2

#: [public] ISO 8608 reference wavenumber n₀ [cycle/m]
ISO_N0 = 0.1
#: [public] ISO 8608 class geometric means Gd(n₀) [m³/cycle]
ISO_CLASSES: dict[str, float] = {c: 16e-6 * 4.0**i for i, c in enumerate("ABCDEFGH")}
#: [substitute] the paper's good / average / poor road surface conditions mapped to ISO B / C / D
PAPER_CLASSES: dict[str, str] = {"good": "B", "average": "C", "poor": "D"}


@dataclass(frozen=True)
class RoadPSD:
    """Power-law displacement PSD φ(n) = phi0 · (n / n0)^(−exponent).

    Parameters
    ----------
    phi0 : float
        φ(n0) [m³/cycle].
    n0 : float
        Reference spatial frequency [cycle/m].
    exponent : float
        Exponent of the power law.
    n_min, n_max : float
        The band [cycle/m] ([substitute] default 0.01–4 cycle/m, model data §4).
    """

    phi0: float
    n0: float = ISO_N0
    exponent: float = 2.0
    n_min: float = 0.01
    n_max: float = 4.0

    def __post_init__(self) -> None:
        if not self.phi0 >= 0:
            raise ValueError(f"phi0 must be >= 0 m³/cycle, got {self.phi0!r}")
        if not (0 < self.n_min < self.n_max):
            raise ValueError(f"need 0 < n_min < n_max (cycle/m), got {self.n_min!r}, {self.n_max!r}")
        if not self.n0 > 0:
            raise ValueError(f"n0 must be > 0 cycle/m, got {self.n0!r}")

    @classmethod
    def iso(cls, road_class: str, **band: float) -> "RoadPSD":
        """ISO 8608 class A–H at its geometric mean (or the paper's good/average/poor)."""
        key = PAPER_CLASSES.get(road_class.lower(), road_class.upper())
        if key not in ISO_CLASSES:
            allowed = ", ".join(list(ISO_CLASSES) + list(PAPER_CLASSES))
            raise ValueError(f"unknown road class {road_class!r}; allowed: {allowed}")
        return cls(ISO_CLASSES[key], ISO_N0, 2.0, **band)

    def __call__(self, n: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.phi0 * (np.asarray(n, float) / self.n0) ** (-self.exponent)

    def band_variance(self) -> float:
        """∫ φ(n) dn over the band [m²] (closed form)."""
        w, a, b = self.exponent, self.n_min, self.n_max
        if abs(w - 1.0) < 1e-12:
            return self.phi0 * self.n0 * np.log(b / a)
        return self.phi0 * self.n0**w * (b ** (1 - w) - a ** (1 - w)) / (1 - w)


def _wavenumber_grid(psd: RoadPSD, spacing: float, length: float) -> tuple[int, float, NDArray[np.int64], NDArray[np.float64]]:
    """The DFT grid of Eq. 7: number of samples N (a power of two, N·Δx ≥ max(length, 1/n_min)),
    period P = N·Δx [m], and the indices k and wavenumbers n_k = k/P [cycle/m] inside the band
    (read-only arrays, kept for the last grids: ``_band_grid``)."""
    return _band_grid(float(psd.n_min), float(psd.n_max), float(spacing), float(length))


@lru_cache(maxsize=16)
def _band_grid(n_min: float, n_max: float, spacing: float, length: float
               ) -> tuple[int, float, NDArray[np.int64], NDArray[np.float64]]:
    """``_wavenumber_grid`` of the band n_min … n_max [cycle/m]."""
    n_samples = 1 << int(np.ceil(np.log2(max(length, 1.0 / n_min) / spacing)))
    period = n_samples * spacing
    k = np.arange(n_samples // 2 + 1)
    n_k = k / period
    in_band = (n_k >= n_min) & (n_k <= n_max)
    k, n_k = k[in_band], n_k[in_band]
    k.setflags(write=False)
    n_k.setflags(write=False)
    return n_samples, period, k, n_k


def random_profile(
    psd: RoadPSD,
    seed: int,
    spacing: float = 0.01,
    length: float = 1000.0,
    x_start: float | None = None,
    label: str = "",
    window: tuple[float, float] | None = None,
    origin: RoadOrigin | None = None,
) -> RoadProfile:
    """One random profile realisation by Eq. 7, reproducible from ``seed``.

    Parameters
    ----------
    psd : RoadPSD
        Target spectrum and band.
    seed : int
        Seed of the phase angles θ_k (numpy ``default_rng``).
    spacing : float
        Sample spacing Δx [m] ([substitute] 0.01 m: several samples inside a 0.254 m patch).
    length : float
        Minimum profile length [m]; the period P is the next power-of-two multiple of Δx not
        shorter than max(length, 1/n_min).  Δn = 1/P also sets how finely the band is
        resolved: the default (P = 1310.72 m at Δx = 0.01 m) keeps the part of the band below
        the first grid wavenumber under 1 % of the variance for ISO spectra.
    x_start : float, optional
        Station of the first sample [m]; default −P/2 (centred on the bridge entry).
    window : (float, float), optional
        Only the stations covering x_lo … x_hi [m] (clipped to the period; module docstring):
        the same road there as without ``window``, at a fraction of the cost.
    origin : RoadOrigin, optional
        Where the road comes from (e.g. the scenario's road class); default a random road of ``seed``.
    """
    origin = dataclasses.replace(origin or RoadOrigin("random", seed=int(seed)), shortest_wavelength=1.0 / psd.n_max,
                                 roughness=float(psd(np.array([ISO_N0]))[0]))
    if spacing <= 0:
        raise ValueError(f"road spacing must be > 0 m, got {spacing!r}")
    if psd.n_max > 0.5 / spacing:
        raise ValueError(f"n_max = {psd.n_max} cycle/m is above the Nyquist wavenumber 1/(2Δx) = {0.5 / spacing} cycle/m")
    n_samples, period, k, n_k = _wavenumber_grid(psd, spacing, length)
    x0 = -period / 2 if x_start is None else float(x_start)
    theta = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, n_k.size)
    amp = _amplitudes(psd, spacing, length)
    label = label or f"PSD phi0={psd.phi0:g}, seed {seed}"
    if window is not None:
        first, last = _window_samples(window, x0, spacing, n_samples)
        z = _window_sum(theta, amp, psd, spacing, length, x0, first, last - first + 1)
        return RoadProfile(x0 + spacing * np.arange(first, last + 1), z, label, origin=origin)
    band = amp * np.exp(1j * (theta + 2.0 * np.pi * n_k * x0))
    coef = np.zeros(n_samples // 2 + 1, complex)
    coef[k] = band
    coef[n_samples // 2] *= 2.0  # irfft counts the Nyquist term once, the others twice (k = 0 is never in the band)
    z = np.fft.irfft(coef, n_samples)
    z *= 0.5 * n_samples  # = Re Σ_k coef_k exp(2πi k j / N): one real FFT (scaled in place: no second period-long array)
    return RoadProfile(_stations(x0, spacing, n_samples), z, label, origin=origin)


@lru_cache(maxsize=4)
def _stations(x0: float, spacing: float, n_samples: int) -> NDArray[np.float64]:
    """x_j = x0 + Δx·j, j = 0 … N − 1 (read-only, kept: the profiles of one period and start share them)."""
    x = x0 + spacing * np.arange(n_samples)
    x.setflags(write=False)
    return x


def random_road_range(psd: RoadPSD, spacing: float = 0.01, length: float = 1000.0,
                      x_start: float | None = None) -> tuple[float, float]:
    """The stations x [m] of the first and last samples of ``random_profile``'s period for these settings
    (a window of it reaches no further)."""
    n_samples, period, _, _ = _wavenumber_grid(psd, spacing, length)
    x0 = -period / 2 if x_start is None else float(x_start)
    return x0, x0 + spacing * (n_samples - 1)


def _window_samples(window: tuple[float, float], x0: float, spacing: float, n_samples: int) -> tuple[int, int]:
    """First and last sample index j (x_j = x0 + j·Δx) covering ``window`` with the margin, clipped to the period."""
    lo, hi = (float(v) for v in window)
    if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
        raise ValueError(f"road window must be finite (x_lo, x_hi) with x_lo <= x_hi, got {window!r}")
    first = math.floor((lo - x0) / spacing) - WINDOW_MARGIN_SAMPLES
    last = math.ceil((hi - x0) / spacing) + WINDOW_MARGIN_SAMPLES
    first, last = max(first, 0), min(last, n_samples - 1)
    return (first, max(last, first + 1)) if first < n_samples - 1 else (n_samples - 2, n_samples - 1)


def _chirp(q: NDArray[np.int64], n_samples: int) -> NDArray[np.complex128]:
    """exp(iπ q²/N) with q² reduced modulo 2N in integers (exact phase for any q)."""
    return np.exp(1j * np.pi * ((q * q) % (2 * n_samples)) / n_samples)


@lru_cache(maxsize=16)
def _amplitudes(psd: RoadPSD, spacing: float, length: float) -> NDArray[np.float64]:
    """√(2 φ(n_k) Δn) of Eq. 7 on the grid of ``_wavenumber_grid`` (read-only, kept per spectrum and grid)."""
    _, period, _, n_k = _wavenumber_grid(psd, spacing, length)
    amp = np.sqrt(2.0 * psd(n_k) / period)
    amp.setflags(write=False)
    return amp


#: [substitute] window lengths are rounded up to a multiple of this many stations for the chirp-z
#: factors (``_band_sum_factors``): the events of a stream, each with its own window, then share a
#: few factor sets instead of computing one each (the extra stations are computed and dropped)
WINDOW_QUANTUM = 512
#: [substitute] factor sets kept (``_band_sum_factors``, one per rounded window length): benchmarks/bench_traffic.py's
#: stream (Bridge 2, 3,816 events of 1–5 trucks) meets 38 lengths, 4096 … 27648 stations (23 MB of factors); with 16
#: kept the rare long windows pushed out common ones, 169 sets made in all at ≈ 2 ms each (≈ 0.1 ms an event)
BAND_FACTOR_SETS = 48


@lru_cache(maxsize=BAND_FACTOR_SETS)
def _band_sum_factors(k0: int, n_band: int, n_samples: int, m: int
                      ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128], int]:
    """The factors of ``_window_sum`` that depend on the grid and the window's length only (not on the
    coefficients, nor on where the window starts): the chirp of each coefficient, the FFT of the
    chirp kernel, the output's carrier-and-chirp, and the FFT length.  Kept for the last lengths:
    every event of a traffic stream or crossing of a study on one bridge asks for a few of them."""
    n = np.arange(n_band, dtype=np.int64)
    pre = _chirp(n, n_samples)
    size = int(sp_fft.next_fast_len(n_band + m - 1))
    b = np.zeros(size, complex)
    b[:m] = np.conj(_chirp(np.arange(m, dtype=np.int64), n_samples))  # W^{−l²/2}, l = 0 … m − 1
    b[size - n_band + 1:] = np.conj(_chirp(np.arange(-(n_band - 1), 0, dtype=np.int64), n_samples))
    l = np.arange(m, dtype=np.int64)
    post = np.exp(2j * np.pi * ((k0 * l) % n_samples) / n_samples) * _chirp(l, n_samples)
    for arr in (pre, b, post):
        arr.setflags(write=False)
    kernel = sp_fft.fft(b)
    kernel.setflags(write=False)
    return pre, kernel, post, size


@lru_cache(maxsize=16)
def _phase_origin(psd: RoadPSD, spacing: float, length: float, x0: float) -> NDArray[np.float64]:
    """2π n_k x0 of Eq. 7 on the grid of ``_wavenumber_grid`` (read-only, kept per grid and start: the
    same numbers as computed with each profile)."""
    n_k = _wavenumber_grid(psd, spacing, length)[3]
    phase = 2.0 * np.pi * n_k * x0
    phase.setflags(write=False)
    return phase


def _window_sum(theta: NDArray[np.float64], amp: NDArray[np.float64], psd: RoadPSD, spacing: float, length: float,
                x0: float, first: int, m: int) -> NDArray[np.float64]:
    """Eq. 7 at the m stations j = first … first + m − 1 (x_j = x0 + j Δx) from the phases θ_k: the
    inverse DFT (times N) of the band's coefficients c_k = amp_k exp(i(θ_k + 2π n_k x0 + 2π (k·first
    mod N)/N)), k = k0 … k0 + M − 1 (the shift to the window's first station in their own phase), at its first m samples only, Re Σ_n c_n exp(2πi (k0 + n) l / N):
    Bluestein's chirp-z convolution (module docstring), its factors independent of the coefficients
    from ``_band_sum_factors`` (kept per length rounded up to ``WINDOW_QUANTUM``), each step in place
    in one zero-padded buffer."""
    n_samples, _, k, _ = _wavenumber_grid(psd, spacing, length)
    if k.size == 0:
        return np.zeros(m)
    m_kept = -(-m // WINDOW_QUANTUM) * WINDOW_QUANTUM
    pre, kernel, post, size = _band_sum_factors(int(k[0]), int(k.size), int(n_samples), int(m_kept))
    buf = np.zeros(size, complex)
    band = buf[:k.size]
    phase = theta + _phase_origin(psd, spacing, length, x0)
    phase += (2.0 * np.pi / n_samples) * ((k * first) & (n_samples - 1))  # N is a power of two: k·first mod N
    np.exp(1j * phase, out=band)
    band *= amp
    band *= pre
    conv = sp_fft.fft(buf, overwrite_x=True)
    conv *= kernel
    conv = sp_fft.ifft(conv, overwrite_x=True)[:m]
    conv *= post[:m]
    return np.real(conv)


def phase_angles(psd: RoadPSD, seed: int, spacing: float = 0.01, length: float = 1000.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The (n_k, θ_k) pairs a profile with these settings uses (for direct evaluation of Eq. 7)."""
    n_k = np.array(_wavenumber_grid(psd, spacing, length)[3])  # a writable copy of the kept grid
    theta = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, n_k.size)
    return n_k, theta


def correlated_profile(
    left: RoadProfile,
    psd: RoadPSD,
    seed: int,
    coherence: float,
    spacing: float = 0.01,
    length: float = 1000.0,
    x_start: float | None = None,
    label: str = "",
    window: tuple[float, float] | None = None,
) -> RoadProfile:
    """The right wheel line's profile, partially correlated with ``left`` (same PSD).

    r_R(x) = c · r_L(x) + √(1 − c²) · r_I(x), with r_I an independent realisation of the same
    PSD (phases from a child seed of ``seed``, ``numpy.random.SeedSequence(seed).spawn``) on the
    same stations.  r_R then has the PSD of ``psd`` and the cross-spectral density c · G(n): the
    ordinary coherence between the two lines is c², the same at every wavenumber.  c = 1 gives
    the paper's identical lines, c = 0 independent ones.  [substitute] Measured roads are more
    coherent at long than at short wavelengths; a constant c is the simplest model that keeps
    both PSDs exact.  ``left`` must come from [`random_profile`][vbikit.road.random_profile] with the same ``psd``,
    ``spacing``, ``length``, ``x_start`` and ``window``.
    """
    if not 0.0 <= coherence <= 1.0:
        raise ValueError(f"left/right coherence must be in [0, 1], got {coherence!r}")
    child = int(np.random.SeedSequence(seed).spawn(1)[0].generate_state(1)[0])
    other = random_profile(psd, child, spacing=spacing, length=length, x_start=x_start, window=window)
    if other.x.shape != left.x.shape or not np.array_equal(other.x, left.x):
        raise ValueError("the left profile was not generated with the same spacing, length, x_start and window")
    z = coherence * left.z + np.sqrt(1.0 - coherence**2) * other.z
    return RoadProfile(left.x, z, label or f"{left.label}, right line (coherence {coherence:g})", origin=left.origin)
