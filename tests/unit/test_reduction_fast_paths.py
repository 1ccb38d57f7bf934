"""The output reduction's shortcuts against the plain computations they replace, bit for bit:

* ``impact.largest_magnitude`` / ``first_largest`` against ``argmax(abs(·))`` / ``argmax(sign · ·)``
  (ties between a value and its negative, repeated extremes, NaN, ±0);
* ``impact.smooth_vertices_rows`` (a run's effects at once, kinks shared by object) against
  ``smooth_vertices`` row by row, and a response's ``peak_series`` through ``_SharedLimits.vertices`` against
  the same response made without it;
* the passing instants of several effects timed together, equal blocks of positions timed once
  (``effects._position_table``), against each effect timed alone;
* ``effects.modal_rates`` (the damping row kept per bridge) against ξ̈ + ξ̇ · 2ζω written out, on two bridges
  of other damping one after the other (a store keyed without the bridge would hand the second the first's);
* ``instants.modal_terms`` kept per bridge, ``effects.distinct_sorted`` against ``np.unique``,
  ``CrossingResult.shared_travel`` against ``travel``, and ``impact.hermite_peak`` (its samples read as Python
  floats, its roots by ``math``) against the same written with numpy's scalars."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vbikit._kept import forget_kept
from vbikit.analysis.effects import (_passing_instants, distinct_sorted, load_effect_responses, modal_rates)
from vbikit.analysis.impact import first_largest, largest_magnitude, smooth_vertices, smooth_vertices_rows
from vbikit.analysis.instants import modal_terms
from vbikit.bridge import paper_beam
from vbikit.bridge.presets import paper_deck
from vbikit.solve import Crossing, VehicleMotion, simulate
from vbikit.vehicle.presets import hs20_44


@pytest.fixture(scope="module")
def deck():
    return paper_deck(1, n_modes=4, use_cache=False, n_elements=12)


@pytest.fixture(scope="module")
def deck_run(deck):
    vehicles = (VehicleMotion(hs20_44(), 20.0, lateral_offset=-1.3), VehicleMotion(hs20_44(), 17.0, direction="-x",
                                                                                    lateral_offset=1.1))
    return simulate(Crossing(deck, vehicles=vehicles, dt=2e-3))


def _effects(deck):
    return [deck.load_effect("moment", 9.0, girder=2), deck.load_effect("shear", 4.0, girder=3),
            deck.load_effect("reaction", support=0, girder=1), deck.load_effect("reaction", support=1, girder=3)]


ARRAYS = [np.array(v, float) for v in (
    [1.0, -3.0, 2.0, 3.0, -3.0], [-2.0, 2.0, 1.0], [0.0, -0.0, 0.0], [-0.0, 0.0], [5.0], [-1.0, -4.0, -4.0, 2.0],
    [1.0, np.nan, -7.0, np.nan], [np.inf, -np.inf, 3.0], [-np.inf, 1.0, np.inf], [2.0, 2.0, -2.0, -2.0])]


@pytest.mark.parametrize("values", ARRAYS)
def test_largest_magnitude_and_first_largest_are_the_argmax_of_the_product(values):
    with np.errstate(invalid="ignore"):
        assert largest_magnitude(values) == int(np.argmax(np.abs(values)))
        for sign in (1.0, -1.0):
            assert first_largest(values, sign) == int(np.argmax(sign * values))
    rng = np.random.default_rng(7)
    for _ in range(200):  # few distinct values: many ties, and ties between a value and its negative
        v = rng.integers(-3, 4, rng.integers(1, 9)).astype(float)
        assert largest_magnitude(v) == int(np.argmax(np.abs(v)))
        assert first_largest(v, 1.0) == int(np.argmax(v)) and first_largest(v, -1.0) == int(np.argmax(-v))


def _same(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)


def test_vertices_of_several_rows_at_once_are_those_row_by_row():
    rng = np.random.default_rng(3)
    t = np.arange(40) * 0.01
    dynamic = np.cos(2 * np.pi * np.array([[2.0], [3.1], [1.3], [0.7]]) * t + rng.uniform(0, 3, (4, 1)))
    static = -np.sin(2 * np.pi * np.array([[1.1], [1.7], [0.5], [2.2]]) * t + rng.uniform(0, 3, (4, 1)))
    dynamic[3, :] = np.linspace(0.0, 1.0, t.size)  # extremes at the ends: none
    shared = np.array([t[7] + 0.003, t[21]])  # one object for rows 0 and 2 (a kink next to some extremes)
    kinks = [shared, np.zeros(0), shared, np.array([t[30], t[2]])]  # (any order)
    rows = smooth_vertices_rows(t, dynamic, static, kinks)
    for k in range(4):
        _same(rows[k], smooth_vertices(t, dynamic[k], static[k], kinks[k]))
    assert sum(r[0].size for r in rows) > 3  # the case has vertices
    short = smooth_vertices_rows(t[:2], dynamic[:, :2], static[:, :2], kinks)
    assert all(r[0].size == 0 for r in short)


def test_a_runs_peak_series_through_the_shared_vertices_is_that_of_its_own_kinks(deck, deck_run):
    for r in load_effect_responses(deck_run, _effects(deck), check_step=False):
        alone = dataclasses.replace(r, vertices=None)  # (the kinks as they are: smooth_vertices of this response)
        _same(r.peak_series, alone.peak_series)
        assert r.impact == alone.impact


def test_passing_instants_of_effects_together_are_each_effects_alone(deck, deck_run):
    """Equal blocks of positions (the reactions' and the shear's deck ends, every effect's station kinks) are
    timed once and shared: each effect's instants must still be its own."""
    effects = _effects(deck)
    forget_kept()
    together = _passing_instants(deck_run, effects, "jump", "kink")
    for k, e in enumerate(effects):
        forget_kept()
        alone = _passing_instants(deck_run, [e], "jump", "kink")
        for kind in range(2):
            np.testing.assert_array_equal(together[kind][k], alone[kind][0])
    assert any(together[0][k].size != together[0][0].size for k in range(1, 4))  # the effects' jumps differ


def test_modal_rates_follow_the_bridge():
    stiff, soft = paper_beam(16.76, "II", n_modes=6), paper_beam(16.76, "II", n_modes=6, damping_ratio=0.05)
    forget_kept()
    for bridge in (stiff, soft, stiff):
        result = simulate(Crossing(bridge, hs20_44(), speed=20.0))
        zeta_omega = 2.0 * np.asarray(bridge.damping_ratios) * np.asarray(bridge.omega)
        np.testing.assert_array_equal(modal_rates(result), result.xi_ddot + result.xi_dot * zeta_omega)
        terms = modal_terms(bridge)
        np.testing.assert_array_equal(terms[0], zeta_omega)
        np.testing.assert_array_equal(terms[1], np.asarray(bridge.omega) ** 2)
        # a history not in one block (a column slice): the plain sum
        thinned = dataclasses.replace(result, xi_dot=np.asfortranarray(result.xi_dot))
        np.testing.assert_array_equal(modal_rates(thinned), result.xi_ddot + result.xi_dot * zeta_omega)


def test_distinct_sorted_is_np_unique():
    rng = np.random.default_rng(11)
    for n in (0, 1, 2, 3, 17):
        for _ in range(30):
            values = rng.integers(-4, 5, n) * 0.25
            np.testing.assert_array_equal(distinct_sorted(values), np.unique(values))


def test_shared_travel_is_the_travel(deck_run):
    np.testing.assert_array_equal(deck_run.shared_travel(), deck_run.travel)
    assert deck_run.shared_travel() is deck_run.shared_travel()  # (the kept array, no copy)
    fresh = dataclasses.replace(deck_run)  # nothing kept yet: computed and kept on first read
    np.testing.assert_array_equal(fresh.shared_travel(), deck_run.travel)


def _hermite_peak_as_it_was(time, values, rates, i):
    """``impact.hermite_peak`` as written before it read its samples as Python floats and took its roots with
    ``math`` (numpy's scalars throughout): the reference its values must equal bit for bit."""
    best, t_best = float(values[i]), float(time[i])
    for j in (i - 1, i):
        if j < 0 or j + 1 >= values.size:
            continue
        h = float(time[j + 1] - time[j])
        y0, y1, d0, d1 = float(values[j]), float(values[j + 1]), h * float(rates[j]), h * float(rates[j + 1])
        a = 6 * y0 + 3 * d0 - 6 * y1 + 3 * d1
        b = -6 * y0 - 4 * d0 + 6 * y1 - 2 * d1
        c = d0
        if a == 0.0:
            roots = (-c / b,) if b != 0.0 else ()
        else:
            disc = b * b - 4.0 * a * c
            if disc < 0.0:
                roots = (-b / (2.0 * a),) if np.sqrt(-disc) / (2.0 * abs(a)) <= 1e-12 else ()
            else:
                q = -0.5 * (b + np.copysign(np.sqrt(disc), b))
                roots = (q / a, c / q) if q != 0.0 else (0.0,)
        for s in roots:
            if not 0.0 < s < 1.0:
                continue
            y = (y0 * (2 * s**3 - 3 * s**2 + 1) + d0 * (s**3 - 2 * s**2 + s) + y1 * (-2 * s**3 + 3 * s**2)
                 + d1 * (s**3 - s**2))
            if y > best:
                best, t_best = float(y), float(time[j] + s * h)
    return best, t_best


def test_hermite_peak_is_the_numpy_scalar_reference():
    from vbikit.analysis.impact import hermite_peak

    rng = np.random.default_rng(5)
    found = 0
    for _ in range(3000):
        n = int(rng.integers(1, 4))
        t = np.cumsum(rng.uniform(1e-4, 2e-3, n)) + rng.uniform(0, 5)
        values = rng.normal(size=n)
        rates = rng.normal(scale=rng.choice([1e-3, 1.0, 1e3]), size=n)
        if rng.random() < 0.1:
            rates[:] = 0.0  # (a = 0 and a double root)
        i = int(np.argmax(values))
        new, old = hermite_peak(t, values, rates, i), _hermite_peak_as_it_was(t, values, rates, i)
        assert new == old and all(type(v) is float for v in new)
        found += new[0] > values[i]
    assert found > 300  # peaks between the samples found, not only the samples
