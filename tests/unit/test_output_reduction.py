"""Output reduction shared between effects and crossings: load effects reduced together (one pass,
a grillage's consistent load of the points once), static wheel loads solved once per vehicle,
scenario bridges kept per spec."""
import numpy as np
import pytest

from vbikit.analysis.effects import (ContactInfluences, contact_influence_table, contact_influences,
                                    load_effect_responses)
from vbikit.bridge import effects as bridge_effects
from vbikit.bridge.presets import paper_deck
from vbikit.solve import Crossing, simulate
from vbikit.vehicle.presets import hs20_44


@pytest.fixture(scope="module")
def deck_result():
    bridge = paper_deck(1, n_modes=4, use_cache=False, n_elements=12)
    return simulate(Crossing(bridge, hs20_44(), speed=20.0, dt=2e-3))


def _brute_force(result, effect):
    """I(x_p, y_p) point by point through the effect's own influence function (one call per point)."""
    crossing = result.crossing
    origin, direction, y = crossing.point_kinematics()
    s = np.asarray(result.travel).reshape(len(result.time), -1)[:, crossing.point_vehicle]
    x = origin + direction * s
    out = np.zeros(x.shape)
    for t in range(0, x.shape[0], 97):
        for p in range(x.shape[1]):
            if 0.0 <= x[t, p] <= crossing.bridge.span:
                out[t, p] = effect.influence(np.array([x[t, p]]), np.array([y[p]]))[0]
    return out[::97]


def test_deck_effects_share_the_consistent_load_and_agree_point_by_point(deck_result, monkeypatch):
    bridge = deck_result.crossing.bridge
    effects = bridge.default_load_effects(girder=2)
    assert len(effects) >= 3
    calls = []
    shared = type(effects[0].influence).shared
    monkeypatch.setattr(type(effects[0].influence), "shared", lambda self, x, y: calls.append(x.size) or shared(self, x, y))
    together = contact_influences(deck_result, effects)
    assert len(calls) == 1  # one consistent load of the points for all effects of the deck
    for k, e in enumerate(effects):
        assert np.allclose(together[k][::97], _brute_force(deck_result, e), rtol=1e-12, atol=1e-15)


def test_effects_reduced_together_equal_one_by_one(deck_result):
    bridge = deck_result.crossing.bridge
    effects = bridge.default_load_effects(girder=2)
    together = load_effect_responses(deck_result, effects)
    tables = load_effect_responses(deck_result, effects, influence=contact_influence_table(deck_result, effects))
    for e, r, t in zip(effects, together, tables):
        # each effect's sums and modal correction are its own: bit for bit, with or without the others,
        # by the compiled sums (the deck's tabulated influences) and by the pair tables
        alone = load_effect_responses(deck_result, [e])[0]
        assert np.array_equal(r.dynamic, alone.dynamic) and np.array_equal(r.static, alone.static)
        alone = load_effect_responses(deck_result, [e], influence=contact_influence_table(deck_result, [e]))[0]
        assert np.array_equal(t.dynamic, alone.dynamic) and np.array_equal(t.static, alone.static)
        # the two the same sums in another order: equal to round-off
        assert np.allclose(r.dynamic, t.dynamic, rtol=0.0, atol=1e-13 * np.abs(t.static).max())
        assert np.allclose(r.static, t.static, rtol=0.0, atol=1e-13 * np.abs(t.static).max())
    sup = load_effect_responses(deck_result, effects, "mode-superposition")
    assert [r.effect for r in sup] == list(effects) and load_effect_responses(deck_result, []) == []


def test_on_deck_pairs_reduce_like_the_dense_influence_array(deck_result):
    # the sparse table (on-deck (time, point) pairs only) against the dense (n_effects, n_t, n_cp)
    # array summed by matrix products: the same sums in another order, equal to round-off; and the
    # table's dense form is the array contact_influences gives (checked point by point above)
    effects = deck_result.crossing.bridge.default_load_effects(girder=2)
    table = contact_influence_table(deck_result, effects)
    dense = table.dense()
    assert isinstance(table, ContactInfluences) and 0 < table.rows.size < dense[0].size  # some points off the deck
    assert np.array_equal(dense, contact_influences(deck_result, effects))
    assert table.values.shape == (len(effects), table.rows.size) and np.count_nonzero(dense) <= table.values.size
    # several weights at once are each weight alone; a weight of one on every pair sums the dense array
    a = np.random.default_rng(1).normal(size=(table.rows.size, 2))
    both = table.sums(a)
    assert both.shape == (2, len(effects), dense.shape[1])
    assert np.array_equal(both[1], table.sums(a[:, 1]))
    assert np.allclose(table.sums(np.ones(table.rows.size)), dense.sum(axis=2), rtol=0.0, atol=1e-13 * np.abs(dense).sum(axis=2).max())
    for sparse, full in zip(load_effect_responses(deck_result, effects, influence=table),
                            load_effect_responses(deck_result, effects, influence=dense)):
        for a, b in ((sparse.static, full.static), (sparse.dynamic, full.dynamic)):
            assert np.allclose(a, b, rtol=0.0, atol=1e-13 * np.abs(b).max())


def test_influence_values_keeps_plain_functions_apart():
    plain = bridge_effects.LoadEffect("moment", 1.0, np.zeros(1), lambda x, y: 2.0 * np.asarray(x), 1.0)
    out = bridge_effects.influence_values([plain, plain], np.array([1.0, 3.0]), np.array([0.0, 0.0]))
    assert out.shape == (2, 2) and np.array_equal(out[:, 1], [2.0, 6.0])


def test_static_wheel_loads_are_solved_once_and_handed_out_as_copies():
    v = hs20_44()
    first = v.static_wheel_loads()
    first[:] = 0.0  # a caller's change must not reach the vehicle
    again = v.static_wheel_loads()
    q = v.static_state()
    expected = np.array([w.fixed_load - w.stiffness * (w.row @ q) for w in v.wheels])
    assert np.array_equal(again, expected) and again.sum() == pytest.approx(v.total_weight)


def test_scenario_bridges_are_kept_per_spec_and_bounded(tmp_path, monkeypatch):
    import importlib

    from vbikit.scenario.schema import parse_scenario

    build_module = importlib.import_module("vbikit.scenario.build")

    def spec(**bridge):
        return parse_scenario({"bridge": {"model": "paper-bridge-2-beam", **bridge}, "vehicle": {"model": "hs20-44"},
                               "crossing": {"speed_kmh": 75}}, ".").bridge

    a = build_module.build_bridge(spec(n_modes=3))
    assert build_module.build_bridge(spec(n_modes=3)) is a
    assert build_module.build_bridge(spec(n_modes=4)) is not a
    monkeypatch.setenv("VBIKIT_CACHE_DIR", str(tmp_path))  # another mode cache: built again
    assert build_module.build_bridge(spec(n_modes=3)) is not a
    for n in range(5, 5 + build_module.BRIDGE_CACHE_SIZE + 2):
        build_module.build_bridge(spec(n_modes=n))
    assert len(build_module._BRIDGES) == build_module.BRIDGE_CACHE_SIZE


def test_a_bridge_from_a_file_is_built_every_time(tmp_path):
    from vbikit.scenario.build import _bridge_key
    from vbikit.scenario.bridge_spec import ModesFileSpec

    assert _bridge_key(ModesFileSpec(model="modes-file", modes_file="m.txt")) is None


def test_quadratic_roots_of_the_peak_refinement_agree_with_numpy_roots():
    """``_real_roots`` (closed form) against ``numpy.roots`` (companion-matrix eigenvalues), and
    ``hermite_peak`` of a sampled sine against its true peak (1 at t = π/2)."""
    from vbikit.analysis.impact import _real_roots, hermite_peak

    rng = np.random.default_rng(5)
    for a, b, c in list(rng.normal(size=(200, 3))) + [(0.0, 2.0, -1.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (1.0, -2.0, 1.0)]:
        ours = sorted(_real_roots(float(a), float(b), float(c)))
        coeffs = [a, b, c] if a != 0.0 else [b, c] if b != 0.0 else []
        ref = np.roots(coeffs) if coeffs else np.array([])
        ref = sorted(r.real for r in ref if abs(r.imag) <= 1e-12)
        assert len(ours) in (len(ref), len(set(ref)))  # a double root may come once
        assert np.allclose(sorted(set(np.round(ours, 9))), sorted(set(np.round(ref, 9))), rtol=1e-9, atol=1e-12)
    t = np.linspace(0.0, 3.0, 13)  # step 0.25: the largest sample 0.25 s from the peak
    peak, when = hermite_peak(t, np.sin(t), np.cos(t), int(np.argmax(np.sin(t))))
    # the cubic Hermite interpolant's error: h⁴/384 · max|f''''| = 1e-5 at h = 0.25
    assert peak == pytest.approx(1.0, abs=2e-5) and when == pytest.approx(np.pi / 2, abs=5e-3)


def test_whole_period_random_roads_are_kept_per_spec_bitwise_and_bounded():
    # a scenario's whole-period road is generated once per [road] spec: the same object again (writeable:
    # numba would compile every kernel again for read-only arrays), bit for bit random_profile's road (and its correlated right line); another seed is another road
    import importlib

    from vbikit.road import RoadPSD, correlated_profile, random_profile
    from vbikit.scenario.schema import parse_scenario

    build_module = importlib.import_module("vbikit.scenario.build")

    def scenario(**road):
        return parse_scenario({"bridge": {"model": "paper-bridge-2-beam"}, "vehicle": {"model": "hs20-44"},
                               "crossing": {"speed_kmh": 75}, "road": {"class": "C", **road}}, ".")

    s = scenario(seed=11, right_coherence=0.5)
    left = build_module.build_road(s.road, s)
    right = build_module.build_right_road(s.road, s, left)
    assert build_module.build_road(s.road, s) is left and build_module.build_right_road(s.road, s, left) is right
    assert left.z.flags.writeable and right.z.flags.writeable
    direct = random_profile(RoadPSD.iso("C"), 11)
    assert np.array_equal(left.x, direct.x) and np.array_equal(left.z, direct.z)
    assert np.array_equal(right.z, correlated_profile(direct, RoadPSD.iso("C"), 11, 0.5).z)
    other = build_module.build_road(scenario(seed=12).road, s)
    assert other is not left and not np.array_equal(other.z, left.z)
    window = build_module.build_road(s.road, s, (0.0, 20.0))  # a window is generated each time
    assert window is not build_module.build_road(s.road, s, (0.0, 20.0))
    for seed in range(20, 20 + build_module.ROAD_CACHE_SIZE + 2):
        build_module.build_road(scenario(seed=seed).road, s)
    assert len(build_module._ROADS) == build_module.ROAD_CACHE_SIZE
