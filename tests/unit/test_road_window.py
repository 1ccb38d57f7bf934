"""A random road generated only over the range a crossing uses (``random_profile(window=…)``): the
same road as the whole period's inverse FFT, the ISO 8608 spectrum, and the crossings that use it."""
import numpy as np
import pytest
from scipy.signal import welch

from vbikit.road import RoadPSD, correlated_profile, phase_angles, random_profile


def _cut(full, part):
    i = int(np.searchsorted(full.x, part.x[0]))
    return full.x[i:i + part.x.size], full.z[i:i + part.x.size]


@pytest.mark.parametrize("window", [(-12.3, 40.1), (-655.36, -600.0), (600.0, 700.0), (3.0, 3.0)])
def test_window_is_the_whole_period_road_there(window):
    psd = RoadPSD.iso("C")
    full = random_profile(psd, 7)
    part = random_profile(psd, 7, window=window)
    x, z = _cut(full, part)
    assert np.array_equal(x, part.x)  # the very same stations
    assert part.x[0] <= max(window[0], full.x[0]) and part.x[-1] >= min(window[1], full.x[-1])
    assert part.x.size < full.x.size / 10
    assert np.max(np.abs(z - part.z)) < 1e-12 * full.z.std()


def test_window_against_a_direct_sum_of_eq7():
    """r(x) = Σ √(2 φ(n_k) Δn) cos(2π n_k (x − x0) + θ_k) summed term by term (no FFT) at a few stations."""
    psd, spacing, length = RoadPSD.iso("B", n_max=2.0), 0.02, 300.0
    part = random_profile(psd, 3, spacing=spacing, length=length, window=(0.0, 20.0))
    n_k, theta = phase_angles(psd, 3, spacing=spacing, length=length)
    period = 1.0 / (n_k[1] - n_k[0])
    x0 = -period / 2
    amp = np.sqrt(2.0 * psd(n_k) / period)
    for j in (0, 311, part.x.size - 1):
        direct = np.sum(amp * np.cos(2.0 * np.pi * n_k * (part.x[j] - x0) + theta + 2.0 * np.pi * n_k * x0))
        assert part.z[j] == pytest.approx(direct, abs=1e-9 * part.z.std())


def test_right_line_window_matches_the_whole_period_one():
    psd = RoadPSD.iso("C")
    w = (-10.0, 40.0)
    right = correlated_profile(random_profile(psd, 1, window=w), psd, 1, 0.5, window=w)
    full = correlated_profile(random_profile(psd, 1), psd, 1, 0.5)
    _, z = _cut(full, right)
    assert np.max(np.abs(z - right.z)) < 1e-12 * full.z.std()
    with pytest.raises(ValueError, match="window"):
        correlated_profile(random_profile(psd, 1, window=w), psd, 1, 0.5)


def test_windowed_roads_have_the_iso_8608_spectrum():
    """Welch PSD of 60 seeds' 50 m windows against Gd(n0)(n/n0)^-2 (ISO 8608 class C), octave by
    octave: 60 seeds × ~4 Hann segments leave ≈ 3 % sampling scatter on an octave's mean."""
    psd = RoadPSD.iso("C")
    spectra = []
    for seed in range(60):
        z = random_profile(psd, seed, window=(-10.0, 40.0)).z
        n, g = welch(z, fs=100.0, nperseg=2048, detrend="linear")
        spectra.append(g)
    ratio = np.mean(spectra, axis=0) / np.where(n > 0, psd(np.maximum(n, 1e-9)), np.inf)
    for lo, hi in ((0.25, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 3.5)):
        band = (n >= lo) & (n < hi)
        assert 0.88 < ratio[band].mean() < 1.12, (lo, hi, ratio[band].mean())
    above = (n > 4.5) & (n < 40.0)  # nothing beyond the band's n_max = 4 cycle/m
    assert np.mean(spectra, axis=0)[above].max() < 1e-3 * psd(np.array([4.0]))[0]


def test_bad_window_is_refused():
    with pytest.raises(ValueError, match="road window"):
        random_profile(RoadPSD.iso("C"), 1, window=(5.0, 1.0))


def test_an_event_crossing_gets_its_road_over_the_range_it_uses():
    from vbikit.scenario.build import build, with_scenario_road
    from vbikit.scenario.schema import parse_scenario
    from vbikit.solve.timestep import automatic_road_per_step

    data = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "vehicle": {"model": "hs20-44"},
            "road": {"class": "C", "seed": 1, "right_coherence": 0.8}, "crossing": {"speed_kmh": 75}}
    scenario = parse_scenario(data, ".")
    whole = build(scenario).crossing  # a scenario run: the whole period
    crossing = with_scenario_road(whole.with_road(None), scenario.road, scenario, seed=5)
    lo, hi = crossing.road_extent()
    full = random_profile(RoadPSD.iso("C"), 5)
    # no more than the range, 1.5 of the longest automatic step on each side (3 cm of road a step) and the
    # window's own 2 stations a side (1 cm apart)
    pad = 3 * automatic_road_per_step(scenario.road.spacing) + 4 * scenario.road.spacing
    for road in (crossing.road, crossing.road_right):
        assert road.covers(lo, hi) and road.x[-1] - road.x[0] < hi - lo + pad + 0.02
    x, z = _cut(full, crossing.road)
    assert np.array_equal(x, crossing.road.x) and np.max(np.abs(z - crossing.road.z)) < 1e-12 * full.z.std()
    assert whole.road.x.size == full.x.size


def test_events_with_a_given_time_step_get_a_road_their_last_step_covers():
    """A traffic stream whose base scenario gives the step ([crossing] dt = 4 ms, 9–11 cm of road a step
    at these speeds): each event's windowed road must cover where the time grid's last step ends (up to
    a step past the crossing's end), not only the crossing's own range; before, 7 of these 8 events
    stopped with "road profile … covers … but … was requested"."""
    from vbikit.solve import simulate
    from vbikit.traffic import LaneTraffic, synthetic_stream
    from vbikit.traffic.study import traffic_study

    base = {"bridge": {"model": "paper-bridge-2", "n_modes": 4}, "tire": {"model": "point"},
            "road": {"class": "B"}, "crossing": {"dt": 0.004}}
    stream = synthetic_stream([LaneTraffic(1, "+x", 600.0, 80, 8), LaneTraffic(2, "-x", 600.0, 75, 8)], 30, seed=2026)
    job = traffic_study(stream, base, batch_size=4)
    for e in range(8):
        crossing = job.crossing(e)
        result = simulate(crossing)
        assert result.integration_dt == 0.004 and np.all(np.isfinite(result.xi))


@pytest.mark.parametrize("window", [None, (0.0, 3.0)])
def test_whole_period_and_window_with_the_band_up_to_nyquist(window):
    """n_max = 1/(2Δx): the Nyquist wavenumber is in the band (a real FFT counts it once)."""
    psd = RoadPSD.iso("C", n_max=50.0)
    p = random_profile(psd, 2, spacing=0.01, length=20.0, window=window)
    n_k, theta = phase_angles(psd, 2, spacing=0.01, length=20.0)
    assert n_k[-1] == pytest.approx(50.0)
    period = 1.0 / (n_k[1] - n_k[0])
    amp = np.sqrt(2.0 * psd(n_k) / period)
    for j in (0, 5, p.x.size - 1):
        direct = np.sum(amp * np.cos(2.0 * np.pi * n_k * p.x[j] + theta))
        assert p.z[j] == pytest.approx(direct, abs=1e-11 * p.z.std())


def test_cached_window_factors_serve_only_their_window():
    """The chirp-z factors kept per (grid, window length rounded up to ``WINDOW_QUANTUM``)
    (``_band_sum_factors``): windows asked for in turn, again with other seeds, and windows of the
    same length elsewhere on the road (the factors do not depend on where a window starts) are
    each the whole-period road there."""
    from vbikit.road.psd import WINDOW_QUANTUM, _band_sum_factors

    psd = RoadPSD.iso("B")
    fulls = {seed: random_profile(psd, seed) for seed in (1, 2)}
    _band_sum_factors.cache_clear()
    # 50 m and 55 m: 5,005 and 5,505 stations, two lengths after rounding to 512 (5,120 and 5,632)
    assert WINDOW_QUANTUM == 512
    for window, seed in (((-30.0, 20.0), 1), ((-10.0, 45.0), 1), ((-30.0, 20.0), 2), ((-10.0, 45.0), 2),
                         ((-20.0, 30.0), 1), ((300.0, 350.0), 2), ((-29.5, 20.3), 2)):
        part = random_profile(psd, seed, window=window)
        x, z = _cut(fulls[seed], part)
        assert np.array_equal(x, part.x)
        assert np.max(np.abs(z - part.z)) < 1e-12 * fulls[seed].z.std()
    info = _band_sum_factors.cache_info()
    assert (info.misses, info.hits) == (2, 5)
