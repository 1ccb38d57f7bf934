"""Modes imported from a file (src/vbikit/bridge/modefile.py): a file written from our own
slab-on-girder model and read back must reproduce the native crossing exactly (issue 4), and
a file without slopes (as most FE programs export: nodal w only) must approximate it closely."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import BRIDGE_PRESETS, paper_deck
from vbikit.bridge.modefile import ModeFileError, modes_from_file, write_modes
from vbikit.contact.tires import MultiPointTire
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.solve import simulate
from vbikit.solve.crossing import Crossing
from vbikit.vehicle.presets import VEHICLE_PRESETS


def crossing(bridge):
    road = random_profile(RoadPSD.iso("C"), 3, spacing=0.01, length=200.0)
    return Crossing(bridge=bridge, vehicle=VEHICLE_PRESETS["hs20-44"].build(), tire=MultiPointTire(4, 0.254),
                    road=road, speed=20.0, approach=5.0, lateral_offset=bridge.default_lateral_offset)


def test_round_trip_reproduces_native_crossing_exactly(tmp_path):
    native = BRIDGE_PRESETS["paper-bridge-1"].build(n_modes=8)
    path = write_modes(native, tmp_path / "bridge1.csv")
    imported = modes_from_file(path)
    assert np.array_equal(imported.omega, native.omega)
    assert np.array_equal(imported.damping_ratios, native.damping_ratios)
    assert np.array_equal(imported.girder_y, native.girder_y)
    assert imported.default_girder == 4 and imported.default_lateral_offset == native.default_lateral_offset
    a, b = simulate(crossing(native)), simulate(crossing(imported))
    assert np.array_equal(a.xi, b.xi) and np.array_equal(a.q, b.q)
    x, y = np.linspace(-1, 10, 57), np.linspace(-5, 5, 57)
    assert np.array_equal(imported.strain_shapes(x, y), native.strain_shapes(x, y))
    assert imported.skew_tan == 0.0 and "skew" not in path.read_text()  # no header: square supports


def test_values_only_file_is_close(tmp_path):
    native = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=6)
    path = write_modes(native, tmp_path / "full.csv")
    lines = path.read_text().splitlines()
    n = 6
    keep = [ln if ln.startswith("#") else ",".join(ln.split(",")[: 2 + n]) for ln in lines]
    (tmp_path / "w_only.csv").write_text("\n".join(keep) + "\n")
    imported = modes_from_file(tmp_path / "w_only.csv")
    X, Y = np.meshgrid(np.linspace(0, native.span, 83), np.linspace(-4.8, 4.8, 41))
    x, y = X.ravel(), Y.ravel()
    # On the node lines only the x-slopes are estimated (not-a-knot spline through 35 stations,
    # error O(h⁴) in values, O(h³) in slopes): measured 1e-5 / 5e-4 of each mode's peak.
    yl = np.full_like(x, 2.13)
    for f in ("mode_shapes", "mode_slopes"):
        ref, got = getattr(native, f)(x, yl), getattr(imported, f)(x, yl)
        assert np.all(np.abs(got - ref).max(axis=0) <= 2e-3 * np.abs(ref).max(axis=0))
    # Across y the transverse slopes come from a spline through only 5 girder lines: fine for the
    # bending, torsion and first transverse mode (measured 0.1 / 0.4 / 1.4 % of the peak), poor for
    # modes with 3+ nodal lines (29 % for mode 4) — a values-only export needs nodes between girders.
    ref, got = native.mode_shapes(x, y), imported.mode_shapes(x, y)
    err = np.abs(got - ref).max(axis=0) / np.abs(ref).max(axis=0)
    assert np.all(err[:3] < 0.02)


@pytest.mark.parametrize("mutate, message", [
    (lambda t: t.replace("# vbikit-modes 1", "# something else"), "first line"),
    (lambda t: "\n".join(ln for ln in t.splitlines() if not ln.startswith("# span")), "span"),
    (lambda t: t.replace("x,y,w_1", "x,y,w_one"), "columns"),
    (lambda t: "\n".join(t.splitlines()[:-1]), "rectangular grid"),
])
def test_bad_files_are_named(tmp_path, mutate, message):
    path = write_modes(BRIDGE_PRESETS["paper-bridge-1"].build(n_modes=3), tmp_path / "m.csv")
    path.write_text(mutate(path.read_text()))
    with pytest.raises(ModeFileError, match=message):
        modes_from_file(path)


@pytest.fixture(scope="module")
def skewed():
    return paper_deck(2, n_modes=6, skew=25.0, use_cache=False)


def _deck_points(bridge, n=400, seed=7):
    """Random points over the deck's plan, including the overhangs and the triangles beyond the
    square ends that a skew deck adds, and some off the deck."""
    rng = np.random.default_rng(seed)
    lo, hi = bridge.deck_extent
    return rng.uniform(lo - 0.5, hi + 0.5, n), rng.uniform(-0.5 * bridge.deck_width, 0.5 * bridge.deck_width, n)


def test_skew_round_trip_is_exact(tmp_path, skewed):
    """A skew deck of vbikit's own grillage written and read back is that deck: the reference is the
    native model itself, evaluated at points it was not tabulated at."""
    native = skewed
    path = write_modes(native, tmp_path / "skew25.csv")
    text = path.read_text()
    assert "# skew = 25.0\n" in text and "\nxi,y,w_1," in text and "# deck_width = 9.75\n" in text
    assert "skew_tan" not in text  # 25° gives the deck's tan θ exactly
    imported = modes_from_file(path)
    assert imported.skew_tan == native.skew_tan == np.tan(np.radians(25.0))
    assert np.array_equal(imported.omega, native.omega)
    assert imported.deck_extent == native.deck_extent
    assert imported.default_response_x == native.default_response_x  # Girder 4's own midspan
    assert imported.default_x_at(-2.13) == native.default_x_at(-2.13)
    x, y = _deck_points(native)
    assert np.array_equal(imported.span_coordinate(x, y), native.span_coordinate(x, y))
    for f in ("mode_shapes", "mode_slopes", "strain_shapes"):
        assert np.array_equal(getattr(imported, f)(x, y), getattr(native, f)(x, y)), f
    again = write_modes(imported, tmp_path / "again.csv")  # an imported skew deck writes the same file
    assert again.read_text() == text.replace("skew25", "again")
    a, b = simulate(crossing(native)), simulate(crossing(imported))
    assert np.array_equal(a.xi, b.xi) and np.array_equal(a.q, b.q)


def _rewrite(path, out, row):
    """Copy a mode file, passing every data row (as floats) through ``row``."""
    lines = []
    for ln in path.read_text().splitlines():
        if ln.startswith("#"):
            lines.append(ln)
        elif ln.startswith("xi,"):
            lines.append("x" + ln[2:])
        else:
            lines.append(row([float(v) for v in ln.split(",")]))
    out.write_text("\n".join(lines) + "\n")
    return out


def test_skew_file_with_plan_coordinates(tmp_path, skewed):
    """An oblique mesh as FE programs export it: the nodes' plan x (here to 8 significant digits,
    0.1 µm on this span) with the skew header; the stations come back to that precision."""
    native = skewed
    t = native.skew_tan
    path = write_modes(native, tmp_path / "xi.csv")
    plan = _rewrite(path, tmp_path / "plan.csv", lambda v: ",".join([f"{v[0] + v[1] * t:.8g}"] + [repr(a) for a in v[1:]]))
    imported = modes_from_file(plan)
    # 8 digits of x ≤ 18.8 m: rounded by ≤ 5e-7 m, and the station is the mean over the lines (measured 1.6e-7 m)
    assert np.abs(imported.modes.x - native.nodal_modes.x).max() < 5e-7
    x, y = _deck_points(native)
    ref = native.mode_shapes(x, y)
    # measured 4.0e-8 of the largest value
    assert np.abs(imported.mode_shapes(x, y) - ref).max() < 1e-7 * np.abs(ref).max()
    # one node 1 mm off its station (6e-5 of the span): refused, naming it and its offset from the
    # mean station of the five lines, 4/5 of 1 mm
    bad = _rewrite(path, tmp_path / "bad.csv", lambda v: ",".join(
        [repr(v[0] + v[1] * t + (1e-3 if (v[0], v[1]) == (native.stations[7], 2.13) else 0.0))] + [repr(a) for a in v[1:]]))
    with pytest.raises(ModeFileError, match=r"line y = 2.13 is 0.0008 m from station 7"):
        modes_from_file(bad)


def test_skew_values_only_file_is_close(tmp_path, skewed):
    """Without slopes the skew file's ∂w/∂y comes from splines across the lines at constant ξ (along
    the oblique members) less tan θ ∂w/∂x: the same accuracy as the square deck's values-only file."""
    native = skewed
    n = 6
    path = write_modes(native, tmp_path / "full.csv")
    keep = [ln if ln.startswith("#") else ",".join(ln.split(",")[: 2 + n]) for ln in path.read_text().splitlines()]
    (tmp_path / "w_only.csv").write_text("\n".join(keep) + "\n")
    imported = modes_from_file(tmp_path / "w_only.csv")
    x, y = _deck_points(native, 2000)
    ref, got = native.mode_shapes(x, y), imported.mode_shapes(x, y)
    err = np.abs(got - ref).max(axis=0) / np.abs(ref).max(axis=0)
    # measured 0.19 / 0.67 / 2.0 % of the peak for the bending, torsion and first transverse mode (the
    # square deck's file: 0.1 / 0.4 / 1.4 %); taking the spline's slope as ∂w/∂y would give 4.8 % for mode 1
    assert err[0] < 0.005 and np.all(err[:3] < 0.025), err


@pytest.mark.parametrize("value", ["95", "nan", "10, 20"])
def test_bad_skew_header_is_named(tmp_path, value):
    path = write_modes(BRIDGE_PRESETS["paper-bridge-1"].build(n_modes=3), tmp_path / "m.csv")
    path.write_text(path.read_text().replace("# default_girder", f"# skew = {value}\n# default_girder"))
    with pytest.raises(ModeFileError, match=r"header 'skew' must be one angle in degrees, -90 < skew < 90"):
        modes_from_file(path)


def test_skew_without_an_exact_angle_gets_its_tan(tmp_path, skewed):
    """tan θ = 0.7 has no angle in degrees whose tan(radians(θ)) is 0.7 to the last bit: the file
    carries it as skew_tan too and reads back exactly; a skew_tan that is not tan(skew) is refused."""
    import dataclasses

    m = skewed.nodal_modes
    bridge = modes_from_file(write_modes(skewed, tmp_path / "s.csv"))
    bridge = dataclasses.replace(bridge, modes=dataclasses.replace(m, skew_tan=0.7))
    path = write_modes(bridge, tmp_path / "t.csv")
    text = path.read_text()
    assert "# skew_tan = 0.7\n" in text and f"# skew = {float(np.degrees(np.arctan(0.7)))!r}"[:16] in text  # 34.99202…°
    again = modes_from_file(path)
    assert again.skew_tan == 0.7
    x, y = _deck_points(skewed)
    assert np.array_equal(again.mode_shapes(x, y), bridge.mode_shapes(x, y))
    path.write_text(text.replace("# skew_tan = 0.7", "# skew_tan = 0.71"))
    with pytest.raises(ModeFileError, match=r"header 'skew_tan' = '0.71' must be tan\(skew\)"):
        modes_from_file(path)
