"""What an identified drive-by frequency is and how far to trust it: a label, quality numbers,
a reliability flag with its reasons in words, and the estimate over several passes.

Every threshold lives here, with its reason (docs/driveby.md, "How accurate is this"):

* **Main lobe.** A tone of a record T seconds long, windowed, spreads over ± ``lobe``/T around
  its frequency (the window's main-lobe half-width: 1 for a rectangular window, 2 for Hann and
  Hamming, 3 for Blackman; Harris 1978, table 1).  Two tones closer than the sum of their
  half-widths share one lobe and pull each other's peak.
* **Band edge** (``EDGE_LOBES`` = 1 main-lobe half-width).  A peak closer than ``lobe``/T to an
  edge of the search band has part of its lobe outside the band: the highest in-band value may
  be the flank of a peak outside the band, or of a spectrum still rising at the edge.  A peak
  that is not a local maximum of the whole spectrum (its neighbours just outside the band
  higher) is such a flank wherever it lies.
* **Vehicle frequency** (``VEHICLE_LOBES`` = 2 main-lobe half-widths, or ``VEHICLE_HALF_BANDS`` =
  1 × the vehicle mode's half-power band f_v (1 ± ζ), whichever is wider).  Inside 2 lobe/T the
  main lobes of the bridge peak and of the vehicle's own response overlap, so the vehicle's
  much larger response biases the bridge peak (or is the peak).  Inside the half-power band of
  a damped vehicle mode its resonance is within 3 dB of its top, so a peak there may be the
  vehicle's own; outside it the resonance is a sloping background, which the background check
  measures.  The same limit applies to the model's frequency of the mode sought: inside it no
  peak of this pass can be that mode.
* **Driving frequencies** n v / L (n = 1 … ``N_DRIVING``): a peak within one main-lobe
  half-width of one is unreliable.
* **Label**: the nearest of the expected frequencies the peak matches (a vehicle frequency
  inside its flagging limit, a driving frequency inside a main lobe, a bridge mode inside
  ``MODE_TOLERANCE``); ``none`` when it matches none, which makes it unreliable.
* **A rival peak** (``RIVAL_LOBES`` = 2 main-lobe half-widths, ``RIVAL_DB`` = 6 dB).  Another
  local maximum of the searched lines within 2 main-lobe half-widths of the peak (their lobes
  overlap) and less than 6 dB (a factor 4 in power, 2 in amplitude) below it: one pass cannot
  tell which of the two is the bridge, and each pulls the other's location.  A bridge peak split
  by the road-induced forced response of the deck looks like this.
* **Background level** (``FALSE_ALARM`` = 1 %).  The peak's power spectral density against the
  median of the band's other lines (outside its main lobe) and of those within ``LOCAL_LOBES``
  = 5 main-lobe half-widths on each side (the local background; a rough road's spectrum rises
  with frequency, so the band's median alone would make any high-frequency line look strong).
  For noise alone the periodogram's lines are exponentially distributed (χ² with 2 degrees of
  freedom; Bendat & Piersol 2010, § 8.5), so a line exceeds r times the median with probability
  2^(−r), and the highest of the M ≈ (f_hi − f_lo) · T independent lines of the band exceeds it
  with probability ≈ M 2^(−r).  A peak counts as above the background when its ratio to the
  larger of the two medians exceeds r = log2(M / ``FALSE_ALARM``): noise alone would produce
  such a peak in 1 % of passes.
* **Bridge mode label** (``MODE_TOLERANCE`` = 20 %).  A peak is labelled bridge mode k when it
  lies within 20 % of the model's k-th frequency (the design model's uncertainty, and more than
  the shift of a 50 % local stiffness loss, −8.7 % in docs/driveby.md); otherwise it matches no
  expected frequency.
* **Passes that agree** (``AGREE_RESOLUTIONS`` = 1).  A pass agrees with the multi-pass median
  when its peak lies within its own resolution 1/T of it (closer than its record can tell two
  frequencies apart); with at least
  ``MIN_PASSES`` = 3 reliable passes a pass that does not agree is unreliable too.

The shifted pair f_b ± v / (2 L) of a single pass is 1 / T apart (T = L / v) and merges into
one lobe centred on f_b (the two components have equal amplitude: the contact point's modal
displacement is sin(π v t / L) sin(ω_b t)), so no speed correction is applied
(``speed_correction_hz`` = 0); the label is the bridge mode of the merged pair.

* **Mode outside the band.**  When the model's frequency of the mode sought lies outside the search
  band (a short, stiff span: 10 m, f_b = 35 Hz, against the default band's 20 Hz), whatever peak
  the band holds is not that mode.
* **Shape of the mode along the path** (``ENVELOPE_RESOLUTIONS`` = 0.5, ``mode_envelope_offset``).
  That merging needs the sought mode to be one half-wave along the vehicle's path.  The contact
  point sees φ(v t) sin(ω_b t), windowed like the record: the bridge's lobe sits at f_b ± k v with
  k where the spectrum of φ(x) w(x) over the deck peaks.  For one half-wave k = 0; the first mode
  of n equal continuous spans is sin(n π x / L), whose spectrum peaks near n / (2 L): the pair
  f_b ± n v / (2 L), n / T apart, no longer one lobe at f_b, and the peak falls on one component
  (two 20 m spans at 15 m/s: 9.15 Hz for 8.78 Hz, +4.2 %, about 1/T).  A pass is unreliable when
  k L exceeds 0.5 (half a resolution 1/T).  Unequal spans whose long span dominates the mode
  stay below it (30 + 10 m: k = 0; 25 + 15 m: k L = 0.43 with a Hann window, measured errors
  0.03–0.25/T at 5–15 m/s).

* **The vehicle's mass on the deck** (``INTERACTION_RESOLUTIONS`` = 0.5, ``interaction_shift``).  A
  pass measures the bridge carrying the vehicle: the sought mode coupled with the vehicle's modes
  (a mode below the bridge's pushes it up, one above pulls it down) has another frequency than the
  bridge alone, by about half the mass ratio where the two are far apart.  Estimated from the
  frozen system (the mode, the vehicle on its tires) at every position of the pass, weighted by
  φ² of the front wheel and the window.  A shift above half a resolution 1/T is unreliable: unlike
  noise it is the same in every pass, so the multi-pass median keeps it (a 6 t cart on the 25 m,
  120 t span of the example: +0.11 Hz, +1.9 %, against identified +1.8 … +2.1 % at 3 … 8 m/s).

Reference: Harris, F.J. (1978). On the use of windows for harmonic analysis with the discrete
Fourier transform. *Proc. IEEE* 66(1), 51–83.  Bendat, J.S. & Piersol, A.G. (2010). *Random
Data*, 4th ed., Wiley.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.analysis.checks import Flag, unconverged_dataset_flags

#: a shift of the sought mode by the vehicle's mass above this many resolutions 1/T is unreliable
INTERACTION_RESOLUTIONS = 0.5
#: main-lobe half-width of a window's spectrum in Rayleigh bins 1/T (Harris 1978, table 1); others: 2
MAIN_LOBE = {"boxcar": 1.0, "hann": 2.0, "hamming": 2.0, "blackman": 3.0}
#: a peak closer than this many main-lobe half-widths to a band edge is flagged
EDGE_LOBES = 1.0
#: a peak closer than this many main-lobe half-widths to a vehicle frequency is flagged ...
VEHICLE_LOBES = 2.0
#: ... or inside this many times the vehicle mode's half-power band f_v (1 ± ζ)
VEHICLE_HALF_BANDS = 1.0
#: driving frequencies n v / L checked, n = 1 ... N_DRIVING
N_DRIVING = 4
#: a rival local maximum within this many main-lobe half-widths ...
RIVAL_LOBES = 2.0
#: ... and less than this many dB below the peak makes it ambiguous
RIVAL_DB = 6.0
#: probability that noise alone gives a peak above the background threshold
FALSE_ALARM = 0.01
#: the local background: lines within this many main-lobe half-widths on each side of the peak
LOCAL_LOBES = 5.0
#: a peak within this fraction of the model's k-th bridge frequency is labelled bridge mode k
MODE_TOLERANCE = 0.20
#: a pass agrees with the multi-pass median within this many of its resolutions 1/T
AGREE_RESOLUTIONS = 1.0
#: reliable passes needed before a pass that disagrees with their median is flagged
MIN_PASSES = 3
#: a mode whose shape along the path moves the bridge's lobe more than this many resolutions 1/T from f_b is flagged
ENVELOPE_RESOLUTIONS = 0.5


def main_lobe(window: str) -> float:
    """Main-lobe half-width of ``window`` in units of 1/T (``MAIN_LOBE``; 2 for other windows)."""
    return MAIN_LOBE.get(window, 2.0)


def vehicle_modes(vehicle) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Undamped natural frequencies [Hz] of a vehicle on rigid ground and the modal damping ratios
    ζ_k = φ_kᵀ C φ_k / (2 ω_k) of its mass-normalised modes (suspension and tire dashpots;
    classical damping assumed)."""
    from scipy.linalg import eigh

    if vehicle.n_dof == 0:
        return np.zeros(0), np.zeros(0)
    c = vehicle.damping + vehicle.tire_damping_matrix()
    lam, phi = eigh(vehicle.stiffness + vehicle.tire_stiffness_matrix(), vehicle.mass)
    omega = np.sqrt(np.clip(lam, 0.0, None))
    zeta = np.array([float(phi[:, k] @ c @ phi[:, k]) / (2 * omega[k]) if omega[k] > 0 else 0.0
                     for k in range(omega.size)])
    return omega / (2 * np.pi), zeta


def interaction_shift(bridge, vehicle, lateral_offset: float, window: str = "hann", mode: int = 1,
                      positions: int = 21) -> float:
    """Estimated shift [Hz] of bridge mode ``mode``'s frequency while ``vehicle`` crosses on the line
    y = ``lateral_offset`` [m] (module docstring): at each of ``positions`` front-wheel positions over
    the deck the frozen system — the mode (mass-normalised, stiffness ω_b²) and the vehicle's DOFs,
    each wheel a spring k_w between its row and the deck φ(x_w) q — is solved, the frequency nearest
    f_b taken, and the shifts averaged with the weights φ(x_front)² × ``window`` over the record."""
    from scipy.linalg import eigh
    from scipy.signal import get_window

    if vehicle.n_dof == 0 or bridge.frequencies_hz.size < mode:
        return 0.0
    f_b = float(bridge.frequencies_hz[mode - 1])
    lo, hi = bridge.deck_extent
    front = np.linspace(lo, hi, positions)
    wheels = vehicle.wheels
    x = front[:, None] - np.array([w.offset for w in wheels], float)[None, :]          # (positions, wheels)
    on = (x >= lo) & (x <= hi)
    phi = np.zeros(x.shape)
    phi[on] = bridge.mode_shapes(x[on], np.full(int(on.sum()), float(lateral_offset)))[:, mode - 1]
    rows = np.array([np.asarray(w.row, float) for w in wheels])                         # (wheels, n)
    k_w = np.array([w.stiffness for w in wheels], float)
    n = vehicle.n_dof
    m = np.zeros((n + 1, n + 1))
    m[0, 0], m[1:, 1:] = 1.0, np.asarray(vehicle.mass, float)
    base = np.zeros((n + 1, n + 1))
    base[0, 0], base[1:, 1:] = (2 * math.pi * f_b) ** 2, np.asarray(vehicle.stiffness, float) + (rows.T * k_w) @ rows
    shifts = np.zeros(positions)
    for i in range(positions):
        k = base.copy()
        k[0, 0] += float(np.sum(k_w * phi[i] ** 2))
        k[0, 1:] = k[1:, 0] = -(k_w * phi[i]) @ rows
        f = np.sqrt(np.clip(eigh(k, m, eigvals_only=True), 0.0, None)) / (2 * math.pi)
        shifts[i] = f[int(np.argmin(np.abs(f - f_b)))] - f_b
    weights = bridge.mode_shapes(front, np.full(positions, float(lateral_offset)))[:, mode - 1] ** 2
    weights = weights * (get_window(window, positions, fftbins=False) if window != "boxcar" else 1.0)
    return float(np.sum(shifts * weights) / np.sum(weights)) if np.sum(weights) > 0 else 0.0


@dataclass(frozen=True)
class PeakQuality:
    """What an identified frequency is (``label``, ``label_hz`` the expected frequency it matches,
    NaN when none) and how reliable (module docstring): ``snr_db`` the peak against the
    background [dB] with its threshold ``snr_threshold_db``; ``vehicle_distance`` and
    ``edge_distance`` the distances to the nearest vehicle frequency and band edge in units of
    the resolution 1/T, with the flagging limits ``vehicle_limit`` and ``edge_limit`` (same
    unit); ``rival_db`` the highest other peak within ``RIVAL_LOBES`` main-lobe half-widths
    relative to this one [dB] (−inf: none); ``speed_correction_hz`` the correction applied; ``reasons`` why it is unreliable (empty:
    reliable)."""

    label: str
    label_hz: float
    snr_db: float
    snr_threshold_db: float
    vehicle_distance: float
    vehicle_limit: float
    edge_distance: float
    edge_limit: float
    local_maximum: bool
    rival_db: float = -math.inf
    speed_correction_hz: float = 0.0
    reasons: tuple[str, ...] = field(default=())
    interaction_hz: float = 0.0

    @property
    def reliable(self) -> bool:
        return not self.reasons

    @property
    def reason(self) -> str:
        """The reasons in words ('' when reliable)."""
        return "; ".join(self.reasons)


def _db(x: float) -> float:
    return 10.0 * math.log10(x) if x > 0 else -math.inf


def _local_maxima(psd: NDArray[np.float64]) -> NDArray[np.bool_]:
    out = np.zeros(psd.size, bool)
    out[1:-1] = (psd[1:-1] >= psd[:-2]) & (psd[1:-1] > psd[2:])
    return out


def _background(frequency, psd, f_peak, p_peak, band, lobe, resolution_hz) -> tuple[float, float, list[str]]:
    """Peak over background [dB], its threshold [dB] and the reason when below (module docstring)."""
    lo, hi = band
    outside = (frequency >= lo) & (frequency <= hi) & (np.abs(frequency - f_peak) > lobe)
    local = outside & (np.abs(frequency - f_peak) <= LOCAL_LOBES * lobe)
    levels = [float(np.median(psd[s])) for s in (outside, local) if s.any()]
    background = max(levels) if levels else 0.0
    snr = _db(p_peak / background) if background > 0 else math.inf
    threshold = _db(math.log2(max(1.0, (hi - lo) / resolution_hz) / FALSE_ALARM))
    if snr >= threshold:
        return snr, threshold, []
    return snr, threshold, [f"peak {snr:.1f} dB above the background, below the {threshold:.1f} dB that noise alone "
                            f"reaches in {100 * FALSE_ALARM:g} % of passes"]


def _rival(frequency, psd, f_peak, p_peak, band, lobe, resolution_hz) -> tuple[float, list[str]]:
    """The highest other local maximum within ``RIVAL_LOBES`` main lobes relative to the peak [dB], and the reason."""
    near = np.abs(frequency - f_peak)
    rivals = _local_maxima(psd) & (frequency >= band[0]) & (frequency <= band[1]) & (near > lobe) & (near <= RIVAL_LOBES * lobe)
    if not rivals.any() or p_peak <= 0:
        return -math.inf, []
    j = np.flatnonzero(rivals)[np.argmax(psd[rivals])]
    rival_db = _db(float(psd[j]) / p_peak)
    if rival_db <= -RIVAL_DB:
        return rival_db, []
    return rival_db, [f"ambiguous: a second peak at {frequency[j]:.4g} Hz, {near[j] / resolution_hz:.2f}/T away, at "
                      f"{rival_db:+.1f} dB of it (within {RIVAL_DB:g} dB)"]


def vehicle_limit(f_v: float, zeta: float, lobe: float, resolution_hz: float) -> float:
    """The distance from a vehicle frequency ``f_v`` [Hz] (damping ratio ``zeta``) inside which a
    peak is flagged, in units of 1/T: ``VEHICLE_LOBES`` main lobes ``lobe`` [Hz] or the half-power
    half-band ζ f_v, whichever is wider."""
    return max(VEHICLE_LOBES * lobe, VEHICLE_HALF_BANDS * zeta * f_v) / resolution_hz


def mode_envelope_offset(shape: ArrayLike, window: str = "hann") -> float:
    """Where the amplitude spectrum of a mode shape sampled uniformly along the vehicle's path over
    the deck (first to last sample: the deck), weighted by the record's ``window``, peaks, in cycles
    per deck length: the shift of the bridge's lobe from f_b in resolutions 1/T (module docstring;
    0 for one half-wave).  Zero-padded FFT, 64-fold."""
    from scipy.signal import get_window

    phi = np.asarray(shape, float)
    weighted = phi * get_window(window, phi.size, fftbins=False)
    n = 1 << int(np.ceil(np.log2(64 * phi.size)))
    return float(np.argmax(np.abs(np.fft.rfft(weighted, n))) * (phi.size - 1) / n)


def peak_quality(frequency: NDArray[np.float64], psd: NDArray[np.float64], f_peak: float, resolution_hz: float,
                 band: tuple[float, float], speed: float, span: float, window: str = "hann",
                 bridge_hz: ArrayLike = (), vehicle_hz: ArrayLike = (), vehicle_zeta: ArrayLike = (),
                 mode: int = 1, envelope_offset: float = 0.0, interaction_hz: float = 0.0) -> PeakQuality:
    """Label and quality of the peak at ``f_peak`` [Hz] of the spectrum (``frequency`` [Hz],
    ``psd``) searched in ``band`` [Hz] for a pass at ``speed`` [m/s] over ``span`` [m];
    ``bridge_hz`` the model's bridge frequencies (labels only), ``vehicle_hz`` and
    ``vehicle_zeta`` the vehicle's frequencies [Hz] and damping ratios (module docstring);
    ``mode`` the bridge mode sought (a peak labelled another bridge mode is unreliable for it);
    ``envelope_offset`` that mode's ``mode_envelope_offset`` along the path [cycles per span]: a
    lobe shift envelope_offset · v / L [Hz] above ``ENVELOPE_RESOLUTIONS`` resolutions is unreliable;
    ``interaction_hz`` the sought mode's shift by the vehicle's mass (``interaction_shift``): above
    ``INTERACTION_RESOLUTIONS`` resolutions, unreliable."""
    lobe = main_lobe(window) * resolution_hz
    lo, hi = band
    i_peak = int(np.argmin(np.abs(frequency - f_peak)))
    p_peak = float(psd[i_peak])
    snr, threshold, reasons = _background(frequency, psd, f_peak, p_peak, band, lobe, resolution_hz)
    rival_db, why = _rival(frequency, psd, f_peak, p_peak, band, lobe, resolution_hz)
    reasons += why
    # band edges and local maximum of the whole spectrum
    edge = min(f_peak - lo, hi - f_peak) / resolution_hz
    edge_limit = EDGE_LOBES * main_lobe(window)
    local_max = bool(p_peak >= psd[max(i_peak - 1, 0)] and p_peak >= psd[min(i_peak + 1, psd.size - 1)])
    if edge < edge_limit:
        reasons.append(f"at the search band's edge ({edge:.2f}/T from [{lo:g}, {hi:g}] Hz, inside the main lobe "
                       f"{edge_limit:g}/T)")
    elif not local_max:
        reasons.append("not a peak of the spectrum (the flank of a larger peak beyond the searched lines)")
    # the expected frequencies the peak may be: (distance [Hz], label, frequency, matches)
    candidates = []
    fv = np.atleast_1d(np.asarray(vehicle_hz, float))
    zeta = np.atleast_1d(np.asarray(vehicle_zeta, float)) if np.size(vehicle_zeta) else np.zeros(fv.size)
    fb = np.atleast_1d(np.asarray(bridge_hz, float))
    v_dist, v_limit = math.inf, VEHICLE_LOBES * main_lobe(window)
    for k, (f_v, z) in enumerate(zip(fv, zeta), start=1):
        limit = vehicle_limit(f_v, z, lobe, resolution_hz)
        d = abs(f_peak - f_v) / resolution_hz
        if d < v_dist:
            v_dist, v_limit = d, limit
        candidates.append((abs(f_peak - f_v), f"vehicle_{k}", float(f_v), d < limit))
        if d < limit:
            reasons.append(f"near the vehicle's own frequency {f_v:.3g} Hz ({d:.2f}/T away, inside {limit:.2f}/T)")
        d_model = abs(fb[mode - 1] - f_v) / resolution_hz if fb.size >= mode else math.inf
        if d_model < limit:
            reasons.append(f"the model's bridge mode {mode} ({fb[mode - 1]:.4g} Hz) lies {d_model:.2f}/T from the "
                           f"vehicle's {f_v:.3g} Hz, inside {limit:.2f}/T: a pass this short cannot separate them")
    for n in range(1, N_DRIVING + 1):
        f_d = n * speed / span
        candidates.append((abs(f_peak - f_d), f"driving_{n}", f_d, abs(f_peak - f_d) < lobe))
        if abs(f_peak - f_d) < lobe:
            reasons.append(f"at the driving frequency {n} v/L = {f_d:.3g} Hz")
    for k, f_b in enumerate(fb, start=1):
        candidates.append((abs(f_peak - f_b), f"bridge_{k}", float(f_b), abs(f_peak / f_b - 1) <= MODE_TOLERANCE))
    matching = sorted(c for c in candidates if c[3])
    label, label_hz = (matching[0][1], matching[0][2]) if matching else ("none", math.nan)
    if label.startswith("bridge_") and label != f"bridge_{mode}":
        reasons.append(f"the peak is bridge mode {label[7:]} (model {label_hz:.4g} Hz), not mode {mode} sought")
    if fb.size >= mode and not lo <= fb[mode - 1] <= hi:
        reasons.append(f"the model's bridge mode {mode} ({fb[mode - 1]:.4g} Hz) lies outside the search band "
                       f"[{lo:g}, {hi:g}] Hz: no peak of it can be found")
    shift_hz = envelope_offset * speed / span  # the lobe's shift from f_b [Hz]; k L / T with T = L / v
    if shift_hz > ENVELOPE_RESOLUTIONS * resolution_hz:
        reasons.append(f"bridge mode {mode} of the model is not one half-wave along the deck (several spans): the "
                       f"contact point sees it modulated by its shape, so its lobe lies at f_b ± {shift_hz:.3g} Hz "
                       f"({shift_hz / resolution_hz:.2f} resolutions, above {ENVELOPE_RESOLUTIONS:g}), not at f_b")
    if abs(interaction_hz) > INTERACTION_RESOLUTIONS * resolution_hz and fb.size >= mode:
        reasons.append(f"the vehicle's mass shifts bridge mode {mode} by about {interaction_hz:+.3g} Hz "
                       f"({100 * interaction_hz / fb[mode - 1]:+.2f} %, {abs(interaction_hz) / resolution_hz:.2f} resolutions, "
                       f"above {INTERACTION_RESOLUTIONS:g}) while it is on the deck: the peak is the bridge carrying the "
                       "vehicle, and the bias is the same in every pass")
    if not matching and fb.size:
        reasons.append(f"matches no expected frequency (bridge modes of the model within ±{100 * MODE_TOLERANCE:g} %, "
                       "vehicle, driving)")
    return PeakQuality(label, label_hz, snr, threshold, v_dist, v_limit, edge, edge_limit, local_max, rival_db, 0.0,
                       tuple(reasons), float(interaction_hz))


@dataclass(frozen=True)
class MultiPass:
    """The frequency of one bridge from several passes: ``median``, ``q25``/``q75`` (interquartile
    range), ``mean``, ``std`` [Hz] over the reliable passes; ``n_passes``, ``n_reliable`` and
    ``n_agree`` (reliable passes within ``AGREE_RESOLUTIONS`` of their resolutions 1/T of the median);
    ``agrees`` per pass (False for an unreliable pass)."""

    median: float
    q25: float
    q75: float
    mean: float
    std: float
    n_passes: int
    n_reliable: int
    n_agree: int
    agrees: NDArray[np.bool_]


def multipass_estimate(frequency_hz: ArrayLike, resolution_hz: ArrayLike, reliable: ArrayLike) -> MultiPass:
    """Median, interquartile range, mean and standard deviation of the reliable passes'
    frequencies [Hz], and which passes agree with the median (module docstring)."""
    f = np.asarray(frequency_hz, float)
    res = np.asarray(resolution_hz, float)
    ok = np.asarray(reliable, bool) & np.isfinite(f)
    if not ok.any():
        return MultiPass(*([math.nan] * 5), int(f.size), 0, 0, np.zeros(f.size, bool))
    g = f[ok]
    med = float(np.median(g))
    q25, q75 = (float(q) for q in np.percentile(g, [25, 75]))
    agrees = ok & (np.abs(f - med) <= AGREE_RESOLUTIONS * res)
    return MultiPass(med, q25, q75, float(g.mean()), float(g.std(ddof=1)) if g.size > 1 else math.nan,
                     int(f.size), int(ok.sum()), int(agrees.sum()), agrees)


def unconverged_pass_flags(counts: NDArray) -> list[Flag]:
    """The ``contact_not_converged`` dataset flag of a sweep whose passes (cases, in the dataset's
    order) counted ``counts`` unconverged contact steps each (``unconverged_dataset_flags``; none
    when every count is 0 or NaN)."""
    return unconverged_dataset_flags(counts, "pass", lambda index: f"case {index[0]}", plural="passes")
