"""Instrumented vehicles: sensors on vehicle bodies and axles, sampled like a data logger.

A sensor sits on a rigid body of the vehicle (``body``, any body of a
[`VehicleBuilder`][vbikit.vehicle.VehicleBuilder] vehicle: a sprung body, a trailer, an axle) at
the longitudinal position ``position`` s [m] (rearward from the front axle, the vehicle
convention) and lateral position y [m]; its vertical motion is

    z_sensor = (h + (s_cg − s)·p + y·r) · q

with h, p, r the body's heave, pitch and roll rows and s_cg its centre of gravity (vehicle
conventions, ``vbikit.vehicle.model``: pitch nose-up, roll raising the left side).  A sensor on
``axle = k`` sits on the wheel centres of the k-th axle (axles ordered by their distance behind
the front axle), the mean of its left and right wheel rows.  ``quantity`` is acceleration
[m/s²], velocity [m/s] or displacement [m] (from the sensor's position at the start of the
record: the vehicle at rest on the approach).

Sampling ([`Sampling`][vbikit.driveby.Sampling]): the simulated history at the integration step is
low-pass filtered by a Butterworth filter of order ``filter_order`` with its −3 dB cut-off at
``cutoff`` × the sensor rate (default 0.4: below the sensor's Nyquist frequency, 0.5 × rate),
applied forward and backward (``scipy.signal.sosfiltfilt``: zero phase, the squared magnitude
response); the filtered history is then resampled at the sensor rate (linear interpolation at
t_k = t_0 + k / rate: exact decimation when the integration step divides the sensor period).
Filtering comes before resampling, so nothing above the cut-off folds back.  Noise is then
added at the sensor rate: white Gaussian noise of standard deviation ``noise_rms`` (units of the
quantity), or of rms(signal) / 10^(``noise_snr_db``/20) for a signal-to-noise ratio in dB, from
``numpy.random.default_rng((seed, sensor index))`` — seeded, reproducible, independent per sensor.
"""
from __future__ import annotations

import functools

import logging
from dataclasses import dataclass, field
from typing import Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._validation import number
from vbikit.errors import VbikitError
from vbikit.vehicle.model import CombinedVehicle, Vehicle

log = logging.getLogger(__name__)

#: measurable quantities: name -> (unit, time derivative of the displacement)
QUANTITIES: dict[str, tuple[str, int]] = {"displacement": ("m", 0), "velocity": ("m/s", 1), "acceleration": ("m/s^2", 2)}


#: a sensor's position s may lie this far ahead of the front axle or behind the last one [m] (overhangs)
MAX_OVERHANG = 3.0
#: the largest lateral position |y| of a sensor [m] (a road vehicle is at most 2.55 m wide; its mirrors, a rack)
MAX_LATERAL = 2.0
#: the largest noise_rms [units of the quantity]: 1,000 m/s², m/s or m is far beyond any sensor's noise
MAX_NOISE_RMS = 1e3


class SensorError(VbikitError):
    """An invalid sensor or sampling definition; the message names the key."""

    message_names_key = True


@dataclass(frozen=True)
class Sensor:
    """One sensor on an instrumented vehicle (module docstring).

    Parameters
    ----------
    name : str
        Label of the sensor (dataset coordinate).
    body : str, optional
        Name of the rigid body it is fixed to (``vehicle.bodies``); give ``body`` or ``axle``.
    axle : int, optional
        1-based axle number (axles in order of their distance behind the front axle).
    position : float, optional
        s [m] rearward from the front axle on the body; default the body's centre of gravity.
    lateral : float
        y [m] from the vehicle centreline (positive left).
    quantity : str
        "acceleration", "velocity" or "displacement".
    noise_rms : float
        Standard deviation of the added white noise [units of the quantity], ≥ 0.
    noise_snr_db : float, optional
        Signal-to-noise ratio [dB] instead of ``noise_rms``.
    vehicle : int
        1-based vehicle number in a crossing of several vehicles.
    """

    name: str
    body: Optional[str] = None
    axle: Optional[int] = None
    position: Optional[float] = None
    lateral: float = 0.0
    quantity: str = "acceleration"
    noise_rms: float = 0.0
    noise_snr_db: Optional[float] = None
    vehicle: int = 1

    def __post_init__(self) -> None:
        import re

        if not isinstance(self.name, str) or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]{0,39}", self.name):
            raise SensorError(f"sensors.name: {self.name!r} must be a letter then letters, digits or _ (at most 40)")
        key = f"sensors.{self.name}"
        if (self.body is None) == (self.axle is None):
            raise SensorError(f"{key}: give body (a vehicle body's name) or axle (an axle number), one of them")
        if self.body is not None and not isinstance(self.body, str):
            raise SensorError(f"{key}.body: expected a body's name (a string), got {type(self.body).__name__}")
        if self.axle is not None:
            number(self.axle, f"{key}.axle", 1, 100, integer=True, error=SensorError)
        if self.position is not None:
            number(self.position, f"{key}.position", -MAX_OVERHANG, 100.0, unit="m", error=SensorError)
        number(self.lateral, f"{key}.lateral", -MAX_LATERAL, MAX_LATERAL, unit="m", error=SensorError)
        number(self.vehicle, f"{key}.vehicle", 1, 1000, integer=True, error=SensorError)
        if not isinstance(self.quantity, str) or self.quantity not in QUANTITIES:
            raise SensorError(f"{key}.quantity: {self.quantity!r} is not measurable; allowed: {', '.join(QUANTITIES)}")
        number(self.noise_rms, f"{key}.noise_rms", 0.0, MAX_NOISE_RMS, unit="units of the quantity", error=SensorError)
        if self.noise_snr_db is not None:
            number(self.noise_snr_db, f"{key}.noise_snr_db", -20.0, 200.0, unit="dB", error=SensorError)
        if self.noise_snr_db is not None and self.noise_rms > 0:
            raise SensorError(f"{key}: give noise_rms or noise_snr_db, not both")

    @property
    def unit(self) -> str:
        return QUANTITIES[self.quantity][0]


@dataclass(frozen=True)
class Sampling:
    """The data logger: sensor rate [Hz] and anti-alias filter (module docstring).

    ``rate`` > 0 [Hz]; ``filter_order`` Butterworth order (1–12; applied twice: zero phase);
    ``cutoff`` its −3 dB frequency as a fraction of the rate, in (0, 0.5)."""

    rate: float = 200.0
    filter_order: int = 8
    cutoff: float = 0.4

    def __post_init__(self) -> None:
        number(self.rate, "sampling.rate", 1.0, 1e5, unit="Hz", error=SensorError)
        number(self.filter_order, "sampling.filter_order", 1, 12, integer=True, error=SensorError)
        number(self.cutoff, "sampling.cutoff", 0.0, 0.5, lo_open=True, hi_open=True, unit="fraction of the rate",
               error=SensorError)

    @property
    def cutoff_hz(self) -> float:
        return self.cutoff * self.rate


@dataclass(frozen=True)
class Measurement:
    """Sensor histories at the sensor rate.

    ``time`` [s] (n_s,); ``values`` (n_sensors, n_s) with noise; ``clean`` the same without
    noise (filtered and resampled: what a perfect sensor of this rate would record); ``sensors``
    and ``sampling`` as given; ``noise_std`` the standard deviation of each sensor's noise."""

    time: NDArray[np.float64]
    values: NDArray[np.float64]
    clean: NDArray[np.float64]
    sensors: tuple[Sensor, ...]
    sampling: Sampling
    noise_std: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        for i, s in enumerate(self.sensors):
            if s.name == name:
                return self.values[i]
        raise KeyError(f"no sensor named {name!r}; sensors: {', '.join(s.name for s in self.sensors)}")

    @property
    def dt(self) -> float:
        return 1.0 / self.sampling.rate


def _part(vehicle: Vehicle, index: int) -> tuple[Vehicle, int]:
    """(vehicle ``index`` (1-based), its first DOF in ``vehicle``)."""
    if isinstance(vehicle, CombinedVehicle):
        if not 1 <= index <= len(vehicle.parts):
            raise SensorError(f"sensors.vehicle: {index} is not a vehicle of this crossing (1 … {len(vehicle.parts)})")
        return vehicle.parts[index - 1], vehicle.dof_offsets[index - 1]
    if index != 1:
        raise SensorError(f"sensors.vehicle: the crossing has one vehicle, got vehicle = {index}")
    return vehicle, 0


def axle_offsets(vehicle: Vehicle) -> list[float]:
    """Distinct wheel offsets s [m] (axles), front first."""
    return sorted({round(w.offset, 9) for w in vehicle.wheels})


def sensor_row(vehicle: Vehicle, sensor: Sensor) -> NDArray[np.float64]:
    """Row c with z_sensor = c · q over the DOFs of ``vehicle`` (one vehicle, or a crossing's
    combined vehicles)."""
    part, first = _part(vehicle, sensor.vehicle)
    key = f"sensors.{sensor.name}"
    if sensor.body is not None:
        if sensor.body not in part.bodies:
            allowed = ", ".join(part.bodies) or "none (a vehicle without bodies)"
            raise SensorError(f"{key}.body: {sensor.body!r} is not a body of vehicle {part.name!r}; bodies: {allowed}")
        s_cg, heave, pitch, roll = part.bodies[sensor.body]
        s = s_cg if sensor.position is None else float(sensor.position)
        offsets = [w.offset for w in part.wheels] or [s_cg]
        lo, hi = min(offsets + [s_cg]) - MAX_OVERHANG, max(offsets + [s_cg]) + MAX_OVERHANG
        if not lo <= s <= hi:
            raise SensorError(f"{key}.position: {s:g} m is off the vehicle {part.name!r}: a sensor sits within "
                              f"{lo:g} … {hi:g} m behind the front axle (its axles ± {MAX_OVERHANG:g} m)")
        local = heave + (s_cg - s) * pitch + sensor.lateral * roll
    else:
        axles = axle_offsets(part)
        if not 1 <= int(sensor.axle) <= len(axles):
            raise SensorError(f"{key}.axle: vehicle {part.name!r} has axles 1 … {len(axles)}, got {sensor.axle}")
        s = axles[int(sensor.axle) - 1]
        rows = [w.row for w in part.wheels if abs(w.offset - s) < 1e-9 and w.row.size]
        if not rows:
            raise SensorError(f"{key}.axle: axle {sensor.axle} of {part.name!r} has no degrees of freedom (a moving force)")
        local = np.mean(rows, axis=0)
    row = np.zeros(vehicle.n_dof)
    row[first:first + part.n_dof] = local
    return row


def design_filter(sampling: Sampling, fs_in: float) -> NDArray[np.float64]:
    """Second-order sections of the anti-alias Butterworth low-pass at the input rate ``fs_in`` [Hz]."""
    if sampling.cutoff_hz >= 0.5 * fs_in:
        raise SensorError(f"sampling.rate: {sampling.rate:g} Hz needs histories faster than {2 * sampling.cutoff_hz:g} Hz "
                          f"(the filter cut-off {sampling.cutoff_hz:g} Hz must be below half the simulation rate "
                          f"{fs_in:g} Hz); use a smaller crossing.dt or a lower sampling.rate")
    return _butter(int(sampling.filter_order), float(sampling.cutoff_hz), float(fs_in)).copy()


@functools.lru_cache(maxsize=32)
def _butter(order: int, cutoff_hz: float, fs_in: float) -> NDArray[np.float64]:
    """``scipy.signal.butter`` sections, designed once per (order, cut-off, rate): the passes of a
    dataset share their filter."""
    from scipy.signal import butter

    return butter(order, cutoff_hz, btype="low", fs=fs_in, output="sos")


def resample(time: NDArray[np.float64], history: NDArray[np.float64], sampling: Sampling,
             t_start: float | None = None, t_end: float | None = None) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Anti-alias filter ``history`` (…, n_t) given at ``time`` (uniform) and resample it at the sensor
    rate over [t_start, t_end] (default the whole record); returns (sensor times, values)."""
    from scipy.signal import sosfiltfilt

    dt = float(time[1] - time[0])
    sos = design_filter(sampling, 1.0 / dt)
    filtered = sosfiltfilt(sos, history, axis=-1) if history.shape[-1] > 3 * (2 * len(sos) + 1) else history
    t0 = float(time[0]) if t_start is None else float(t_start)
    t1 = float(time[-1]) if t_end is None else float(t_end)
    n = int(np.floor((t1 - t0) * sampling.rate * (1 + 1e-12))) + 1
    t = t0 + np.arange(n) / sampling.rate
    flat = filtered.reshape(-1, filtered.shape[-1])
    out = np.stack([np.interp(t, time, f) for f in flat]).reshape(*filtered.shape[:-1], n)
    return t, out


def measure(result, sensors: Sequence[Sensor], sampling: Sampling, seed: int = 0) -> Measurement:
    """The sensors' histories of a simulated crossing (``CrossingResult``) at the sensor rate.

    Raw history z = c · q (or c · q̇, c · q̈) at the integration step, anti-alias filtered,
    resampled, then seeded noise added (module docstring)."""
    sensors = tuple(sensors)
    if not sensors:
        raise SensorError("sensors: an instrumented vehicle needs at least one [[sensors]] table")
    names = [s.name for s in sensors]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise SensorError(f"sensors.name: each sensor needs its own name; repeated: {', '.join(dup)}")
    vehicle = result.crossing.vehicle
    states = (result.q - result.q[0], result.q_dot, result.q_ddot)
    raw = np.stack([states[QUANTITIES[s.quantity][1]] @ sensor_row(vehicle, s) for s in sensors])
    t, clean = resample(result.time, raw, sampling)
    std = np.zeros(len(sensors))
    noisy = clean.copy()
    for i, s in enumerate(sensors):
        if s.noise_snr_db is not None:
            std[i] = float(np.sqrt(np.mean(clean[i] ** 2))) / 10.0 ** (s.noise_snr_db / 20.0)
        else:
            std[i] = s.noise_rms
        if std[i] > 0:
            noisy[i] = clean[i] + std[i] * np.random.default_rng((int(seed), i)).standard_normal(t.size)
    return Measurement(t, noisy, clean, sensors, sampling, std)


#: rows of ``contact_truth``: name -> (units, long name)
CONTACT_TRUTH: dict[str, tuple[str, str]] = {
    "contact_displacement": ("m", "deck displacement under the instrumented vehicle's front wheel, z up (the model's "
                                  "truth, no road, no noise; 0 off the deck), filtered and resampled like the sensors"),
    "contact_acceleration": ("m s-2", "deck acceleration under the instrumented vehicle's front wheel, sum of the modal "
                                      "accelerations times the mode shapes there (the model's truth, no noise; 0 off "
                                      "the deck), filtered and resampled like the sensors"),
}


def contact_truth(result, sampling: Sampling) -> NDArray[np.float64]:
    """The bridge's response at the contact point of wheel 0 (the instrumented vehicle's front
    wheel) at the sensor rate, rows ``CONTACT_TRUTH``: w(x_c(t), t) = Σ_m ξ_m(t) φ_m(x_c(t), y_c)
    and Σ_m ξ̈_m(t) φ_m(x_c(t), y_c), with y_c the lateral position of the wheel's first contact
    point; anti-alias filtered and resampled as the sensors are (``resample``)."""
    crossing = result.crossing
    bridge = crossing.bridge
    x = result.wheel_positions()[:, 0]
    _, _, y = crossing.point_kinematics()
    yp = float(y[np.flatnonzero(crossing.contact.wheel == 0)[0]])
    lo, hi = bridge.deck_extent
    on = (x >= lo) & (x <= hi)
    rows = np.zeros((len(CONTACT_TRUTH), x.size))
    if on.any():
        phi = bridge.mode_shapes(x[on], np.full(int(on.sum()), yp))
        rows[0, on] = np.einsum("tm,tm->t", result.xi[on], phi)
        rows[1, on] = np.einsum("tm,tm->t", result.xi_ddot[on], phi)
    return resample(result.time, rows, sampling)[1]


def amplitude_spectrum(records: NDArray[np.float64], n_fft: int) -> NDArray[np.float64]:
    """Single-sided amplitude spectrum of each row of ``records`` (…, N), zero-padded to ``n_fft``
    points: A_k = c_k |X_k| / N with X = DFT, c_0 = 1 (and c = 1 at the Nyquist line of an even
    ``n_fft``), c_k = 2 otherwise, so that a sinusoid of amplitude a on a line of the record gives
    A = a there (rectangular window, no detrending).  Frequencies ``numpy.fft.rfftfreq(n_fft, 1/rate)``."""
    records = np.asarray(records, float)
    n = records.shape[-1]
    if n > n_fft:
        raise SensorError(f"amplitude_spectrum: a record of {n} samples is longer than the spectrum's {n_fft} points")
    a = np.abs(np.fft.rfft(records, n=n_fft, axis=-1)) * (2.0 / max(n, 1))
    a[..., 0] *= 0.5
    if n_fft % 2 == 0:
        a[..., -1] *= 0.5
    return a
