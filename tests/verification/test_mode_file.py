"""Modes imported from a file (src/vbikit/bridge/modefile.py): a file written from our own
slab-on-girder model and read back must reproduce the native crossing exactly (issue 4), and
a file without slopes (as most FE programs export: nodal w only) must approximate it closely."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import BRIDGE_PRESETS
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
