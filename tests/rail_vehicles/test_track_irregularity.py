# Vertical track-irregularity spectra and profiles, against the sources' formulas and constants
# written out here: German high-speed spectra (Ω_c = 0.8246, Ω_r = 0.0206 rad/m; A_v = 4.032e-7 /
# 1.080e-6 m·rad; Zhai 2020) and FRA classes (k = 0.25, Ω_c = 0.8245 rad/m, A_v in cm²·rad/m;
# Garg & Dukkipati 1984), integrated with scipy.integrate.quad.
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from vbikit.road import TRACK_PSDS, RoadProfile, TrackPSD, track_profile


def german(omega, a_v):
    return a_v * 0.8246**2 / ((omega**2 + 0.0206**2) * (omega**2 + 0.8246**2))


def fra(omega, a_v_cm2):
    return 0.25 * a_v_cm2 * 1e-4 * 0.8245**2 / (omega**2 * (omega**2 + 0.8245**2))


def test_spectrum_values_by_hand():
    """S_v at a few wavenumbers, hand arithmetic from the printed constants."""
    # German low, Ω = 0.1 rad/m: 4.032e-7 · 0.67996516 / ((0.01 + 0.00042436)(0.01 + 0.67996516))
    #   = 2.74162e-7 / (0.01042436 · 0.68996516) = 2.74162e-7 / 7.19245e-3 = 3.81181e-5 m²/(rad/m)
    assert TRACK_PSDS["german-low"].spectrum(0.1) == pytest.approx(3.81181e-5, rel=1e-5)
    # German high = low × 1.080e-6 / 4.032e-7 at every Ω
    assert TRACK_PSDS["german-high"].spectrum(0.1) == pytest.approx(3.81181e-5 * 1.080e-6 / 4.032e-7, rel=1e-5)
    # FRA class 4, Ω = 1 rad/m: 0.25 · 0.5376e-4 · 0.67980 / (1 · 1.67980) = 5.4390e-6 m²/(rad/m)
    assert TRACK_PSDS["fra-4"].spectrum(1.0) == pytest.approx(5.4390e-6, rel=1e-4)
    # FRA class 1 vs 6 at Ω = 0.3 rad/m: ratio of A_v, 1.2107 / 0.0339
    assert TRACK_PSDS["fra-1"].spectrum(0.3) / TRACK_PSDS["fra-6"].spectrum(0.3) == pytest.approx(1.2107 / 0.0339, rel=1e-12)
    omega = np.array([0.05, 0.4, 2.0, 5.0])
    np.testing.assert_allclose(TRACK_PSDS["german-high"].spectrum(omega), german(omega, 1.080e-6), rtol=1e-13)
    for c, a in {1: 1.2107, 2: 1.0181, 3: 0.6816, 4: 0.5376, 5: 0.2095, 6: 0.0339}.items():
        np.testing.assert_allclose(TRACK_PSDS[f"fra-{c}"].spectrum(omega), fra(omega, a), rtol=1e-13)


def test_wavenumber_form_preserves_variance():
    """G(n) [m³/cycle] of n = Ω/2π integrates to the same variance as S_v(Ω) (the factor 2π)."""
    psd = TRACK_PSDS["german-low"]
    var_n = quad(lambda n: float(psd(n)), psd.n_min, psd.n_max, limit=200)[0]
    var_omega = quad(lambda w: german(w, 4.032e-7), 2 * np.pi * psd.n_min, 2 * np.pi * psd.n_max, limit=200)[0]
    assert var_n == pytest.approx(var_omega, rel=1e-9)


@pytest.mark.parametrize("name", sorted(TRACK_PSDS))
def test_band_variance_closed_form(name):
    """The closed-form band integral against quad of the formula written above."""
    psd = TRACK_PSDS[name]
    f = (lambda w: german(w, psd.A_v)) if name.startswith("german") else \
        (lambda w: fra(w, {1: 1.2107, 2: 1.0181, 3: 0.6816, 4: 0.5376, 5: 0.2095, 6: 0.0339}[int(name[-1])]))
    ref = quad(f, 2 * np.pi * psd.n_min, 2 * np.pi * psd.n_max, limit=400, epsrel=1e-12)[0]
    assert psd.band_variance() == pytest.approx(ref, rel=1e-9)


def test_band_defaults():
    """German: wavelengths 1–80 m; FRA: 1.524–304.8 m (5–1000 ft)."""
    assert (TRACK_PSDS["german-low"].n_min, TRACK_PSDS["german-low"].n_max) == (1 / 80, 1.0)
    assert TRACK_PSDS["fra-3"].n_min == pytest.approx(1 / 304.8) and TRACK_PSDS["fra-3"].n_max == pytest.approx(1 / 1.524)


@pytest.mark.parametrize("name", ["german-low", "fra-5"])
def test_profile_periodogram_and_variance(name):
    """One seeded profile: its periodogram over one period equals G(n_k) at every in-band grid
    wavenumber (Eq. 7 has deterministic amplitudes), zero outside the band.  Its variance is then
    the rectangle sum Σ G(n_k) Δn over the grid n_k = k/P, which by Euler–Maclaurin is
    ∫ G dn over [n_first, n_last] + Δn (G(n_first) + G(n_last))/2
    + Δn²/12 (G′(n_last) − G′(n_first)) + O(Δn⁴ G‴): checked against quad of the formula
    within 1e-4.  The end term makes a realisation's variance exceed the band integral over
    [n_min, n_max] by 1.3 % (German low) / 2.4 % (FRA 5) at P = 3277 m (measured 2026-12-02);
    the excess is below Δn · G(n_min)."""
    psd = TRACK_PSDS[name]
    prof = track_profile(name, seed=7, spacing=0.05, length=2000.0)
    assert isinstance(prof, RoadProfile)
    z = prof.z
    n_s, spacing = z.size, 0.05
    period = n_s * spacing
    spec = np.fft.rfft(z)
    n_k = np.arange(spec.size) / period
    band = (n_k >= psd.n_min) & (n_k <= psd.n_max)
    periodogram = 2.0 * np.abs(spec) ** 2 * period / n_s**2
    f = (lambda w: german(w, 4.032e-7)) if name == "german-low" else (lambda w: fra(w, 0.2095))
    np.testing.assert_allclose(periodogram[band], 2 * np.pi * f(2 * np.pi * n_k[band]), rtol=1e-9)
    assert periodogram[~band].max() < 1e-20 * periodogram[band].max()
    g = lambda n: 2 * np.pi * f(2 * np.pi * n)  # noqa: E731  G(n) [m³/cycle]
    first, last, dn = n_k[band][0], n_k[band][-1], 1.0 / period
    dg = lambda n: (g(n * (1 + 1e-6)) - g(n * (1 - 1e-6))) / (2e-6 * n)  # noqa: E731  G'(n)
    euler_maclaurin = (quad(g, first, last, limit=400, epsrel=1e-12)[0] + dn * (g(first) + g(last)) / 2
                       + dn**2 / 12 * (dg(last) - dg(first)))
    assert np.var(z) == pytest.approx(euler_maclaurin, rel=1e-4)
    exact = quad(g, psd.n_min, psd.n_max, limit=400, epsrel=1e-12)[0]
    assert abs(np.var(z) - exact) <= dn * g(psd.n_min)


def test_profile_seeded_and_named():
    a = track_profile("german-high", seed=3, length=500.0)
    b = track_profile(TrackPSD.named("german-high"), seed=3, length=500.0)
    c = track_profile("german-high", seed=4, length=500.0)
    np.testing.assert_array_equal(a.z, b.z)
    assert not np.allclose(a.z, c.z)
    assert "German" in a.label
    narrow = TrackPSD.named("german-high", n_min=0.05, n_max=0.5)
    assert narrow.A_v == 1.080e-6 and narrow.n_max == 0.5


@pytest.mark.parametrize("bad", [dict(form="iso"), dict(A_v=-1.0), dict(omega_r=1.0), dict(n_min=2.0)])
def test_bad_spectra_refused(bad):
    kw = dict(form="german", A_v=1e-7, omega_c=0.8, omega_r=0.02)
    kw.update(bad)
    with pytest.raises(ValueError):
        TrackPSD(**kw)
    with pytest.raises(ValueError, match="allowed"):
        TrackPSD.named("german-medium")
