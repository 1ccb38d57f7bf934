"""Two results that looked like design values without a word (a new user's findings):

* An HS20-44 on an ISO class-F road over the paper's 3D Bridge 2 (examples/paper/bridge2_hs20_girder4.toml
  with ``class = "F"``) reads IM = 2.06 and |a| = 21.6 m/s²: its front axle is off the road for 0.55 s
  of its 16.76 m / 20.83 m/s = 0.805 s on the deck (68 %).  The IM now carries "!" and a warning that
  the wheels' leaving and landing dominate it (vbikit.analysis.checks.airborne_flags, flagged above
  AIRBORNE_FRACTION = 5 % of a wheel's time on the bridge); the road warning names the random road,
  not a profile file's unit.
* The Yang–Yau sprung mass (examples/verification/yang_yau_sprung_mass.toml, 10 modes) reads a
  strain IM of −0.0003 beside a moment IM of −0.054: its static strain from the modes' curvatures is
  20.32 µε against the exact c·P·L/(4·EI) = 0.5 · 56 407.5 N · 25 m / (4 · 8.323e9 N m²) = 21.18 µε
  (closed form of the simply supported beam, computed below), −4.0 %; with 50 modes 21.01 µε (−0.8 %).
  The strain IM now carries "!" and a warning above STRAIN_MODE_TOLERANCE = 1 %.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.analysis.checks import AIRBORNE_FRACTION, STRAIN_MODE_TOLERANCE
from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


def _run(text: str, tmp_path: Path):
    path, summary = tmp_path / "s.toml", tmp_path / "s.json"
    path.write_text(text)
    res = runner.invoke(app, ["run", str(path), "--summary", str(summary)])
    assert res.exit_code == 0, res.output
    return res, json.loads(summary.read_text())


def _im_line(stdout: str) -> str:
    return next(t for t in stdout.splitlines() if t.startswith("  IMPACT FACTOR"))


def test_wheels_airborne_on_a_class_f_road_flag_the_impact_factor(tmp_path):
    text = (ROOT / "examples" / "paper" / "bridge2_hs20_girder4.toml").read_text()
    assert 'class = "average"' in text
    res, s = _run(text.replace('class = "average"', 'class = "F"'), tmp_path)
    # each wheel's time off the road on the bridge, from the per-wheel contact warnings
    on_bridge = {m[0]: float(m[1]) for m in re.findall(r"wheel (\S+) lost contact with the road on the bridge: .*?"
                                                      r"for ([0-9.]+) s on the bridge", "\n".join(s["warnings"]))}
    time_on_deck = 16.76 / (75 / 3.6)  # span / speed: 0.805 s
    assert len(on_bridge) == 6 and max(on_bridge.values()) / time_on_deck == pytest.approx(0.68, abs=0.01)
    (flag,) = [f for f in s["flags"] if f["code"] == "airborne_wheels"]
    flagged = [flag["message"]]
    n = sum(t / time_on_deck > AIRBORNE_FRACTION for t in on_bridge.values())
    assert f"{n} wheels left the road" in flagged[0] and "68%" in flagged[0]
    assert "not design values" in flagged[0] and "point-contact impacts" in flagged[0]
    # the same finding as data: the longest-airborne wheel's share of its time on the deck, the threshold
    longest = max(on_bridge, key=on_bridge.get)
    assert flag["output"] == "impact_factor" and flag["wheel"] == longest
    assert flag["value"] == pytest.approx(on_bridge[longest] / time_on_deck, abs=0.01)
    assert flag["threshold"] == AIRBORNE_FRACTION
    assert s["warnings"] == [f["message"] for f in s["flags"]]  # one truth: the warnings are the flags' messages
    line = _im_line(res.stdout)
    assert f"IM = {s['impact_factor']:.4f}!" in line and s["impact_factor"] > 2
    assert "! unreliable: wheels left the road" in res.stdout
    assert f"(IM = {s['governing_girder_impact_factor']:.4f}!)" in res.stdout
    road_flag = next(f for f in s["flags"] if f["code"] == "road_elevation")
    road = road_flag["message"]
    assert road_flag["value"] == pytest.approx(0.292, abs=5e-4) and road_flag["threshold"] == 0.1
    assert road.startswith("road: the random class-F road (seed 1) reaches 0.292 m")
    assert "profile's unit" not in road and "defect" not in road and "road class" in road


def test_class_c_example_is_not_flagged(tmp_path):
    """The same example on its own class-C road: no wheel leaves the road, no mark on the IM, and
    its strain (modal 76.21 µε against the grid's full-stiffness static 76.75 µε: −0.7 %) is converged."""
    res, s = _run((ROOT / "examples" / "paper" / "bridge2_hs20_girder4.toml").read_text(), tmp_path)
    assert "!" not in _im_line(res.stdout)
    assert not {"airborne_wheels", "strain_not_converged", "road_elevation"} & {f["code"] for f in s["flags"]}


def test_strain_not_converged_in_ten_modes_is_flagged(tmp_path):
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    exact = 0.5 * 5750.0 * 9.81 * 25.0 / (4 * 8.323e9)  # c P L / (4 EI), midspan of the simply supported beam
    assert exact * 1e6 == pytest.approx(21.18, abs=0.005)
    res, s = _run(text, tmp_path)
    error = s["max_static_strain"] / exact - 1
    assert error == pytest.approx(-0.040, abs=0.001) and abs(error) > STRAIN_MODE_TOLERANCE
    (flag,) = [f for f in s["flags"] if f["code"] == "strain_not_converged"]
    flagged = [flag["message"]]
    assert flag["output"] == "strain_impact_factor" and flag["point"] == s["points"][0]["name"]
    assert flag["value"] == pytest.approx(error, abs=5e-4) and flag["threshold"] == STRAIN_MODE_TOLERANCE
    assert f"{s['max_static_strain'] * 1e6:.4g} µε, is {error:+.1%} off the exact {exact * 1e6:.4g} µε" in flagged[0]
    assert "more modes" in flagged[0]
    line = _im_line(res.stdout)
    assert f"IM = {s['impact_factor']:.4f}  " in line and f"strain IM = {s['strain_impact_factor']:.4f}!" in line
    assert "! unreliable strain and strain IM" in res.stdout
    strain_line = next(x for x in res.stdout.splitlines() if x.strip().startswith("max strain"))
    assert strain_line.count("µε!") == 2  # the strain peaks themselves are the modes' too

    res50, s50 = _run(text.replace("n_modes = 10", "n_modes = 50"), tmp_path)
    assert s50["max_static_strain"] / exact - 1 == pytest.approx(-0.008, abs=0.001)  # within 1 %: not flagged
    assert not any(f["code"] == "strain_not_converged" for f in s50["flags"])
    assert "!" not in _im_line(res50.stdout)
    assert "µε!" not in res50.stdout


def test_deck_strain_influence_is_the_full_stiffness_static_strain():
    """A girder deck's exact static strain (``deck_strain_influence``: v = K⁻¹g, I = vᵀF) against two
    independent routes on a small grid (3 girders, 6 elements, 57 free DOFs): the sparse static
    solution K u = F of the force itself (``static_solution``) read by the modes' strain rule, and the
    spectral identity K⁻¹ = Σ φᵢφᵢᵀ/ωᵢ² with every one of the 57 modes — exact for loads on the grid's
    lines (the modes are loaded through their interpolated shapes, the full stiffness through the
    consistent load: off the lines both within 0.2 %)."""
    import numpy as np

    from vbikit.bridge.girder_deck import SlabOnGirderBridge
    from vbikit.bridge.nodal import girder_line_strain

    deck = SlabOnGirderBridge(span=12.0, n_girders=3, n_elements=6, n_modes=57, use_cache=False)
    _, _, free = deck.assemble()
    assert deck.omega.size == free.size == 57  # every mode of the grid
    P = 1e5
    for x, y in ((6.0, 0.0), (5.0, 0.5), (7.3, -2.13)):
        influence = deck.strain_influence(x, y)
        for x0, y0, on_line in ((4.0, 0.0, True), (4.1, 2.13, True), (9.7, -2.13, True), (4.1, 0.9, False)):
            exact = float(influence.direct(np.array([x0]), np.array([y0]))[0]) * P
            solved = float(girder_line_strain(deck.static_solution(x0, y0, P), deck.line_properties["c"], x, y)[0, 0])
            assert exact == pytest.approx(solved, rel=1e-9)
            spectral = P * float(np.sum(deck.mode_shapes([x0], [y0])[0] * deck.strain_shapes([x], [y])[0] / deck.omega**2))
            assert spectral == pytest.approx(exact, rel=1e-9 if on_line else 2e-3)


def test_girder_decks_are_checked_against_their_full_stiffness_strain(tmp_path):
    """A girder deck's reference is the strain of the grid's full-stiffness static solution, not c/EI
    times the girder moment (which the modes' element curvature does not converge to: 75.92 µε on
    Bridge 2).  A 100 kN force on Bridge 2's Girder 4 line (smooth road, 20 modes): the reference
    equals the largest static strain of a brute-force walk of the force along its line (a sparse
    static solve every 2 cm), and the flag's value is the modes' error against it, −22.6 % (the force
    runs over the point the strain is read at, where the curvature's kink makes the modes' sum
    converge slowest; the HS20-44's wheels beside the line read −1.2 %); the three-span
    grillage example (20 modes, −7.4 %) is flagged with the deck's advice, the paper example (class C,
    multipoint tires, 20 modes, −0.7 %) is not (``test_class_c_example_is_not_flagged``)."""
    import numpy as np

    from scipy.sparse.linalg import splu

    import vbikit
    from vbikit.analysis.response import exact_static_strain_peak
    from vbikit.bridge.nodal import girder_line_strain

    path = tmp_path / "d.toml"
    path.write_text('[bridge]\nmodel = "paper-bridge-2"\nn_modes = 20\n[vehicle]\nmodel = "moving-force"\n'
                    '[road]\nclass = "none"\n[crossing]\nspeed_kmh = 60\nlateral_offset = 2.13\n[response]\ngirder = 4\n')
    report = vbikit.run(str(path))
    deck, (x, y) = report.result.crossing.bridge, (report.response.x, report.response.y)
    assert (x, y) == (pytest.approx(8.38), pytest.approx(2.13))
    K, _, free = deck.assemble()
    lu = splu(K[free][:, free].tocsc())
    u = np.zeros((K.shape[0], 1))
    walk = []
    for x0 in np.arange(0.0, 16.77, 0.02):  # z up: the force is −100 kN
        u[free, 0] = lu.solve(deck.load_vector(x0, y, -1e5)[free])
        walk.append(float(girder_line_strain(deck.dof_map.nodal(u), deck.line_properties["c"], x, y)[0, 0]))
    reference = exact_static_strain_peak(report.result, report.response)
    assert reference == pytest.approx(max(walk), rel=2e-3)  # the run's time samples step past the kink
    error = report.summary["max_static_strain"] / max(walk) - 1
    assert error == pytest.approx(-0.226, abs=0.005)  # the force on the strain's own line: the curvature's kink there
    (flag,) = [f for f in report.summary["flags"] if f["code"] == "strain_not_converged"]
    assert flag["value"] == pytest.approx(error, abs=2e-3)

    grillage = vbikit.run(str(ROOT / "examples" / "bridges" / "three_span_grillage_hs20.toml"))
    (flag,) = [f for f in grillage.summary["flags"] if f["code"] == "strain_not_converged"]
    assert flag["value"] == pytest.approx(-0.074, abs=0.002)
    assert "full-stiffness static solution" in flag["message"] and "girder deck" in flag["message"]
    assert "use more modes" not in flag["message"]  # on a grid more modes can move it further off


def test_road_warning_advice_follows_the_road_origin(tmp_path):
    """The road's origin is data (RoadProfile.origin, set where the profile is made), never read from
    its label: random, measured, with defects, and a profile from the Python API without an origin,
    each gets advice that fits it; a label that looks like a scenario's says nothing by itself."""
    import numpy as np

    from vbikit.analysis.checks import road_advice, road_origin
    from vbikit.road import Defect, RoadOrigin, RoadProfile, random_profile, read_profile_csv, with_defects

    def profile(origin=None, label=""):
        return RoadProfile(np.array([0.0, 1.0]), np.zeros(2), label, origin=origin)

    random_f = profile(RoadOrigin("random", "F", 1))
    assert road_origin(random_f) == "random class-F road (seed 1)"
    assert "road class" in road_advice(random_f) and "unit" not in road_advice(random_f)
    measured = profile(RoadOrigin("measured", file="mm.csv", defects=("pothole",)))
    assert road_origin(measured) == "measured profile (mm.csv, with defects)"
    assert "file's unit" in road_advice(measured) and "defect sizes" in road_advice(measured)
    assert "road class" not in road_advice(measured)
    # the label is a name, not data: a measured profile labelled like a random road stays measured
    assert road_origin(profile(RoadOrigin("measured", file="f.csv"), "class F, seed 1")) == "measured profile (f.csv)"
    unknown = profile(label="class F, seed 1")
    assert road_origin(unknown) == "road (class F, seed 1)"
    assert road_advice(unknown) == road_advice(profile()) == "check the profile's unit (elevations are in metres)"
    # where profiles are made: a random profile, a file, defects added, a right wheel line
    from vbikit.road import RoadPSD, correlated_profile

    left = random_profile(RoadPSD.iso("C"), 7, length=200.0, window=(-5.0, 30.0))
    assert left.origin == RoadOrigin("random", seed=7, shortest_wavelength=0.25, roughness=256e-6)  # ISO 8608 C
    bumped = with_defects(left, [Defect.of_kind("bump", 3.0)])
    assert bumped.origin.defects == ("bump",) and road_origin(bumped) == "random road (seed 7, with defects)"
    right = correlated_profile(left, RoadPSD.iso("C"), 7, 0.5, length=200.0, window=(-5.0, 30.0))
    assert right.origin == left.origin
    csv = tmp_path / "mm.csv"
    csv.write_text("x,elevation\n0,0\n1,0.001\n")
    assert read_profile_csv(csv).origin == RoadOrigin("measured", file="mm.csv")


def test_the_report_marks_follow_the_flag_codes_not_the_words(tmp_path, capsys):
    """The text report's "!" and notes come from the summary's flags (codes), not from how a warning is
    worded: the Yang–Yau run (strain flagged) with its strain message reworded keeps its mark; with an
    airborne-wheels flag added the IM is marked; a warning that merely reads like the airborne one, without
    its flag, marks nothing."""
    from types import SimpleNamespace

    from vbikit.cli.render import print_summary

    _, s = _run((ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text(), tmp_path)
    assert [f["code"] for f in s["flags"]] == ["strain_not_converged"]

    def report(summary):
        print_summary(SimpleNamespace(name="", summary=summary))
        return _im_line(capsys.readouterr().out)

    reworded = s | {"flags": [s["flags"][0] | {"message": "reworded"}], "warnings": ["reworded"]}
    assert report(reworded).endswith("!)") and "IM = " in report(reworded)
    airborne = {"code": "airborne_wheels", "message": "any words", "output": "impact_factor", "subject": None,
                "girder": None, "point": None, "wheel": "F", "value": 0.5, "threshold": AIRBORNE_FRACTION}
    line = report(s | {"flags": [airborne]})
    assert f"IM = {s['impact_factor']:.4f}!" in line
    words_only = s | {"flags": [], "warnings": ["impact factors dominated by airborne wheels: …",
                                                "strain not converged in the modes: …"]}
    assert "!" not in report(words_only)


def test_every_flag_has_a_documented_code():
    """A flag's code is one of FLAG_CODES (a typo fails at once), and docs/results.md lists every code."""
    from vbikit.analysis.checks import FLAG_CODES, Flag

    with pytest.raises(ValueError, match="airborne_wheel"):
        Flag("airborne_wheel", "typo")
    text = (ROOT / "docs" / "results.md").read_text()
    assert all(f"| `{code}` |" in text for code in FLAG_CODES)


def _skew_result(airborne: dict[str, tuple[float, float]]):
    """The parts of a CrossingResult the contact checks read, on the shipped 20° skew example
    (examples/bridges/skew_grillage_hs20.toml: span 16.76 m, deck x range −1.77 … 18.53 m, the truck at
    y = 1.4 m): its real crossing, the front axle at 1 m/s from x = −5 m to 40 m (dt = 0.01 s) and each
    wheel of ``airborne`` off the road while its centre is within the given x range [m]."""
    from types import SimpleNamespace

    import numpy as np

    from vbikit.scenario import build, load_scenario

    crossing = build(load_scenario(ROOT / "examples" / "bridges" / "skew_grillage_hs20.toml")).crossing
    x_front = np.arange(-5.0, 40.0, 0.01)
    wheels = crossing.vehicle.wheels
    x = x_front[:, None] - np.array([w.offset for w in wheels])[None, :]
    forces = np.full(x.shape, 5e4)
    for w, wheel in enumerate(wheels):
        if wheel.name in airborne:
            lo, hi = airborne[wheel.name]
            forces[(x[:, w] >= lo) & (x[:, w] < hi), w] = 0.0
    return SimpleNamespace(crossing=crossing, wheel_forces=forces, dt=0.01, time=np.arange(x_front.size) * 0.01,
                           wheel_positions=lambda: x.copy())


def test_airborne_time_on_a_skew_deck_is_per_wheel_track():
    """A wheel's time on a skew deck is its own track's stretch, span long between the oblique support
    lines at its y (0 ≤ x − y·tan θ ≤ span, bridge.span_coordinate), not the deck's whole x range: the
    left front wheel (y = 2.5 m) is on the deck for x = 0.910 … 17.670 m (16.76 m), not −1.77 … 18.53 m
    (20.31 m).  Airborne for 0.90 m of it that is 5.4 % (flagged above 5 %); against the whole range it
    read 4.4 % and was not flagged."""
    import math

    import numpy as np

    from vbikit.analysis.checks import airborne_wheels, wheel_track_ends

    result = _skew_result({"axle1_left": (5.0, 5.9)})
    bridge = result.crossing.bridge
    ends = wheel_track_ends(result)
    y = result.crossing.point_kinematics()[2][result.crossing.contact.wheel == 0][0]
    assert y == pytest.approx(2.5) and bridge.skew == 20.0
    assert ends[0] == pytest.approx([y * math.tan(math.radians(20.0)), y * math.tan(math.radians(20.0)) + 16.76])
    assert np.allclose(ends[:, 1] - ends[:, 0], bridge.span)
    assert bridge.deck_extent[1] - bridge.deck_extent[0] == pytest.approx(20.31, abs=0.01)
    (name, t, share), = airborne_wheels(result)
    assert name == "axle1_left" and t == pytest.approx(0.90, abs=0.011)
    assert share == pytest.approx(0.90 / 16.76, abs=0.002) and share > AIRBORNE_FRACTION > 0.90 / 20.31


def test_contact_lost_past_a_skew_track_is_after_the_bridge():
    """The right front wheel (y = 0.3 m) leaves the skew deck at x = 16.869 m; off the road at 17.5 … 18 m
    it is past its own track, though within the deck's x range (to 18.53 m): "only after the bridge"."""
    from vbikit.analysis.checks import contact_flags

    (flag,) = contact_flags(_skew_result({"axle1_right": (17.5, 18.0)}))
    assert flag.code == "contact_loss" and flag.wheel == "axle1_right" and flag.value == 0.0
    assert "only after the bridge (its track on the deck: x from 0.109 to 16.869 m)" in flag.message


def _three_moment_influence(s: float, a: float, spans=(20.0, 25.0, 20.0)) -> float:
    """Sagging moment [m] at section s of the first span of a three-span continuous beam on rigid pinned
    supports, under a unit load at a: Clapeyron's three-moment equation (e.g. S. Timoshenko, D. H. Young,
    *Theory of Structures*, 1965, §8.2), M_{j−1} L_j + 2 M_j (L_j + L_{j+1}) + M_{j+1} L_{j+1} =
    −Σ P u (L² − u²) / L over the loaded span next to support j, u the load's distance from that span's
    far support; then M(s) = the simply supported span's moment + M_B s / L_1 (the two equations for
    M_B, M_C solved by Cramer's rule)."""
    l1, l2, l3 = spans
    xb, xc, xd = l1, l1 + l2, l1 + l2 + l3
    rb = rc = 0.0
    if 0.0 <= a <= xb:
        rb = a * (l1**2 - a**2) / l1
    elif xb < a <= xc:
        rb = (xc - a) * (l2**2 - (xc - a) ** 2) / l2
        rc = (a - xb) * (l2**2 - (a - xb) ** 2) / l2
    elif xc < a <= xd:
        rc = (xd - a) * (l3**2 - (xd - a) ** 2) / l3
    a11, a12, a22 = 2 * (l1 + l2), l2, 2 * (l2 + l3)  # [[a11, a12], [a12, a22]] [M_B, M_C] = [−rb, −rc]
    mb = (-rb * a22 + rc * a12) / (a11 * a22 - a12 * a12)
    simple = (s * (l1 - a) / l1 if s <= a else a * (l1 - s) / l1) if 0.0 <= a <= l1 else 0.0
    return simple + mb * s / l1


def test_continuous_beams_are_checked_for_strain_convergence(tmp_path):
    """A continuous beam's exact static strain is c/EI times its full-stiffness static moment
    (ContinuousBeam.strain_per_moment; before, the check ran on simply supported beams only: no reference,
    no flag).  The three-span example (20 + 25 + 20 m, EI = 1.286e10 N m², c = 0.78 m) on a smooth road
    with point tires at x = 10 m: the HS20-44's static moment peak there by the three-moment equation is
    915.6 kN m, c/EI times it 55.54 µε; the run's reference reads within 0.2 % of it (its time samples
    step past the peak's kink).  16 modes read −1.5 % (flagged); 12 and 64 modes within 1 %."""
    import numpy as np

    from vbikit.analysis.response import exact_static_strain_peak

    text = (ROOT / "examples" / "bridges" / "three_span_continuous_hs20.toml").read_text()
    assert 'class = "C"' in text and 'model = "multipoint"\nn_points = 6' in text and "n_modes = 12" in text
    text = text.replace('class = "C"', 'class = "none"').replace('model = "multipoint"\nn_points = 6', 'model = "point"')
    import vbikit

    path = tmp_path / "c.toml"
    path.write_text(text.replace("n_modes = 12", "n_modes = 16"))
    report = vbikit.run(str(path))
    crossing = report.result.crossing
    assert report.response.x == 10.0
    loads = crossing.vehicle.static_wheel_loads()
    offsets = np.array([w.offset for w in crossing.vehicle.wheels])
    fronts = np.arange(0.0, 90.0, 0.002)
    moment = [sum(p * _three_moment_influence(10.0, f - o) for p, o in zip(loads, offsets)) for f in fronts]
    exact = 0.78 / 1.286e10 * max(moment)
    assert max(moment) == pytest.approx(915.6e3, rel=1e-3)
    reference = exact_static_strain_peak(report.result, report.response)
    assert reference == pytest.approx(exact, rel=2e-3)
    (flag,) = [f for f in report.summary["flags"] if f["code"] == "strain_not_converged"]
    assert flag["value"] == pytest.approx(report.summary["max_static_strain"] / reference - 1, rel=1e-9)
    assert flag["value"] == pytest.approx(-0.015, abs=0.001)

    for n in (12, 64):  # not monotonic: 12 modes happen to be within 1 %, 16 not, 64 again
        path.write_text(text.replace("n_modes = 12", f"n_modes = {n}"))
        converged = vbikit.run(str(path))
        assert abs(converged.summary["max_static_strain"] / reference - 1) < STRAIN_MODE_TOLERANCE
        assert not any(f["code"] == "strain_not_converged" for f in converged.summary["flags"])


def test_a_continuous_beam_section_where_ei_changes_has_no_strain_reference():
    """c/EI is one number inside an element; at a support between spans of different EI there is none."""
    from vbikit.bridge import ContinuousBeam

    beam = ContinuousBeam((20.0, 25.0), (1e10, 2e10), 7500.0, neutral_axis_depth=0.8, n_modes=4)
    assert beam.strain_per_moment(10.0) == pytest.approx(0.8 / 1e10)
    assert beam.strain_per_moment(30.0) == pytest.approx(0.8 / 2e10)
    assert beam.strain_per_moment(20.0) is None


def test_a_flag_record_is_strict_json():
    """A flag's record holds plain numbers (numpy floats as float) and null for a value that is not
    finite, so a summary's flags never add a non-finite warning of their own."""
    import numpy as np

    from vbikit.analysis.checks import Flag, flag_fields

    fields = flag_fields([Flag("effect_step", "m", output="moment", value=np.float64(1e-3), threshold=float("inf")),
                          Flag("effect_step", "m", output="moment")])
    assert fields["warnings"] == ["m"]  # each message once
    (record,) = fields["flags"]
    assert record["value"] == 1e-3 and type(record["value"]) is float and record["threshold"] is None
    json.dumps(record, allow_nan=False)


def test_a_girder_decks_strain_advice_says_which_im_to_sign_with():
    """On the three-span grillage example the strain is flagged (−7.4 %) and its two substitutes differ
    a lot: Girder 4's deflection IM 0.116 and its moment IM at the same section 0.187 (docs/bridges.md).
    On main the warning offered "the deflection's or the moment's IM" as equals; it now says to sign
    with the moment IM (a moment's IM is the one applied in moment design, a deflection's only in
    serviceability checks), and so does the report's note.  A beam keeps "use more modes"."""
    from vbikit.analysis.checks import strain_convergence_flags

    res = runner.invoke(app, ["run", str(ROOT / "examples" / "bridges" / "three_span_grillage_hs20.toml")])
    assert res.exit_code == 0, res.output
    warning = next(x for x in res.output.splitlines() if x.startswith("warning: strain not converged"))
    assert "sign with the girder's moment IM at this section (response.moment), not the deflection IM" in warning
    assert "moment (strength) design, a deflection's only in serviceability checks" in warning
    assert "deflection's or the moment's IM" not in warning
    assert "on a girder deck sign with the moment IM, not the deflection IM" in res.output
    # the moment IM the advice points to is reported at the strain's own section (girder 4, x = 8.38 m)
    assert any(x.strip().startswith("moment   x = 8.38 m, girder 4") for x in res.output.splitlines())
    # … and printed under the advice, the number to sign with (the moment table's own row: 0.1868, docs/bridges.md)
    row = next(x for x in res.output.splitlines() if x.strip().startswith("moment   x = 8.38 m, girder 4"))
    assert f"the moment IM at x = 8.38 m, girder 4: {row.split('IM')[1].split()[0]}" in res.output
    # a deck of three spans gives its whole length as such, not as "span 53.52 m"
    assert "(length 53.52 m," in res.output and "(span 53.52 m" not in res.output
    (beam,) = strain_convergence_flags(0.9e-4, 1e-4, 10, "x = 5.000 m")
    assert "use more modes (bridge.n_modes)" in beam.message and "sign with" not in beam.message
