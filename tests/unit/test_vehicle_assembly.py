"""``VehicleBuilder.build`` and the vehicle's tire matrices against their definitions written out as
dense outer products added one by one (``vbikit.vehicle.builder``, module docstring:
M = Σ_b (m h hᵀ + J_θ p pᵀ + J_φ r rᵀ), F_G = −g Σ_b m h, K (C) = Σ_s k (c) d dᵀ with d = a − b;
``Vehicle.tire_stiffness_matrix`` = Σ_w k_w r_w r_wᵀ): the same bits, for a hand-built vehicle
(hinged body, pivoted beam, springs to the ground) and the trucks of a traffic stream."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.vehicle import axles as axles_module
from vbikit.vehicle import builder as builder_module
from vbikit.vehicle.axles import GROUP_KINDS, axle_truck, semitrailer_3s2
from vbikit.vehicle.builder import VehicleBuilder
from vbikit.vehicle.model import GRAVITY, combine_vehicles


def dense(row, n):
    v = np.zeros(n)
    for i, c in row.items():
        v[i] += c
    return v


def by_definition(vb: VehicleBuilder):
    n = len(vb.dofs)
    m, k, c, fg = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n)), np.zeros(n)
    for b in vb.bodies:
        h, p, r = dense(b.heave, n), dense(b.pitch, n), dense(b.roll, n)
        m += b.mass * np.outer(h, h) + b.pitch_inertia * np.outer(p, p) + b.roll_inertia * np.outer(r, r)
        fg -= GRAVITY * b.mass * h
    for a, b_, ks, cs in vb.springs:
        d = dense(a, n) - dense(b_, n)
        k += ks * np.outer(d, d)
        c += cs * np.outer(d, d)
    return m, k, c, fg


def hand_built() -> VehicleBuilder:
    vb = VehicleBuilder("test")
    tractor = vb.body("tractor", 7000.0, 2.1, pitch_inertia=2.1e4, roll_inertia=4e3, pitch=True, roll=True)
    trailer = vb.hinged_body("trailer", 15000.0, 7.3, tractor, 3.9, pitch_inertia=1.5e5, roll_inertia=1e4, roll=True)
    beam = vb.pivoted_beam("beam", trailer, 11.0, 0.9, mass=300.0, pitch_inertia=120.0)
    axle = vb.body("axle1", 700.0, 0.0, roll_inertia=600.0, roll=True)
    for y in (0.9, -0.9):
        vb.spring(tractor.point(0.0, y), axle.point(0.0, y), 3e5, 1e4)
        vb.wheel(f"front_{y}", axle.point(0.0, y), 0.0, y, 8e5, 2e3)
    vb.spring(beam.point(10.4, 0.9), None, 2e6, 5e3)  # to the ground
    vb.wheel("rear", beam.point(11.6, 0.9), 11.6, 0.9, 1e6, 1e3)
    return vb


def test_hand_built_vehicle_matrices_are_the_definition_bit_for_bit():
    vb = hand_built()
    v = vb.build()
    m, k, c, fg = by_definition(vb)
    for got, want in ((v.mass, m), (v.stiffness, k), (v.damping, c), (v.gravity, fg)):
        assert got.shape == want.shape and np.array_equal(got, want)
    assert np.count_nonzero(v.stiffness) > 10 and np.count_nonzero(v.mass - np.diag(np.diag(v.mass))) > 0
    tires = sum(w.stiffness * np.outer(w.row, w.row) for w in v.wheels)
    assert np.array_equal(v.tire_stiffness_matrix(), tires)


@pytest.mark.parametrize("loads, spacings", [((53e3, 75e3, 74e3, 76e3, 73e3), (5.5, 1.3, 9.5, 1.3)),
                                             ((45e3, 90e3), (5.0,)), ((55e3, 85e3, 85e3), (5.0, 1.3))])
def test_axle_trucks_are_the_definition_bit_for_bit(loads, spacings, monkeypatch):
    specs, seen = [], []
    fast = axles_module.build_truck
    monkeypatch.setattr(axles_module, "build_truck", lambda *a, **kw: specs.append((a, kw)) or fast(*a, **kw))
    v = axle_truck(loads, spacings)  # (by its layout: ``_TruckLayout``)
    build = builder_module.VehicleBuilder.build
    monkeypatch.setattr(builder_module.VehicleBuilder, "build", lambda self, *a, **kw: seen.append(self) or build(self, *a, **kw))
    axles_module._build_truck_with_builder(*specs[0][0], **specs[0][1])
    m, k, c, fg = by_definition(seen[0])
    for got, want in ((v.mass, m), (v.stiffness, k), (v.damping, c), (v.gravity, fg)):
        assert np.array_equal(got, want)
    # a combined vehicle's blocks are its parts' matrices; the static wheel loads sum to the axle loads
    both = combine_vehicles([v, hand_built().build()])
    n = v.n_dof
    assert np.array_equal(both.mass[:n, :n], v.mass) and not both.stiffness[:n, n:].any()
    assert both.static_wheel_loads()[:len(v.wheels)].sum() == pytest.approx(sum(loads), rel=1e-12)


def _same_vehicle(v, w) -> None:
    """``v`` and ``w`` alike bit for bit: DOFs, matrices, wheels (names, positions, tires, rows with their
    signs of zero), bodies, name, description and parameters."""
    assert v.dof_names == w.dof_names and v.name == w.name and v.description == w.description
    assert v.parameters == w.parameters
    for attr in ("mass", "damping", "stiffness", "gravity"):
        assert np.array_equal(getattr(v, attr), getattr(w, attr)), attr
    assert [(x.name, x.offset, x.lateral, x.stiffness, x.damping, x.fixed_load) for x in v.wheels] == \
        [(x.name, x.offset, x.lateral, x.stiffness, x.damping, x.fixed_load) for x in w.wheels]
    for x, y in zip(v.wheels, w.wheels):
        assert np.array_equal(x.row, y.row) and np.array_equal(np.signbit(x.row), np.signbit(y.row))
    assert v.bodies.keys() == w.bodies.keys()
    for name, (s_cg, *rows) in v.bodies.items():
        assert s_cg == w.bodies[name][0] and all(np.array_equal(a, b) for a, b in zip(rows, w.bodies[name][1:]))


LAYOUTS = [dict(groups=None), dict(groups=["single", "walking-beam", "walking-beam"]),
           dict(groups=["single", "tandem", "tridem"]), dict(groups=["single", "walking-beam", "tridem"], tractor_groups=2),
           dict(groups=["single", "walking-beam", "single"], tractor_groups=2), dict(groups=["tandem", "tandem"]),
           dict(groups=["single", "tandem", "walking-beam"], tractor_groups=2),
           dict(groups=["single", "tandem", "single", "tandem"], tractor_groups=3)]


@pytest.mark.parametrize("layout", LAYOUTS)
def test_truck_layouts_build_the_builders_vehicle_bit_for_bit(layout, monkeypatch):
    """``build_truck`` fills each layout's rows (``_TruckLayout``) instead of running ``VehicleBuilder``:
    the same vehicle, bit for bit, for rigid and articulated trucks, independent axles and walking beams,
    random loads and spacings (many trucks of one layout: the kept layout serves them all)."""
    specs = []
    fast = axles_module.build_truck
    monkeypatch.setattr(axles_module, "build_truck", lambda *a, **kw: specs.append((a, kw)) or fast(*a, **kw))
    rng = np.random.default_rng(7)
    n_axles = sum(GROUP_KINDS[g] for g in layout["groups"]) if layout["groups"] else 5
    built = []
    for _ in range(12):
        spacings = rng.uniform(1.1, 1.8, n_axles - 1) if layout["groups"] else rng.uniform(1.2, 6.0, n_axles - 1)
        if layout["groups"]:
            spacings[rng.random(n_axles - 1) < 0.5] += 3.0
        try:
            built.append(axle_truck(rng.uniform(40e3, 95e3, n_axles), spacings, **layout))
        except ValueError:  # (loads that cannot carry a semitrailer)
            continue
    assert len(built) >= 6
    for v, (args, kw) in zip(built, specs):
        _same_vehicle(v, axles_module._build_truck_with_builder(*args, **kw))


def test_the_3s2_by_its_layout_is_the_builders():
    specs = []
    fast = axles_module.build_truck
    try:
        axles_module.build_truck = lambda *a, **kw: specs.append((a, kw)) or fast(*a, **kw)
        v = semitrailer_3s2()
    finally:
        axles_module.build_truck = fast
    _same_vehicle(v, axles_module._build_truck_with_builder(*specs[0][0], **specs[0][1]))


def test_trucks_of_one_layout_differing_in_one_axle_load_differ():
    """A kept layout holds no truck's numbers: two trucks of one layout built one after the other, alike but
    for their third axle's load, get their own masses, springs and rows (a layout keyed or filled wrongly
    would hand the second the first's)."""
    loads = [50e3, 75e3, 74e3, 76e3, 73e3]
    a = axle_truck(loads, (5.5, 1.3, 9.5, 1.3))
    b = axle_truck(loads[:2] + [60e3] + loads[3:], (5.5, 1.3, 9.5, 1.3))
    assert a.dof_names == b.dof_names
    assert not np.array_equal(a.stiffness, b.stiffness) and not np.array_equal(a.mass, b.mass)
    assert sum(b.static_wheel_loads()) == pytest.approx(sum(loads) - 14e3, rel=1e-12)
    assert sum(a.static_wheel_loads()) == pytest.approx(sum(loads), rel=1e-12)
    # and each is the builder's own
    specs = []
    fast = axles_module.build_truck
    try:
        axles_module.build_truck = lambda *a_, **kw: specs.append((a_, kw)) or fast(*a_, **kw)
        c = axle_truck(loads[:2] + [60e3] + loads[3:], (5.5, 1.3, 9.5, 1.3))
    finally:
        axles_module.build_truck = fast
    _same_vehicle(c, axles_module._build_truck_with_builder(*specs[0][0], **specs[0][1]))
    _same_vehicle(b, c)
