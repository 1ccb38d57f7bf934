"""Skew support lines on the slab-on-girder grillage: checks that need no other code.

Each test compares with a number that does not come from the skew implementation: the square
deck (skew 0 must be it bit for bit), rigid-body motion (no strain: zero nodal forces), the deck's
mass (a skew deck of the same span and width has the same plan area and mass), static
equilibrium of the bearing reactions (force and both moments), and the 180° rotational
symmetry of a skew deck (a truck driving −x on the other side of the centreline sees the
rotated deck).  The comparison with an independent OpenSeesPy grillage is in
``test_opensees_skew.py``.
"""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis import point_response
from vbikit.bridge import paper_deck
from vbikit.road.profile import RoadProfile
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.solve.crossing import VehicleMotion
from vbikit.vehicle import hs20_44


@pytest.fixture(scope="module")
def skewed():
    return paper_deck(2, n_modes=8, skew=30.0, use_cache=False)


def test_skew_zero_is_the_square_deck_bit_for_bit():
    square = paper_deck(2, n_modes=6, use_cache=False)
    zero = paper_deck(2, n_modes=6, skew=0.0, use_cache=False)
    assert zero.cache_key() == square.cache_key()  # the square deck keeps its cached modes
    assert np.array_equal(zero.omega, square.omega)
    for name in ("w", "wx", "wy"):
        assert np.array_equal(getattr(zero.nodal_modes, name), getattr(square.nodal_modes, name))
    assert zero.deck_extent == (0.0, square.span)
    assert paper_deck(2, n_modes=6, skew=10.0, use_cache=False).cache_key() != square.cache_key()


def _rigid_plane(bridge, a: float, b: float, c: float) -> np.ndarray:
    """Nodal DOFs (w, ∂w/∂x, ∂w/∂y) of the rigid motion w = a + b x + c y at every node (x of line j's
    node i = ξ_i + y_j tan θ)."""
    u = np.zeros(3 * bridge.n_girders * (bridge.element_count + 1))
    for j, y in enumerate(bridge.girder_y):
        x = bridge.stations + y * bridge.skew_tan
        for i, xi in enumerate(x):
            u[bridge.dof_map.dof(j, i, 0)] = a + b * xi + c * y
            u[bridge.dof_map.dof(j, i, 1)] = b
            u[bridge.dof_map.dof(j, i, 2)] = c
    return u


@pytest.mark.parametrize("skew", [-35.0, 15.0, 40.0])
def test_rigid_motion_strains_no_member(skew):
    """K u = 0 for every rigid plane w = a + b x + c y (before the supports are applied): a wrong
    sign or factor in the oblique members' transformation strains them under a tilt (measured
    ≤ 3.3e-15 of the largest stiffness entry)."""
    bridge = paper_deck(2, n_modes=2, skew=skew, use_cache=False)
    K, _, _ = bridge.assemble()
    scale = np.abs(K).max()
    for plane in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.3, -0.2, 0.7)):
        f = K @ _rigid_plane(bridge, *plane)
        assert np.abs(f).max() < 1e-14 * scale, plane


@pytest.mark.parametrize("skew", [0.0, 25.0, -40.0])
def test_deck_mass_is_that_of_the_square_deck(skew):
    """Translating the whole deck by w = 1: uᵀ M u is the total mass, and a skew deck of the same
    span and width has the same plan area, hence the same mass as the square one (girders, slab,
    overhangs; the diaphragms lie along the support lines, longer by 1/cos θ)."""
    square = paper_deck(2, n_modes=2, use_cache=False)
    bridge = paper_deck(2, n_modes=2, skew=skew, use_cache=False)
    u = _rigid_plane(bridge, 1.0, 0.0, 0.0)
    total = u @ (bridge.assemble()[1] @ u)
    u0 = _rigid_plane(square, 1.0, 0.0, 0.0)
    total0 = u0 @ (square.assemble()[1] @ u0)
    # diaphragm mass per member length ρ b_d h_d over (n − 1) members of length s / cos θ, two ends
    hd, bd = 0.75 * square.section.depth, square.diaphragm_width
    diaphragms = len(square.diaphragms) * square.density * bd * hd * (square.n_girders - 1) * square.girder_spacing
    cos = np.cos(np.radians(skew))
    assert total == pytest.approx(total0 + diaphragms * (1.0 / cos - 1.0), rel=1e-12)


@pytest.fixture(scope="module")
def continuous_skewed():
    return paper_deck(2, n_modes=4, spans=(16.76, 20.0, 16.76), skew=20.0, use_cache=False)


@pytest.mark.parametrize("deck, where", [("skewed", (4.3, -3.1)), ("skewed", (8.2, 0.4)), ("skewed", (12.9, 4.0)),
                                         ("skewed", (16.0, 2.2)), ("continuous_skewed", (8.2, 0.4)),
                                         ("continuous_skewed", (25.0, 1.0)), ("continuous_skewed", (47.0, -4.0))])
def test_bearing_reactions_are_in_equilibrium(deck, where, request):
    """A point load P at (x, y): the bearing reactions (influence functions of every girder's
    bearings, at their own x = x_k + y_g tan θ) sum to P and their moments about both axes to P·x
    and P·y — statics alone, on a simple span (30°) and a three-span continuous deck (20°)
    (measured: force 2.2e-11, moments 2.1e-10 m)."""
    bridge = request.getfixturevalue(deck)
    x, y = where
    x = x + y * bridge.skew_tan  # a point on the deck: ξ = x − y tan θ = the given value
    total = mx = my = 0.0
    for g in range(1, bridge.n_girders + 1):
        for support in range(bridge.support_x.size):
            effect = bridge.load_effect("reaction", support=support, girder=g)
            r = -float(effect.influence(np.array([x]), np.array([y]))[0])  # reaction to a unit downward load
            total += r
            mx += r * effect.x
            my += r * bridge.girder_y[g - 1]
    assert total == pytest.approx(1.0, abs=1e-10)
    assert mx == pytest.approx(x, abs=1e-9)
    assert my == pytest.approx(y, abs=1e-9)


def test_support_lines_and_off_deck_points(skewed):
    """The mode shapes vanish on every bearing (rigid supports) and beyond the oblique ends; the
    deck's x extent reaches (width/2)·tan θ beyond 0 and span."""
    b = skewed
    t = b.skew_tan
    reach = 0.5 * b.deck_width * t
    assert b.deck_extent == pytest.approx((-reach, b.span + reach), rel=1e-15)
    y = b.girder_y
    for x0 in (0.0, b.span):
        np.testing.assert_array_equal(b.mode_shapes(x0 + y * t, y), 0.0)
    y_edge = 0.5 * b.deck_width
    assert np.all(b.mode_shapes([-reach - 1e-9, b.span + reach + 1e-9], [-y_edge, y_edge]) == 0.0)
    assert np.any(b.mode_shapes([b.span / 2 + 3.0 * t], [3.0]) != 0.0)


def test_skew_changes_the_frequencies_and_is_even_in_the_angle():
    """±θ decks are mirror images (y → −y) of each other: same frequencies (measured to round-off);
    a skew of 30° moves the first torsion and transverse modes (the square deck's are not kept)."""
    plus = paper_deck(2, n_modes=6, skew=30.0, use_cache=False)
    minus = paper_deck(2, n_modes=6, skew=-30.0, use_cache=False)
    square = paper_deck(2, n_modes=6, use_cache=False)
    np.testing.assert_allclose(plus.omega, minus.omega, rtol=1e-10)
    assert np.abs(plus.frequencies_hz / square.frequencies_hz - 1.0).max() > 0.01


def test_truck_driving_minus_x_sees_the_rotated_deck(skewed):
    """A skew deck is symmetric under the half turn (x, y) → (span − x, −y) about its centre: a truck
    driving −x at lateral offset −e on the mirrored road responds at (x, y) as the truck driving +x
    at offset e responds at (span − x, −y) — the oblique ends, the deck's x extent, the exit time
    and the track tables all enter.  Measured 1.1e-7 of the peak wheel force and 2e-9 of the peak
    deflection: each track's table starts at its own support line, so a grid point falls on the
    midspan station of the FE mesh, where ∂φ/∂x between girder lines jumps on a skew deck
    (tan θ ∂²w/∂ξ² of the lines, read on the element to the right) — the two runs read that jump
    from opposite sides there; away from it the two runs agree to round-off."""
    bridge = skewed
    span = bridge.span
    road = random_profile(RoadPSD.iso("C"), seed=4, length=400.0, x_start=-200.0037)
    mirrored = RoadProfile(span - road.x[::-1], road.z[::-1], "mirrored")
    e = 1.4
    kw = dict(approach=10.0, free_vibration=0.2, dt=2e-4)
    plus = simulate(Crossing(bridge, road=road, vehicles=(VehicleMotion(hs20_44(), 20.0, lateral_offset=e),), **kw))
    minus = simulate(Crossing(bridge, road=mirrored, vehicles=(VehicleMotion(hs20_44(), 20.0, direction="-x",
                                                                            lateral_offset=-e),), **kw))
    assert plus.time.size == minus.time.size
    np.testing.assert_allclose(minus.wheel_forces, plus.wheel_forces, rtol=0, atol=3e-7 * plus.wheel_forces.max())
    for x, y in ((0.5 * span, 2.13), (0.3 * span, -2.13), (0.6 * span + 2.13 * bridge.skew_tan, 2.13)):
        d_minus = point_response(minus, x, y).displacement
        d_plus = point_response(plus, span - x, -y).displacement
        assert np.abs(d_minus - d_plus).max() < 1e-8 * np.abs(d_plus).max()


def test_static_reactions_carry_the_truck_on_the_oblique_ends(skewed):
    """While a truck crosses, the static bearing reactions of all girders sum at every instant to
    the static wheel loads on the deck — counting the wheels on the parts of the deck before x = 0
    and after x = span that the oblique ends add (a right-lane truck on a 30° deck enters at
    x = y tan θ < 0); measured 1.7e-11 of the truck's weight."""
    from vbikit.analysis.effects import contact_positions, load_effect_response

    bridge = skewed
    result = simulate(Crossing(bridge, vehicle=hs20_44(), speed=20.0, lateral_offset=-2.8, free_vibration=0.05))
    total = np.zeros(result.time.size)
    for g in range(1, bridge.n_girders + 1):
        for support in (0, 1):
            total += load_effect_response(result, bridge.load_effect("reaction", support=support, girder=g)).static
    x, y = contact_positions(result)
    cp = result.crossing.contact
    loads = cp.weight * result.crossing.vehicle.static_wheel_loads()[cp.wheel]
    xi = bridge.span_coordinate(x, y)
    on = (xi >= 0.0) & (xi <= bridge.span)
    assert np.any(on & (x < 0.0))  # the case this test is about: wheels on the deck before x = 0
    expected = (on * loads).sum(axis=1)
    assert np.abs(total - expected).max() < 1e-10 * loads.sum()


def test_a_section_at_a_station_is_read_just_right_of_it_on_every_girder(skewed):
    """The grillage's girder moment jumps at a node by the couple of the transverse members there
    (their torsion and, on a skew, their bending act on ∂w/∂x); a moment or shear at a station is
    documented as the one just right of it.  On a skew deck a girder's station ξ_i is asked for at
    x = ξ_i + y_g tan θ, whose ξ = x − y_g tan θ can come back an ulp below ξ_i: it must still
    be the right-hand value, the same as at ξ_i + 1 µm up to the 1 µm lever of the shear (and not
    the left-hand one, ξ_i − 1 µm, which differs by the jump)."""
    bridge = skewed
    px, py = np.meshgrid(np.linspace(1.0, 17.0, 9), np.linspace(-4.0, 4.0, 5))
    px, py = px.ravel(), py.ravel()
    d = 1e-6  # [m]
    jumps = []
    for g in range(1, bridge.n_girders + 1):
        for xi in bridge.stations[1:-1]:
            x = float(bridge.girder_x(g, xi))
            shear_right = bridge.load_effect("shear", x + d, girder=g)
            for kind in ("moment", "shear"):
                at = bridge.load_effect(kind, x, girder=g)
                right = bridge.load_effect(kind, x + d, girder=g)
                # no load between ξ_i and ξ_i + d: V is the same there and M(ξ_i⁺) = M(ξ_i + d) − V d
                expected = right.influence(px, py) - (d * shear_right.influence(px, py) if kind == "moment" else 0.0)
                scale = np.abs(expected).max()
                assert np.abs(at.influence(px, py) - expected).max() < 1e-9 * scale, (g, xi, kind)  # measured 2.5e-13
                assert np.abs(at.modal - right.modal).max() < 1e-5 * np.abs(right.modal).max(), (g, xi, kind)
                if kind == "moment":
                    left = bridge.load_effect(kind, x - d, girder=g)
                    jumps.append(np.abs(left.influence(px, py) - right.influence(px, py)).max() / scale)
    assert max(jumps) > 1e-2  # the jump the choice is about: measured up to 0.075 of the peak influence (median 0.009)


def test_a_section_at_the_exit_bearing_of_a_skew_girder_is_on_the_span(skewed):
    """x = y_g tan θ and span + y_g tan θ are on girder g's span whatever their round-off: a section
    1e-12 m beyond the bearing is the bearing's section (same influence at a few deck points, to
    1e-12 of the midspan moment's), not an error and not the neighbouring element's."""
    xs = np.array([3.0, 8.0, 12.0])
    ys = np.array([-2.0, 0.5, 3.0])
    pts = (xs + ys * skewed.skew_tan, ys)
    for g in range(1, skewed.n_girders + 1):
        scale = np.abs(skewed.load_effect("moment", float(skewed.girder_x(g, 0.5 * skewed.span)), girder=g).influence(*pts)).max()
        for xi, nudge in ((0.0, -1e-12), (skewed.span, 1e-12)):
            at = skewed.load_effect("moment", float(skewed.girder_x(g, xi)), girder=g).influence(*pts)
            beyond = skewed.load_effect("moment", float(skewed.girder_x(g, xi)) + nudge, girder=g).influence(*pts)
            assert np.abs(beyond - at).max() < 1e-12 * scale


def test_girder_strain_at_a_station_is_read_just_right_of_it(skewed):
    """The modal girder curvature (hence strain) of the Hermite elements jumps at a node; as for the
    moment, a station of girder g given as x = ξ_i + y_g tan θ is read on the element right of it
    whatever the round-off of x − y_g tan θ."""
    bridge = skewed
    d = 1e-6  # [m]
    jumps = []
    for g in range(1, bridge.n_girders + 1):
        y = float(bridge.girder_y[g - 1])
        for xi in bridge.stations[1:-1]:
            x = float(bridge.girder_x(g, xi))
            at, right, left = (bridge.strain_shapes(v, y)[0] for v in (x, x + d, x - d))
            scale = np.abs(right).max()
            assert np.abs(at - right).max() < 1e-4 * scale, (g, xi)  # the curvature's slope over d: measured ≤ 2e-6
            jumps.append(np.abs(left - right).max() / scale)
    assert max(jumps) > 1e-2  # measured up to 0.3 (the highest kept mode)


def test_loaded_length_is_the_span_of_the_section_along_its_girder():
    """On a continuous skew deck the design-code loaded length is the span holding the response
    section along its girder: Girder 5 (y = 4.26 m) of a 40° deck with spans 16 + 24 m at x = 19 m is
    at ξ = 19 − 4.26 tan 40° = 15.43 m, in the 16 m span (the deck's x alone would say the 24 m one)."""
    from vbikit.analysis.effects import loaded_length

    bridge = paper_deck(2, n_modes=2, spans=(16.0, 24.0), skew=40.0, use_cache=False)
    assert loaded_length(bridge, 19.0, 4.26) == 16.0
    assert loaded_length(bridge, 19.0, -4.26) == 24.0
