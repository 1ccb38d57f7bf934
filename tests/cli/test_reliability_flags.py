"""Results that are not what they seem are said so in words (the JSON's warnings, stderr and a mark in
the text report), and a negative impact factor is explained, not left to look like an error.

* An impact factor on a small static reference: on the paper's 3D Bridge 2 under the HS20-44
  (examples/paper/bridge2_hs20_girder4.toml) Girder 1 carries a static deflection of 0.28 mm
  against 2.79 mm on Girder 4 and reads IM = 1.35; before, printed without a word.  The expected
  flags are recomputed here from the run's own static peaks (|R_st| < 20 % of the largest:
  vbikit.analysis.checks.SMALL_STATIC_FRACTION).
* A negative IM: the Yang–Yau sprung mass (examples/verification/yang_yau_sprung_mass.toml), whose
  mid-span moment's IM is −0.054: the report prints the one note (NEGATIVE_IM_NOTE); the 3D example,
  every IM positive, does not.
"""
from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from vbikit.analysis.checks import NEGATIVE_IM_NOTE, SMALL_STATIC_FRACTION, small_static
from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


def _run(path: Path, tmp_path: Path):
    summary = tmp_path / "s.json"
    res = runner.invoke(app, ["run", str(path), "--summary", str(summary)])
    assert res.exit_code == 0, res.output
    return res, json.loads(summary.read_text())


def test_small_static_rule_by_hand():
    """Girder statics of the 3D example [mm]: 0.283 / 2.795 = 10 % is flagged, 1.378 / 2.795 = 49 % is not;
    the sign does not matter (a girder lifting, as on the three-span deck), nor does an all-zero set."""
    assert small_static([-0.283, -1.378, -2.434, -2.795, -2.321]) == [True, False, False, False, False]
    assert small_static([0.179, -0.976, -2.069]) == [True, False, False]
    assert small_static([-1.0, -0.2001 / 1.0]) == [False, False] and small_static([-1.0, -0.1999]) == [False, True]
    assert small_static([0.0, 0.0]) == [False, False]


def test_lightly_loaded_girder_is_flagged_and_negative_note_absent(tmp_path):
    res, s = _run(ROOT / "examples" / "paper" / "bridge2_hs20_girder4.toml", tmp_path)
    static = [abs(v) for v in s["girder_max_static_displacement"]]
    expected = [v < SMALL_STATIC_FRACTION * max(static) for v in static]
    assert expected == [True, False, False, False, False]  # Girder 1 only (0.28 of 2.79 mm)
    flagged = [w for w in s["warnings"] if w.startswith("Girder ")]
    assert len(flagged) == 1 and flagged[0].startswith(f"Girder 1: IM = {s['girder_impact_factors'][0]:.3g}")
    assert "unreliable as a design value" in flagged[0] and "10%" in flagged[0]
    assert flagged[0] in res.stderr  # printed with the report
    im_line = next(t for t in res.stdout.splitlines() if t.startswith("  IM "))
    assert im_line.count("!") == 1 and f"{s['girder_impact_factors'][0]:7.4f}!" in im_line
    assert "! unreliable: static deflection under 20% of the largest" in res.stdout
    assert NEGATIVE_IM_NOTE not in res.stdout  # every IM of this run is positive
    assert min(s["girder_impact_factors"]) > 0


def test_negative_impact_factor_is_explained(tmp_path):
    res, s = _run(ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml", tmp_path)
    assert s["moment"]["impact_factor"] < 0  # −0.054: the dynamic moment peak below the static one
    assert f"IM {s['moment']['impact_factor']:7.4f}" in res.stdout
    assert res.stdout.count(NEGATIVE_IM_NOTE) == 1
    # a note, not a warning (its one warning is that the 10-mode strain is not converged:
    # tests/cli/test_airborne_and_strain_flags.py)
    assert not any("IM" in f["message"] for f in s["flags"] if f["code"] != "strain_not_converged")


def test_a_lightly_loaded_load_effect_is_flagged_against_its_own_kind(tmp_path):
    """The same rule for moments, shears and reactions, each kind against the largest static peak of its
    own kind: on the demo beam (16.76 m, HS20-44) the moment 0.5 m from the entry support carries 13 %
    of the mid-span moment (a simply supported beam's influence ordinate x(L − x)/L is 0.49 m there
    against 4.19 m at mid-span) and is flagged, naming the mid-span moment as the largest; the mid-span
    moment is not, nor the one shear (no other shear to compare with).  The expected flags are
    recomputed from the run's own static peaks."""
    from vbikit.scenario import demo_scenario_text

    path = tmp_path / "two_moments.toml"
    path.write_text(demo_scenario_text().replace("[response]", "[response]\nmoment = [0.5, 8.38]\nshear = [2.0]"))
    res, s = _run(path, tmp_path)
    sections = s["moment"]["sections"]
    assert [m["x"] for m in sections] == [0.5, 8.38]
    assert small_static([m["static_peak"] for m in sections]) == [True, False]
    flagged = [w for w in s["warnings"] if "rests on a static moment" in w]
    assert len(flagged) == 1 and flagged[0].startswith("moment at x = 0.5 m") and "x = 8.38 m" in flagged[0]
    assert not any("rests on a static shear" in w for w in s["warnings"])
    assert "rests on a static moment" in res.stderr


def test_girder_marks_agree_with_the_warnings(tmp_path):
    """The text report's '!' beside a girder's IM follows the same judgement as the warnings: against the
    largest static peak of the girders AND the response points.  Headline at x = 1.5 m (girders lightly
    loaded there), a second point at mid-span (2.79 mm): Girders 1 and 2 are warned of, and both must be
    marked (the marks compared the girders among themselves only and marked Girder 1 alone)."""
    path = tmp_path / "girder_vs_point.toml"
    path.write_text('name = "girder marks vs warning"\n[bridge]\nmodel = "paper-bridge-2"\nn_modes = 10\n'
                    '[vehicle]\nmodel = "hs20-44"\n[tire]\nmodel = "point"\n[road]\nclass = "none"\n'
                    '[crossing]\nspeed_kmh = 75\n[[response.points]]\nname = "near_support"\nx = 1.5\ngirder = 4\n'
                    '[[response.points]]\nname = "mid"\nx = 8.38\ngirder = 4\n')
    res, s = _run(path, tmp_path)
    statics = list(s["girder_max_static_displacement"]) + [p["max_static_displacement"] for p in s["points"]]
    expected = small_static(statics)[:len(s["girder_max_static_displacement"])]
    warned = [g for g in range(1, len(expected) + 1) if any(w.startswith(f"Girder {g}:") for w in s["warnings"])]
    assert warned == [g for g, f in enumerate(expected, start=1) if f] and len(warned) >= 2
    im_line = next(line for line in res.stdout.splitlines() if line.strip().startswith("IM ") and "!" in line)
    marks = [cell.endswith("!") for cell in im_line.split()[1:]]
    assert marks == expected


def test_bridge_without_a_figure_does_not_need_the_default_folder(tmp_path, monkeypatch):
    """`vbikit bridge --no-plot` (and `--plot FILE`) write nothing into vbikit-out, so a file of that name
    in the working folder does not refuse them; the default figure still needs the folder."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "vbikit-out").write_text("not a folder")
    assert runner.invoke(app, ["bridge", "paper-bridge-1-beam", "--no-plot"]).exit_code == 0
    assert runner.invoke(app, ["bridge", "paper-bridge-1-beam", "--plot", "modes.png"]).exit_code == 0
    res = runner.invoke(app, ["bridge", "paper-bridge-1-beam"])
    assert res.exit_code == 2 and "vbikit-out" in res.stderr
