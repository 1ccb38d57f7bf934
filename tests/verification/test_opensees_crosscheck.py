"""Independent cross-check of the slab-on-girder deck against a grillage built in OpenSeesPy.

OpenSees (McKenna et al., opensees.berkeley.edu) is the field's standard open FE program.  The
grillage here is built directly in openseespy (ospgrillage was not used: its member masses came
out 1000× too large in our trial, A·ρ·1e3, and slab strips given a unit width had their stiffness scaled but not their mass):
``elasticBeamColumn`` members on the same node grid as vbikit's Bridge 2 model — girder lines
along x, slab strips (and diaphragms) along y — with in-plane DOFs (ux, uy, rz) fixed and the
bearings fixed in uz.  Masses follow docs/bridges.md: the deck slab as a distributed mass on the
transverse members (OpenSees' consistent ``-cMass`` matrix), the girders' own mass and rotary
inertia lumped at their nodes.  The overhang is set to zero: OpenSees' diagonal nodal masses
cannot carry the mass–twist coupling of vbikit's rigid overhang strips.  Section properties are
worked out again in this file from the documented formulas, not taken from vbikit.  Expected
differences: the twist inertia m J / A that OpenSees' ``-cMass`` gives the slab strips (vbikit's
strips have none; 0.12 % on mode 5) and lumped vs consistent girder mass (≤ 3e-5, measured in
``test_opensees_skew.py``, which removes the strips' twist inertia); tolerance 0.5 %.
Statics use the same nodal loads, so the static girder deflections must agree to solver
round-off (1e-6).

Runs when the optional ``opensees`` extra is installed (``pip install -e ".[opensees]"``).
"""
from __future__ import annotations

import ctypes
import importlib.util
import os

import numpy as np
import pytest

from vbikit.bridge import paper_deck

IN = 0.0254


@pytest.fixture(scope="module")
def ops():
    spec = importlib.util.find_spec("openseespylinux")
    if spec is None or not spec.submodule_search_locations:
        pytest.skip("openseespy is not installed (optional extra 'opensees')")
    lib = os.path.join(spec.submodule_search_locations[0], "lib", "libblas.so.3")
    if os.path.exists(lib):  # the wheel's LAPACK needs libblas.so.3 (ecosystem notes)
        ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)
    ops = pytest.importorskip("openseespy.opensees")
    return ops


def composite_line(b, t=0.20, Eg=36e9, Ed=33e9, nu=0.2):
    """Girder line of Bridge 2 with deck width b [m] (AASHTO Type II, full composite action, deck
    mid-plane t/2 above the girder, n = E_deck / E_girder; GJ = G_g J_g + G_d t³ b / 6 with the
    Saint-Venant J_g estimate — the documented formulas): (area [m²], I [m⁴] about the composite
    axis, GJ [N m²])."""
    A, yb, h, I = 369 * IN**2, 15.83 * IN, 36 * IN, 50979 * IN**4  # AASHTO Type II (PCI)
    Gg, Gd = Eg / (2 * (1 + nu)), Ed / (2 * (1 + nu))
    Jg = A**4 / (4 * np.pi**2 * I)
    n = Ed / Eg
    Ad, yd = n * b * t, h + t / 2
    yna = (A * yb + Ad * yd) / (A + Ad)
    Ic = I + A * (yna - yb) ** 2 + n * b * t**3 / 12 + Ad * (yd - yna) ** 2
    return A + Ad, Ic, Gg * Jg + Gd * t**3 / 6 * b


def build_grillage(ops, bridge, log_path):
    """Bridge-2 grillage in OpenSees; returns node tags [line][station]."""
    ops.wipe()
    ops.logFile(str(log_path), "-noEcho")
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    L, n_el, s, t = bridge.span, bridge.element_count, 2.13, 0.20
    Eg, Ed, nu, rho = 36e9, 33e9, 0.2, 2400.0
    Gg, Gd = Eg / (2 * (1 + nu)), Ed / (2 * (1 + nu))
    A, h, I = 369 * IN**2, 36 * IN, 50979 * IN**4  # AASHTO Type II (PCI); girder lines: composite_line
    xs = np.linspace(0, L, n_el + 1)
    ys = (np.arange(5) - 2) * s
    ov = bridge.overhang
    trib_y = np.array([s / 2 + ov, s, s, s, s / 2 + ov])
    tag = {}
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            tag[j, i] = 1000 * j + i + 1
            ops.node(tag[j, i], float(x), float(y), 0.0)
            ops.fix(tag[j, i], 1, 1, 0, 0, 0, 1)  # grillage: in-plane DOFs fixed
    for j in range(5):
        for i in (0, n_el):
            ops.fix(tag[j, i], 0, 0, 1, 0, 0, 0)  # bearings
    ops.geomTransf("Linear", 1, 0.0, 1.0, 0.0)  # members along x: local z = global y -> vertical bending uses Iz
    ops.geomTransf("Linear", 2, 1.0, 0.0, 0.0)  # members along y
    ele = 1
    hx = xs[1] - xs[0]
    mu = rho * t
    for j in range(5):
        area, Ic, GJ = composite_line(trib_y[j])
        for i in range(n_el):
            ops.element("elasticBeamColumn", ele, tag[j, i], tag[j, i + 1], area, Eg, Gg, GJ / Gg, 1.0, Ic, 1)
            ele += 1
        m_line = rho * A  # the deck's mass is on the transverse members
        J_line = rho * I
        for i in range(n_el + 1):
            lx = hx / 2 if i in (0, n_el) else hx
            ops.mass(tag[j, i], 0.0, 0.0, m_line * lx, J_line * lx, 0.0, 0.0)
    Dd = 0.75 * h
    bd = 0.25
    GJd = Gd * (1 - 0.63 * bd / Dd) / 3 * Dd * bd**3
    for i, x in enumerate(xs):
        lx = hx / 2 if i in (0, n_el) else hx
        n_d = 1 if (i in (0, n_el) or abs(x - L / 2) < 1e-9) else 0
        Iz = t**3 * lx / (12 * (1 - nu**2)) + n_d * bd * Dd**3 / 12
        J = t**3 / 6 * lx + n_d * GJd / Gd
        m = mu * lx + n_d * rho * bd * Dd
        for j in range(4):
            ops.element("elasticBeamColumn", ele, tag[j, i], tag[j + 1, i], t * lx, Ed, Gd, J, 1.0, Iz, 2, "-mass", m, "-cMass")
            ele += 1
    return tag, xs, ys


@pytest.fixture(scope="module")
def models(ops, tmp_path_factory):
    bridge = paper_deck(2, n_modes=8, overhang=0.0)
    tag, xs, ys = build_grillage(ops, bridge, tmp_path_factory.mktemp("ops") / "ops.log")
    return ops, bridge, tag, xs, ys


def test_first_five_frequencies_agree(models):
    ops, bridge, tag, xs, ys = models
    # shift-invert Lanczos: the same eigenpairs as the dense "-fullGenLapack" (frequencies to 2e-11,
    # 1 − MAC to 1e-15: test_opensees_skew.frequencies) in a fraction of its time
    lam = np.array(ops.eigen("-genBandArpack", 5))
    f_ops = np.sqrt(lam) / (2 * np.pi)
    f_vbi = bridge.frequencies_hz[:5]
    print("OpenSees", f_ops, "vbikit", f_vbi)
    assert f_vbi == pytest.approx(f_ops, rel=0.005)
    # mode shapes on the girder lines: modal assurance criterion
    for k in range(5):
        a = np.array([[ops.nodeEigenvector(tag[j, i], k + 1, 3) for i in range(xs.size)] for j in range(5)]).ravel()
        b = bridge.nodal_modes.w[:, :, k].ravel()
        mac = (a @ b) ** 2 / ((a @ a) * (b @ b))
        assert mac > 0.99


def static_truck(ops, tag, xs, axles):
    """Static OpenSees analysis under ``axles`` [(x [m], axle load [N])], each axle's load split
    over the wheel lines above Girders 3 and 4 at the nearest stations; returns the loads as
    (station index, girder line index, wheel load [N])."""
    pts = [(int(np.argmin(np.abs(xs - x))), j, P / 2) for x, P in axles for j in (2, 3)]
    static_nodal(ops, tag, [(j, i, P) for i, j, P in pts])
    return pts


def static_nodal(ops, tag, pts):
    """Linear static OpenSees analysis under downward nodal forces pts [(line j, station i, P [N])]
    (reactions computed)."""
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for j, i, P in pts:
        ops.load(tag[j, i], 0.0, 0.0, -P, 0.0, 0.0, 0.0)
    ops.system("UmfPack")
    ops.numberer("RCM")
    ops.constraints("Plain")
    ops.integrator("LoadControl", 1.0)
    ops.algorithm("Linear")
    ops.analysis("Static")
    assert ops.analyze(1) == 0
    ops.reactions()


def test_static_girder_deflections_under_a_truck_agree(models):
    ops, bridge, tag, xs, ys = models
    # HS20-44 axle loads 35.6 / 142.3 / 142.3 kN (AASHTO), axles 4.27 m apart, front axle near
    # 12.5 m; wheel lines over Girders 3 and 4 (y = 0, 2.13 m); loads at the nearest stations.
    axles = [(12.5, 35.6e3), (12.5 - 4.27, 142.3e3), (12.5 - 8.54, 142.3e3)]
    pts = static_truck(ops, tag, xs, axles)
    mid = xs.size // 2
    w_ops = np.array([ops.nodeDisp(tag[j, mid], 3) for j in range(5)])
    s = bridge.static_solution([xs[i] for i, _, _ in pts], [ys[j] for _, j, _ in pts], [-P for _, _, P in pts])
    w_vbi = s.w[:, mid, 0]
    assert w_vbi == pytest.approx(w_ops, rel=1e-6)
