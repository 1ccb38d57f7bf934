"""Vertical track irregularities: PSDs of the rail's vertical profile and random profiles from them.

Spectra, Ω the angular wavenumber [rad/m], S_v(Ω) one-sided [m²/(rad/m)]:

* German high-speed spectra, low and high disturbance (as tabulated by Zhai 2020 with the track
  irregularity spectra, and by Guo, Xia, De Roeck & Liu 2012):

      S_v(Ω) = A_v Ω_c² / ((Ω² + Ω_r²)(Ω² + Ω_c²)),   Ω_c = 0.8246 rad/m, Ω_r = 0.0206 rad/m,
      A_v = 4.032e-7 m·rad (low) / 1.080e-6 m·rad (high)

* US Federal Railroad Administration classes 1–6 (Garg & Dukkipati 1984, after Hamid &
  Yang 1981):

      S_v(Ω) = k A_v Ω_c² / (Ω² (Ω² + Ω_c²)),   k = 0.25, Ω_c = 0.8245 rad/m,
      A_v = 1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339 cm²·rad/m (class 1 … 6)

The profile generator is vbikit's road generator ([`random_profile`][vbikit.road.random_profile], paper Eq. 7):
a [`TrackPSD`][vbikit.road.TrackPSD] presents the spectrum in the road PSD's terms — a callable
giving the one-sided displacement PSD G(n) [m³/cycle] of the wavenumber n = Ω/2π [cycle/m], with
the band [n_min, n_max] — so the same seeded mechanism builds roads and tracks:
G(n) = 2π S_v(2πn), since S_v dΩ = G dn.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.road.profile import RoadProfile
from vbikit.road.psd import ISO_N0, random_profile

Spectrum = Callable[[NDArray[np.float64], "TrackPSD"], NDArray[np.float64]]
Integral = Callable[[float, "TrackPSD"], float]


def _german(omega: NDArray[np.float64], p: "TrackPSD") -> NDArray[np.float64]:
    return p.A_v * p.omega_c**2 / ((omega**2 + p.omega_r**2) * (omega**2 + p.omega_c**2))


def _german_primitive(omega: float, p: "TrackPSD") -> float:
    # A Ωc²/(Ωc² − Ωr²) · [atan(Ω/Ωr)/Ωr − atan(Ω/Ωc)/Ωc]  (partial fractions)
    c, r = p.omega_c, p.omega_r
    return p.A_v * c**2 / (c**2 - r**2) * (np.arctan(omega / r) / r - np.arctan(omega / c) / c)


def _fra(omega: NDArray[np.float64], p: "TrackPSD") -> NDArray[np.float64]:
    return p.k * p.A_v * p.omega_c**2 / (omega**2 * (omega**2 + p.omega_c**2))


def _fra_primitive(omega: float, p: "TrackPSD") -> float:
    # k A [−1/Ω − atan(Ω/Ωc)/Ωc]  (partial fractions)
    return p.k * p.A_v * (-1.0 / omega - np.arctan(omega / p.omega_c) / p.omega_c)


#: spectrum family -> (S_v(Ω) [m²/(rad/m)], a primitive of S_v in Ω [m²])
TRACK_SPECTRUM_FORMS: dict[str, tuple[Spectrum, Integral]] = {
    "german": (_german, _german_primitive),
    "fra": (_fra, _fra_primitive),
}


@dataclass(frozen=True)
class TrackPSD:
    """A vertical track-irregularity spectrum (module docstring) and its wavenumber band.

    Parameters
    ----------
    form : {"german", "fra"}
        The spectrum's formula.
    A_v : float
        Roughness coefficient [m²·rad/m].
    omega_c : float
        Cut-off wavenumber Ω_c [rad/m].
    omega_r : float
        Ω_r [rad/m] (German spectra only).
    k : float
        Safety factor k [-] (FRA spectra only; 0.25).
    n_min, n_max : float
        The band [cycle/m] of the generated profile (wavelengths 1/n_max … 1/n_min).
    name : str
        Label.
    """

    form: str
    A_v: float
    omega_c: float
    omega_r: float = 0.0
    k: float = 1.0
    n_min: float = 1.0 / 80.0
    n_max: float = 1.0
    name: str = ""

    def __post_init__(self) -> None:
        if self.form not in TRACK_SPECTRUM_FORMS:
            raise ValueError(f"unknown track spectrum form {self.form!r}; allowed: {', '.join(TRACK_SPECTRUM_FORMS)}")
        if not (np.isfinite(self.A_v) and self.A_v >= 0):
            raise ValueError(f"track spectrum A_v must be >= 0 m²·rad/m, got {self.A_v!r}")
        if not (np.isfinite(self.omega_c) and self.omega_c > 0):
            raise ValueError(f"track spectrum omega_c must be > 0 rad/m, got {self.omega_c!r}")
        if self.form == "german" and not (0 < self.omega_r < self.omega_c):
            raise ValueError(f"German track spectrum needs 0 < omega_r < omega_c (rad/m), got {self.omega_r!r}")
        if not (np.isfinite(self.k) and self.k > 0):
            raise ValueError(f"track spectrum k must be > 0, got {self.k!r}")
        if not (0 < self.n_min < self.n_max and np.isfinite(self.n_max)):
            raise ValueError(f"need 0 < n_min < n_max (cycle/m), got {self.n_min!r}, {self.n_max!r}")

    @classmethod
    def named(cls, name: str, **band: float) -> "TrackPSD":
        """A registered spectrum (``vbikit.road.TRACK_PSDS``), optionally with another band
        (``n_min``, ``n_max`` [cycle/m])."""
        try:
            psd = TRACK_PSDS[name.lower()]
        except KeyError:
            raise ValueError(f"unknown track spectrum {name!r}; allowed: {', '.join(TRACK_PSDS)}") from None
        return dataclasses.replace(psd, **band) if band else psd

    def spectrum(self, omega: ArrayLike) -> NDArray[np.float64]:
        """S_v(Ω) [m²/(rad/m)] at angular wavenumbers Ω [rad/m] (one-sided)."""
        return TRACK_SPECTRUM_FORMS[self.form][0](np.asarray(omega, float), self)

    def __call__(self, n: ArrayLike) -> NDArray[np.float64]:
        """G(n) = 2π S_v(2πn) [m³/cycle] at wavenumbers n [cycle/m] (the road PSD's terms)."""
        n = np.asarray(n, float)
        return 2.0 * np.pi * self.spectrum(2.0 * np.pi * n)

    @property
    def phi0(self) -> float:
        """G at ISO 8608's reference wavenumber n₀ = 0.1 cycle/m [m³/cycle] (for labels)."""
        return float(self(ISO_N0))

    def band_variance(self) -> float:
        """∫ G(n) dn over [n_min, n_max] = ∫ S_v(Ω) dΩ over 2π n_min … 2π n_max, in m² (closed form)."""
        primitive = TRACK_SPECTRUM_FORMS[self.form][1]
        return float(primitive(2 * np.pi * self.n_max, self) - primitive(2 * np.pi * self.n_min, self))


#: [public] German high-speed spectra: Ω_c, Ω_r [rad/m] and A_v [m²·rad/m] (module docstring).
#: Band [substitute]: wavelengths 1–80 m (n = 0.0125–1 cycle/m), the range commonly simulated
#: for vehicle–bridge dynamics.
GERMAN_OMEGA_C, GERMAN_OMEGA_R = 0.8246, 0.0206
GERMAN_A_V: dict[str, float] = {"low": 4.032e-7, "high": 1.080e-6}
#: [public] FRA classes: k, Ω_c [rad/m] and A_v [cm²·rad/m] (module docstring).
#: Band [public]: wavelengths 1.524–304.8 m (5–1000 ft), the FRA spectra's range.
FRA_K, FRA_OMEGA_C = 0.25, 0.8245
FRA_A_V_CM2: dict[int, float] = {1: 1.2107, 2: 1.0181, 3: 0.6816, 4: 0.5376, 5: 0.2095, 6: 0.0339}

#: Registered vertical track-irregularity spectra, by name.
TRACK_PSDS: dict[str, TrackPSD] = {
    **{f"german-{level}": TrackPSD("german", a, GERMAN_OMEGA_C, GERMAN_OMEGA_R, n_min=1 / 80.0, n_max=1.0,
                                   name=f"German high-speed, {level} disturbance")
       for level, a in GERMAN_A_V.items()},
    **{f"fra-{c}": TrackPSD("fra", a * 1e-4, FRA_OMEGA_C, k=FRA_K, n_min=1 / 304.8, n_max=1 / 1.524,
                            name=f"FRA class {c}")
       for c, a in FRA_A_V_CM2.items()},
}


def track_profile(psd: TrackPSD | str, seed: int, spacing: float = 0.05, length: float = 1000.0,
                  x_start: float | None = None, label: str = "") -> RoadProfile:
    """One vertical rail profile (elevation, z up) [m] from ``psd``, reproducible from ``seed``.

    The road generator ([`random_profile`][vbikit.road.random_profile], paper Eq. 7) with the track
    spectrum: r(x) = Σ_k √(2 G(n_k) Δn) cos(2π n_k x + θ_k) over the band.  ``spacing`` [m]
    ([substitute] 0.05 m: ≥ 10 samples per shortest default wavelength, 1 m), ``length`` and
    ``x_start`` [m] as there.
    """
    if isinstance(psd, str):
        psd = TrackPSD.named(psd)
    return random_profile(psd, seed, spacing=spacing, length=length, x_start=x_start,  # type: ignore[arg-type]
                          label=label or f"{psd.name or psd.form} track, seed {seed}")
