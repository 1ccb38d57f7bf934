"""Unit tests for vbikit.road: ISO 8608 PSDs, random profiles (paper Eq. 7), measured CSV files, RoadProfile."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.road import (
    ISO_CLASSES,
    ISO_N0,
    PAPER_CLASSES,
    RoadFileError,
    RoadProfile,
    RoadPSD,
    phase_angles,
    random_profile,
    read_profile_csv,
)


# ------------------------------------------------------------------ PSD
def test_iso_class_values():
    # ISO 8608 geometric means Gd(n0) [1e-6 m³]: A 16, B 64, C 256, D 1024, E 4096, F 16384, G 65536, H 262144
    expected = dict(zip("ABCDEFGH", [16, 64, 256, 1024, 4096, 16384, 65536, 262144]))
    assert list(ISO_CLASSES) == list("ABCDEFGH")
    for cls, value in expected.items():
        assert ISO_CLASSES[cls] == pytest.approx(value * 1e-6, rel=1e-15)
    assert ISO_N0 == 0.1


def test_iso_psd_and_paper_names():
    psd = RoadPSD.iso("C")
    assert (psd.phi0, psd.n0, psd.exponent) == (256e-6, 0.1, 2.0)
    assert psd(np.array([0.1, 0.2, 1.0])) == pytest.approx([256e-6, 64e-6, 2.56e-6])
    assert PAPER_CLASSES == {"good": "B", "average": "C", "poor": "D"}
    assert RoadPSD.iso("average") == RoadPSD.iso("c") == psd
    with pytest.raises(ValueError, match="road class"):
        RoadPSD.iso("Z")


def test_band_variance_closed_form_against_quadrature():
    for psd in (RoadPSD.iso("B"), RoadPSD(1e-5, n0=1 / (2 * np.pi), exponent=2.5, n_min=0.05, n_max=3.0),
                RoadPSD(1e-5, exponent=1.0)):
        n = np.geomspace(psd.n_min, psd.n_max, 200_001)
        y = psd(n)
        quad = float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(n)))
        assert psd.band_variance() == pytest.approx(quad, rel=1e-6)


@pytest.mark.parametrize("kwargs", [dict(phi0=-1.0), dict(phi0=1e-6, n_min=0.0), dict(phi0=1e-6, n_min=2.0, n_max=1.0),
                                    dict(phi0=1e-6, n0=0.0)])
def test_invalid_psd_raises(kwargs):
    with pytest.raises(ValueError):
        RoadPSD(**kwargs)


# ------------------------------------------------------------------ random profiles
def test_random_profile_reproducible_by_seed():
    psd = RoadPSD.iso("C")
    a, b = random_profile(psd, seed=7), random_profile(psd, seed=7)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.z, b.z)
    c = random_profile(psd, seed=8)
    assert np.max(np.abs(a.z - c.z)) > 1e-3  # different seeds: different roads
    assert a.spacing == pytest.approx(0.01)


def test_variance_is_sum_of_line_spectrum_exactly():
    # Parseval over one full period: mean r² = Σ ½ (2 φ(n_k) Δn) = Σ φ(n_k) Δn
    psd = RoadPSD.iso("C")
    prof = random_profile(psd, seed=3)
    period = prof.x.size * 0.01
    n_k, _ = phase_angles(psd, seed=3)
    assert np.mean(prof.z) == pytest.approx(0.0, abs=1e-15)
    assert np.mean(prof.z**2) == pytest.approx(np.sum(psd(n_k)) / period, rel=1e-10)


def test_variance_close_to_band_variance_for_a_long_period():
    # Σ φ(n_k) Δn is a Riemann sum of ∫ φ dn; with the default 327.68 m period (Δn = 3.05e-3 cycle/m)
    # the first line is at 0.0122 cycle/m and ≈ 7 % of the n⁻² band power below it is missing.  With a
    # 5243 m period (Δn = 1.9e-4) the sum is within 0.2 %.
    psd = RoadPSD.iso("C")
    prof = random_profile(psd, seed=3, length=3000.0)
    assert np.var(prof.z) == pytest.approx(psd.band_variance(), rel=0.02)


def test_fft_equals_direct_evaluation_of_eq7():
    psd = RoadPSD.iso("D")
    prof = random_profile(psd, seed=11)
    n_k, theta = phase_angles(psd, seed=11)
    dn = 1.0 / (prof.x.size * 0.01)
    amp = np.sqrt(2.0 * psd(n_k) * dn)
    for j in (0, 1, 777, prof.x.size // 2, prof.x.size // 2 + 1234, prof.x.size - 1):
        x = prof.x[j]
        direct = np.sum(amp * np.cos(2 * np.pi * n_k * x + theta))
        assert abs(prof.z[j] - direct) <= 1e-12


def test_same_seed_same_road_when_the_period_is_unchanged():
    # 200 m and 300 m both round up to 2¹⁵ samples of 0.01 m (period 327.68 m)
    psd = RoadPSD.iso("B")
    a = random_profile(psd, seed=5, length=200.0)
    b = random_profile(psd, seed=5, length=300.0)
    assert a.x.size == b.x.size == 2**15
    np.testing.assert_array_equal(a.z, b.z)
    x = np.array([-12.345, 0.0, 3.21, 48.0])
    np.testing.assert_array_equal(a.elevation(x), b.elevation(x))


def test_profile_is_centred_on_the_bridge_entry_by_default():
    prof = random_profile(RoadPSD.iso("A"), seed=1)
    period = prof.x.size * 0.01
    assert prof.x[0] == pytest.approx(-period / 2)
    moved = random_profile(RoadPSD.iso("A"), seed=1, x_start=-50.0)
    assert moved.x[0] == pytest.approx(-50.0)
    # the same function of x: Eq. 7 does not depend on where the samples start
    x = np.array([-10.0, 0.0, 25.0])
    n_k, theta = phase_angles(RoadPSD.iso("A"), seed=1)
    amp = np.sqrt(2.0 * RoadPSD.iso("A")(n_k) / period)
    direct = np.cos(2 * np.pi * np.outer(x, n_k) + theta) @ amp
    np.testing.assert_allclose(moved.elevation(x), direct, atol=1e-12)


def test_random_profile_rejects_bad_sampling():
    with pytest.raises(ValueError, match="spacing"):
        random_profile(RoadPSD.iso("C"), seed=1, spacing=0.0)
    with pytest.raises(ValueError, match="Nyquist"):
        random_profile(RoadPSD.iso("C"), seed=1, spacing=0.2)  # n_max = 4 > 1/(2·0.2)


# ------------------------------------------------------------------ measured CSV
def _write(tmp_path, text, name="profile.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_read_good_csv_with_header_and_comments(tmp_path):
    path = _write(tmp_path, "# laser profiler, wheel track 1\nx_m,elevation_m\n-1.0,0.001\n\n0.0,0.002\n# mid comment\n0.5,-0.003\n")
    prof = read_profile_csv(path)
    np.testing.assert_array_equal(prof.x, [-1.0, 0.0, 0.5])
    np.testing.assert_array_equal(prof.z, [0.001, 0.002, -0.003])
    assert "profile.csv" in prof.label


def test_read_csv_without_header(tmp_path):
    prof = read_profile_csv(_write(tmp_path, "0,0\n1,0.01\n2,0.02\n"))
    assert prof.elevation(1.5) == pytest.approx(0.015)


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("x,z\n0.0,0.0\n1.0,0.001\n2.0,abc\n3.0,0.0\n", 4, "not a number"),
        ("x,z\n0.0,0.0\n1.0,0.001\n0.5,0.002\n", 4, "not greater"),
        ("x,z\n0.0,0.0\n1.0,0.001\n1.0,0.002\n", 4, "not greater"),
        ("# comment\nx,z\n0.0,0.0\n1.5\n2.0,0.0\n", 4, "2 columns"),
        ("0.0,0.0\n1.0,inf\n", 2, "non-finite"),
        # a typo in the first data row of a file without header is an error, not a header
        ("0.0,0.00l\n1.0,0.0\n2.0,0.0\n", 1, "not a number"),
        ("# comment\n0.0,\n1.0,0.0\n2.0,0.0\n", 2, "not a number"),
    ],
)
def test_bad_csv_names_the_line(tmp_path, text, line, words):
    path = _write(tmp_path, text)
    with pytest.raises(RoadFileError, match=words) as err:
        read_profile_csv(path)
    assert f"profile.csv:{line}:" in str(err.value)


@pytest.mark.parametrize("text", ["", "x,z\n", "# only a comment\n\n", "x,z\n0.0,0.0\n"])
def test_empty_or_too_short_csv_raises(tmp_path, text):
    with pytest.raises(RoadFileError, match="at least 2 data rows"):
        read_profile_csv(_write(tmp_path, text))


def test_missing_csv_raises(tmp_path):
    with pytest.raises(RoadFileError, match="not found"):
        read_profile_csv(tmp_path / "nope.csv")


def test_road_file_error_is_a_value_error():
    assert issubclass(RoadFileError, ValueError)


# ------------------------------------------------------------------ RoadProfile
@pytest.fixture
def tent() -> RoadProfile:
    return RoadProfile(np.array([0.0, 1.0, 3.0]), np.array([0.0, 0.02, 0.0]), "tent")


def test_evaluate_elevation_and_slope(tent):
    z, s = tent.evaluate(np.array([0.0, 0.5, 1.0, 2.0, 3.0]))
    np.testing.assert_allclose(z, [0.0, 0.01, 0.02, 0.01, 0.0], atol=1e-15)
    np.testing.assert_allclose(s, [0.02, 0.02, -0.01, -0.01, -0.01])  # right-hand slope at a station
    np.testing.assert_allclose(tent.elevation([0.25]), [0.005])
    np.testing.assert_allclose(tent.slope([2.5]), [-0.01])
    assert tent.spacing == pytest.approx(1.0)


def test_evaluate_keeps_shape(tent):
    z, s = tent.evaluate(np.full((4, 3), 0.5))
    assert z.shape == s.shape == (4, 3)


@pytest.mark.parametrize("x", [-0.01, 3.01, -100.0])
def test_evaluate_outside_range_raises(tent, x):
    with pytest.raises(ValueError, match="covers"):
        tent.evaluate(np.array([1.0, x]))


def test_flat_road(tent):
    flat = RoadProfile.flat()
    z, s = flat.evaluate(np.array([-500.0, 0.0, 900.0]))
    assert not np.any(z) and not np.any(s)
    assert flat.spacing == 0.0
    assert flat.covers(-100.0, 100.0) and not tent.covers(-1.0, 2.0)


@pytest.mark.parametrize(
    ("x", "z"),
    [([0.0, 1.0, 1.0], [0.0, 0.0, 0.0]), ([0.0, 2.0, 1.0], [0.0, 0.0, 0.0]), ([0.0], [0.0]), ([0.0, 1.0], [0.0, np.nan])],
)
def test_invalid_profile_raises(x, z):
    with pytest.raises(ValueError):
        RoadProfile(np.array(x), np.array(z))


def test_secant_rate_by_hand_on_a_kink_and_past_the_ends():
    """``RoadProfile.secant_rate``: v (r(x + a) − r(x − a)) / 2a with a = |v| span.  Stations 0, 1, 2 m at
    0, 10, −20 mm (slopes +0.01, −0.03): at the kink x = 1 m with a = 1 cm, by hand r(1.01) = 9.7 mm and
    r(0.99) = 9.9 mm, so dr/dx = −0.01 either way (the cell's slope would be +0.01 or −0.03); past the
    ends the end segments extend (at x = 0, a = 1 cm: r(−0.01) = −0.1 mm, r(0.01) = 0.1 mm, slope +0.01);
    span 0 gives the cell's slope."""
    from vbikit.road import RoadProfile

    road = RoadProfile(np.array([0.0, 1.0, 2.0]), np.array([0.0, 0.01, -0.02]))
    for v in (20.0, -20.0):
        assert road.secant_rate(1.0, v, 0.01 / 20.0) == pytest.approx(v * -0.01, abs=1e-13)
    assert road.secant_rate(0.0, 20.0, 0.01 / 20.0) == pytest.approx(20.0 * 0.01, abs=1e-13)
    assert road.secant_rate(2.0, 20.0, 0.01 / 20.0) == pytest.approx(20.0 * -0.03, abs=1e-13)
    np.testing.assert_allclose(road.secant_rate([0.5, 1.5], 20.0, 0.0), [20.0 * 0.01, 20.0 * -0.03], rtol=1e-13)


@pytest.mark.parametrize("make", [
    lambda: RoadProfile.flat(),
    lambda: RoadProfile(np.array([0.0, 1.0, 3.0]), np.zeros(3)),
    lambda: RoadProfile(np.array([0.0, 1.0, 3.0]), np.array([0.0, 1e-3, 0.0])),
    lambda: RoadProfile(np.array([0.0, 1.0, 3.0]), np.array([0.0, 1e-3, 0.0]), resolution=0.25),
    lambda: RoadProfile(np.array([0.0, 1.0, 3.0]), np.array([0.0, 1e-3, 0.0]), resolution=0.0),
    lambda: random_profile(RoadPSD.iso("B"), 3, spacing=0.01, length=100.0, window=(-5.0, 20.0)),
])
def test_has_features_is_spacing_above_zero(make):
    """``RoadProfile.has_features`` (the step rule's test, without the stations' differences) is
    ``spacing > 0`` for flat, stepped, resolved and generated profiles, before and after ``spacing`` is known."""
    road = make()
    before = road.has_features
    assert before == (road.spacing > 0) == road.has_features
