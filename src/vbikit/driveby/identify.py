"""Identification from a passing vehicle: spectra, the bridge frequency with the driving and
shifted frequencies labelled, roughness cancellation, mode-shape squares and damage indicators.

Frequencies of a vehicle crossing a simply supported span L at speed v (Yang, Lin & Yau 2004;
Yang & Lin 2005; a light vehicle, the bridge as under a moving load): the vehicle response
holds the vehicle frequency f_v, the *driving* frequencies n v / L (the load's position enters
as sin(π v t / L), so the contact point's quasi-static deflection oscillates at v / L), and the
bridge frequencies *shifted* by the moving contact point, f_b ± v / (2 L) (circular:
ω_b ± π v / L).

Spectral resolution: a record of duration T resolves frequencies 1 / T apart (Rayleigh
resolution).  A single pass over the span lasts T = L / v, so the shifted pair f_b ± v / (2 L)
— exactly 1 / T apart — merges into one peak near f_b.  Zero-padding (``nfft``) interpolates
the spectrum between its bins and locates an isolated peak more finely; it does not separate
peaks closer than 1 / T, which every result reports as ``resolution_hz``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.driveby.quality import N_DRIVING, PeakQuality, peak_quality
from vbikit.errors import VbikitError

#: spectral estimators: name -> description
SPECTRUM_METHODS = {"periodogram": "one windowed FFT of the whole record (finest resolution, 1 / T)",
                    "welch": "Welch's average of overlapping windowed segments (smoother, resolution 1 / segment)"}


@dataclass(frozen=True)
class Spectrum:
    """One-sided power spectral density ``psd`` [unit²/Hz] at ``frequency`` [Hz]; ``resolution_hz``
    the Rayleigh resolution 1 / (record or segment duration) [Hz]."""

    frequency: NDArray[np.float64]
    psd: NDArray[np.float64]
    resolution_hz: float
    method: str
    window: str


def spectrum(signal: ArrayLike, fs: float, method: str = "periodogram", window: str = "hann",
             nperseg: Optional[int] = None, nfft: Optional[int] = None, detrend: str = "linear") -> Spectrum:
    """Power spectral density of ``signal`` sampled at ``fs`` [Hz] (``scipy.signal.periodogram`` or
    ``welch``; any scipy window name; ``nfft`` zero-pads, default 16 × the record or segment)."""
    from scipy.signal import periodogram, welch

    x = np.asarray(signal, float)
    if method not in SPECTRUM_METHODS:
        raise VbikitError(f"identification.spectrum: {method!r} is not a spectral method; allowed: {', '.join(SPECTRUM_METHODS)}")
    if x.size < 8:
        raise VbikitError(f"identification: a record of {x.size} samples is too short for a spectrum (at least 8)")
    if method == "periodogram":
        n = nfft or 16 * x.size
        f, p = periodogram(x, fs, window=window, nfft=n, detrend=detrend)
        res = fs / x.size
    else:
        seg = min(nperseg or max(8, x.size // 2), x.size)
        f, p = welch(x, fs, window=window, nperseg=seg, nfft=nfft or 16 * seg, detrend=detrend)
        res = fs / seg
    return Spectrum(f, p, float(res), method, window)


def peak(spec: Spectrum, band: tuple[float, float], exclude_hz: ArrayLike = (), exclude_width: float | None = None) -> float:
    """Frequency [Hz] of the highest peak (local maximum of the whole spectrum) inside ``band``
    (f_lo, f_hi) [Hz], outside ± ``exclude_width`` [Hz] of each of ``exclude_hz`` (known
    frequencies, e.g. the test vehicle's own); default 2 / T, the half-width of the Hann window's
    main lobe (a tone's peak spreads that far).  The flank of a larger peak outside the searched
    lines (beyond the band or inside an excluded zone) is no peak; only when the searched lines
    hold no local maximum is their highest value returned (``vbikit.driveby.quality`` flags it)."""
    lo, hi = band
    sel = (spec.frequency >= lo) & (spec.frequency <= hi)
    width = 2.0 * spec.resolution_hz if exclude_width is None else float(exclude_width)
    for f0 in np.atleast_1d(np.asarray(exclude_hz, float)):
        sel &= np.abs(spec.frequency - f0) > width
    if not sel.any():
        raise VbikitError(f"identification.band: [{lo:g}, {hi:g}] Hz holds no spectral line (spectrum up to "
                          f"{spec.frequency[-1]:g} Hz)")
    p = spec.psd
    local = np.zeros(p.size, bool)
    local[1:-1] = (p[1:-1] >= p[:-2]) & (p[1:-1] > p[2:])
    pick = sel & local if (sel & local).any() else sel
    i = np.flatnonzero(pick)[np.argmax(p[pick])]
    return float(spec.frequency[i])


def frequency_labels(speed: float, span: float, bridge_hz: ArrayLike = (), vehicle_hz: ArrayLike = (),
                     n_driving: int = N_DRIVING) -> dict[str, float]:
    """The frequencies [Hz] expected in a drive-by record: ``driving_n`` = n v / L (n = 1 …
    ``n_driving``), ``bridge_k``, ``bridge_k_minus`` / ``bridge_k_plus`` = f_b,k ∓ v / (2 L), and
    ``vehicle_k`` (module docstring)."""
    labels = {f"driving_{n}": n * speed / span for n in range(1, n_driving + 1)}
    for k, fb in enumerate(np.atleast_1d(np.asarray(bridge_hz, float)), start=1):
        labels[f"bridge_{k}"] = float(fb)
        labels[f"bridge_{k}_minus"] = float(fb - speed / (2 * span))
        labels[f"bridge_{k}_plus"] = float(fb + speed / (2 * span))
    for k, fv in enumerate(np.atleast_1d(np.asarray(vehicle_hz, float)), start=1):
        labels[f"vehicle_{k}"] = float(fv)
    return labels


@dataclass(frozen=True)
class Identification:
    """An identified frequency [Hz] with its spectrum, search band [Hz], Rayleigh resolution [Hz],
    the labelled expected frequencies, and what the peak is and how reliable
    (``quality``, ``vbikit.driveby.quality.peak_quality``)."""

    frequency_hz: float
    resolution_hz: float
    band: tuple[float, float]
    spectrum: Spectrum
    labels: dict[str, float] = field(default_factory=dict)
    quality: Optional[PeakQuality] = None

    @property
    def reliable(self) -> bool:
        """True when the peak passed every check of ``quality`` (``vbikit.driveby.quality``)."""
        return self.quality is not None and self.quality.reliable


def default_band(speed: float, span: float, vehicle_hz: ArrayLike = (), f_max: float = 30.0) -> tuple[float, float]:
    """A search band that avoids the driving frequencies: from 4 v / L (twice the second driving
    frequency) to ``f_max`` [Hz].  (Vehicle frequencies inside it are not removed; identify
    from the contact-point response, where they are absent, or give ``band``.)"""
    return (4.0 * speed / span, float(f_max))


def identify_frequency(signal: ArrayLike, fs: float, speed: float, span: float, band: Optional[tuple[float, float]] = None,
                       method: str = "periodogram", window: str = "hann", nperseg: Optional[int] = None,
                       bridge_hz: ArrayLike = (), vehicle_hz: ArrayLike = (), exclude_vehicle: bool = False,
                       vehicle_zeta: ArrayLike = (), envelope_offset: float = 0.0,
                       interaction_hz: float = 0.0) -> Identification:
    """The highest spectral peak of ``signal`` (sampled at ``fs`` [Hz], a record of a pass at
    ``speed`` [m/s] over a span ``span`` [m]) inside ``band`` [Hz] (default ``default_band``),
    with the expected frequencies labelled (``frequency_labels``; the true bridge and vehicle
    frequencies when known); ``exclude_vehicle``: skip ± 2 / T (``peak``) around the vehicle frequencies
    ``vehicle_hz`` (known for a test vehicle; a rough road makes the vehicle shake the bridge at
    them).  The peak's label and quality (``vbikit.driveby.quality.peak_quality``) use
    ``bridge_hz`` (the model's bridge frequencies, for the label only), ``vehicle_hz`` and the
    vehicle's damping ratios ``vehicle_zeta`` (default 0), and ``envelope_offset``, the first
    mode's ``quality.mode_envelope_offset`` along the path [1/T] (several spans: above 0.5, unreliable),
    and ``interaction_hz``, its shift by the vehicle's mass (``quality.interaction_shift``)."""
    spec = spectrum(signal, fs, method, window, nperseg)
    band = band or default_band(speed, span, vehicle_hz, 0.45 * fs)
    band = (float(band[0]), float(band[1]))
    f = peak(spec, band, vehicle_hz if exclude_vehicle else ())
    quality = peak_quality(spec.frequency, spec.psd, f, spec.resolution_hz, band, speed, span, window,
                           bridge_hz, vehicle_hz, vehicle_zeta, envelope_offset=envelope_offset,
                           interaction_hz=interaction_hz)
    return Identification(f, spec.resolution_hz, band, spec, frequency_labels(speed, span, bridge_hz, vehicle_hz), quality)


#: half-length [samples] of the windowed-sinc fractional-delay filter of ``delayed``, and its Kaiser β
DELAY_TAPS, DELAY_BETA = 32, 8.0


def delayed(x: ArrayLike, shift: float) -> NDArray[np.float64]:
    """The record ``x`` advanced by ``shift`` ≥ 0 samples, y[n] = x(n + shift), by band-limited
    (Shannon) interpolation: an integer shift plus a fractional one by a windowed-sinc filter,
    y[n] = Σ_j x[n + j] sinc(j − δ) w(j − δ), |j| ≤ ``DELAY_TAPS``, w a Kaiser window of β =
    ``DELAY_BETA`` (Laakso et al. 1996, windowed-sinc fractional delay).  Exact for an integer
    shift; for a fractional one, error below 1e-4 of the amplitude up to 0.4 × the sample rate
    (the anti-alias filter's cut-off), where linear interpolation loses up to 1 − cos(π f / f_s)
    … 5 % at 20 Hz and 200 Hz.  Samples that need values beyond the record are NaN."""
    from scipy.special import i0

    x = np.asarray(x, float)
    n0 = int(math.floor(shift + 1e-9))
    frac = float(shift - n0)
    y = np.full(x.size, np.nan)
    if frac > 1e-9:
        j = np.arange(-DELAY_TAPS, DELAY_TAPS + 1)
        u = (j - frac) / (DELAY_TAPS + 1)
        h = np.sinc(j - frac) * i0(DELAY_BETA * np.sqrt(np.clip(1 - u * u, 0, None))) / i0(DELAY_BETA)
        h /= h.sum()  # unit gain at 0 Hz
        inner = np.correlate(x, h, mode="valid")  # inner[i] = x(i + DELAY_TAPS + frac)
        frac_shifted = np.full(x.size, np.nan)
        frac_shifted[DELAY_TAPS:DELAY_TAPS + inner.size] = inner
    else:
        frac_shifted = x
    if n0 < x.size:
        y[:x.size - n0] = frac_shifted[n0:]
    return y


def residual_response(front: ArrayLike, rear: ArrayLike, fs: float, spacing: float, speed: float) -> NDArray[np.float64]:
    """Roughness cancellation: the front contact response minus the rear one shifted by the time
    the rear contact point needs to reach the front one's position, Δt = spacing / speed:

        Δu(t) = u_front(t) − u_rear(t + Δt)

    Both terms pass the same road point at time t, so the road profile cancels and only the
    deck's displacement at that point at the two times remains (Yang et al.'s residual response
    of two connected vehicles or two axles; here for any two contact points on one wheel line).
    The rear record is shifted by band-limited interpolation (``delayed``): the road's share of a
    contact acceleration grows with frequency and is far larger than the bridge's, so the few
    per cent lost by linear interpolation at a fractional shift would leave more road than
    bridge.  Samples whose shifted time falls outside the record are NaN."""
    front, rear = np.asarray(front, float), np.asarray(rear, float)
    return front - delayed(rear, spacing / speed * fs)


def bandpass(signal: ArrayLike, fs: float, band: tuple[float, float], order: int = 4) -> NDArray[np.float64]:
    """Zero-phase Butterworth band-pass (``scipy.signal.sosfiltfilt``) of order ``order`` over
    ``band`` [Hz]."""
    from scipy.signal import butter, sosfiltfilt

    sos = butter(order, band, btype="bandpass", fs=fs, output="sos")
    return sosfiltfilt(sos, np.asarray(signal, float))


def mode_shape_squares(contact: ArrayLike, fs: float, frequency_hz: float, half_width_hz: float,
                       order: int = 4) -> NDArray[np.float64]:
    """Squared instantaneous amplitude of the bridge component of a contact-point response, the
    drive-by estimate of φ(x)² along the path x = v t (Yang, Li & Chang 2014: the contact point's
    bridge component is A(t) φ(v t) sin(ω_b t); the Hilbert transform's envelope of the
    component band-passed around ω_b is |A φ(v t)|).  Band: ``frequency_hz`` ± ``half_width_hz``
    (at least v / (2 L), to pass the shifted pair).  Returns the envelope squared, scaled to a
    maximum of 1."""
    from scipy.signal import hilbert

    comp = bandpass(contact, fs, (frequency_hz - half_width_hz, frequency_hz + half_width_hz), order)
    env2 = np.abs(hilbert(comp)) ** 2
    return env2 / env2.max()


def frequency_shift(healthy_hz: float, damaged_hz: float) -> float:
    """Relative frequency change (f_damaged − f_healthy) / f_healthy [-] (negative for a loss of stiffness)."""
    return (damaged_hz - healthy_hz) / healthy_hz


#: what the position of the largest curvature change is worth, in words (reports and datasets print it beside it)
CURVATURE_LOCATION_CAVEAT = ("not a damage location: from one pass the mode-shape estimate changes with the damage by "
                             "less than its own end and envelope errors, so its largest curvature change falls anywhere "
                             "(docs/driveby.md, Verification and measured accuracy); the frequency shift is the damage indicator")


def shape_change(healthy: ArrayLike, damaged: ArrayLike) -> dict[str, float]:
    """Damage indicators from two mode-shape estimates on the same x grid (each scaled to a
    maximum of 1): ``mac`` (modal assurance criterion, Allemang & Brown 1982: 1 = same shape),
    ``shape_change`` = max |ψ_d − ψ_h| and ``curvature_change`` = max |ψ_d'' − ψ_h''| (Pandey,
    Biswas & Samman 1991's curvature indicator, central differences per grid step, no units),
    and ``curvature_argmax`` the grid index of the largest curvature change (Pandey et al.'s damage
    location estimate; from one vehicle pass it does not locate damage: ``CURVATURE_LOCATION_CAVEAT``)."""
    h = np.asarray(healthy, float)
    d = np.asarray(damaged, float)
    h, d = h / np.max(np.abs(h)), d / np.max(np.abs(d))
    mac = float(np.dot(h, d) ** 2 / (np.dot(h, h) * np.dot(d, d)))
    ch = np.diff(h, 2)
    cd = np.diff(d, 2)
    dc = np.abs(cd - ch)
    return {"mac": mac, "shape_change": float(np.max(np.abs(d - h))), "curvature_change": float(dc.max()),
            "curvature_argmax": int(np.argmax(dc)) + 1}
