"""`vbikit compare-tires`, disk / rigid-disk scenarios with [[road.defects]], and bad defect keys."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

# small and fast: 10 m beam, 3 modes, sprung mass (Yang & Yau's vehicle, 56 kN: disk compression
# d_s = 1.5 F/k = 53 mm < the disk's 100 mm arc), 20 m/s, 2 m run-up
SMALL = """
name = "small tire comparison"
[bridge]
model = "beam"
span = 10.0
EI = 1e10
mass_per_length = 5000.0
n_modes = 3
[vehicle]
model = "sprung-mass"
damping = 2000.0
[crossing]
speed = 20.0
approach = 2.0
"""

DEFECTS = """
[road]
class = "A"
seed = 2
length = 200.0
[[road.defects]]
kind = "depression"
position = 0.0
[[road.defects]]
kind = "bump"
position = 5.0
height = 0.02
"""

#: the JSON's keys: the tire models by the names a [tire] table and `vbikit field --tires` take (each row's
#: "label" is the text's, figure's and warnings' name of it)
MODELS = ("point", "multipoint", "disk", "rigid-disk")
LABELS = ("point", "multipoint (n = 6)", "disk", "rigid disk")


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "scenario.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("with_defects", [False, True])
def test_compare_tires_writes_figure_and_table(tmp_path, with_defects):
    path = write(tmp_path, SMALL + (DEFECTS if with_defects else ""))
    out = tmp_path / "out"
    res = runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(out), "--json"])
    assert res.exit_code == 0, res.output
    table = json.loads(res.stdout)
    assert tuple(table) == MODELS and tuple(row["label"] for row in table.values()) == LABELS
    assert [row["tire"]["model"] for row in table.values()] == list(MODELS)
    assert json.loads((out / "compare-tires.json").read_text()) == table
    assert (out / "compare-tires.png").stat().st_size > 10_000
    for label, row in table.items():
        for key in ("max_dynamic_displacement", "impact_factor", "max_dynamic_strain", "strain_impact_factor",
                    "max_abs_acceleration", "min_tire_force", "contact_lost", "seconds"):
            assert key in row, (label, key)
        assert row["max_dynamic_displacement"] < 0  # z up: the deck deflects downward
        assert row["min_tire_force"] >= 0.0  # loss of contact is on by default: no tire pulls
        # at least the static deflection P L³/(48 EI) = 56.4 kN × 10³ m³/(48e10 N m²) = 0.1175 mm
        # minus the 3-mode truncation (< 0.3 %): at α = v/(2 f1 L) = 20/(2 × 22.2 × 10) = 0.045 the
        # moving-force amplification is ≈ 1.04 > 1 (Frýba; model data §5)
        assert -row["max_dynamic_displacement"] > 0.997 * 5750 * 9.81 * 10.0**3 / (48 * 1e10)
        # scripts read units and flag codes as from vbikit run's JSON (CF spelling; the codes, never the words)
        assert row["units"]["max_abs_acceleration"] == "m s-2" and row["units"]["impact_factor"] == "1"
        assert row["units"]["min_tire_force"] == "N" and row["response_x"] == 5.0
        # how good each run is, as vbikit run states it: its step and its half-step check
        assert row["dt"] > 0 and row["units"]["dt"] == "s" and row["max_static_displacement"] < 0
        assert row["step_check"]["dt"] == pytest.approx(row["dt"] / 2) and row["step_check"]["largest_change"] >= 0
        assert [f["message"] for f in row["flags"]] == [w for w in row["warnings"] if w in {f["message"] for f in row["flags"]}]
    if not with_defects:
        # smooth road: the rigid disk acts through its centre point like the point tire
        assert table["rigid-disk"]["max_dynamic_displacement"] == pytest.approx(table["point"]["max_dynamic_displacement"],
                                                                                rel=1e-9)


def test_the_multipoint_tire_takes_the_scenario_s_n_points(tmp_path):
    """Without --n-points the multi-point tire is the scenario's own (a trial's file with n_points = 3 was compared
    with 6 points, silently); --n-points overrides it."""
    path = write(tmp_path, SMALL + '[tire]\nmodel = "multipoint"\nn_points = 3\n')
    table = json.loads(runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(tmp_path), "--json"]).stdout)
    assert table["multipoint"]["tire"]["n_points"] == 3 and table["multipoint"]["label"] == "multipoint (n = 3)"
    table = json.loads(runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(tmp_path), "--json",
                                           "--n-points", "5"]).stdout)
    assert table["multipoint"]["tire"]["n_points"] == 5 and table["multipoint"]["label"] == "multipoint (n = 5)"


def test_compare_tires_text_output(tmp_path):
    path = write(tmp_path, SMALL)
    res = runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(tmp_path), "--n-points", "4"])
    assert res.exit_code == 0, res.output
    assert "small tire comparison" in res.stdout
    for label in ("point", "multipoint (n = 4)", "disk", "rigid disk", "compare-tires.png"):
        assert label in res.stdout
    # each model's half-step check, as vbikit run gives it
    checks = [line for line in res.stdout.splitlines() if line.startswith("  step check, ")]
    assert [line.split(":")[0] for line in checks] == [f"  step check, {label}" for label in
                                                       ("point", "multipoint (n = 4)", "disk", "rigid disk")]
    assert all("at half the step (" in line for line in checks)


@pytest.mark.parametrize("model,points", [("disk", 61), ("rigid-disk", 61)])
def test_disk_scenarios_with_defects_run(tmp_path, model, points):
    text = SMALL + f'[tire]\nmodel = "{model}"\nradius = 0.5\ndisk_spacing = 0.01\n' + DEFECTS
    res = runner.invoke(app, ["run", str(write(tmp_path, text)), "--json"])
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    assert s["tire_model"] == model
    # |ξ| ≤ √(R² − (R − R/5)²) = 0.3 m at 0.01 m spacing: 61 points per wheel
    assert s["n_contact_points_per_wheel"] == points
    assert s["min_wheel_force"]["w1"] >= 0.0
    assert set(s["contact_loss"]) == {"w1"}
    lo, hi = s["contact_length_range"]["w1"]
    if model == "disk":
        # static patch 2√(2R d_s), d_s = 1.5 × 5750 × 9.81 / 1.595e6 = 53 mm → 0.46 m; it varies with load
        assert 0.0 <= lo < hi and hi > 0.4
    else:
        assert lo == hi == 0.0  # a rigid disk touches at one point


def test_loss_of_contact_key_is_accepted(tmp_path):
    text = SMALL + '[tire]\nmodel = "multipoint"\nloss_of_contact = false\n' + DEFECTS
    res = runner.invoke(app, ["run", str(write(tmp_path, text)), "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["tire_model"] == "multipoint"


@pytest.mark.parametrize(
    "defect,expect",
    [
        ('kind = "bump"\ndepth = 0.02', ["road.defects[1]", "depth", "height"]),
        ('kind = "crack"', ["road.defects[1].kind", "depression", "pothole"]),
        ('kind = "depression"\ndepth = -0.02', ["road.defects[1].depth", "expected a number in (0, "]),
        ('kind = "depression"\nheight = 0.02', ["road.defects[1]", "depth", "not height"]),
        ('kind = "bump"\nheight = -0.01', ["road.defects[1]", "height", "> 0"]),
        ('kind = "step"\nheight = 0.01\nramp = 0.0', ["road.defects[1].ramp", "expected a number in (0, "]),
        ('kind = "pothole"\nwidth = 0.3', ["road.defects[1].width", "unknown key"]),
    ],
)
def test_bad_defect_keys_exit_2_naming_the_key(tmp_path, defect, expect):
    text = SMALL + "[road]\n[[road.defects]]\n" + defect + "\n"
    for command in (["run", "--json"], ["compare-tires", "--out-dir", str(tmp_path / "out")]):
        res = runner.invoke(app, [command[0], str(write(tmp_path, text)), *command[1:]])
        assert res.exit_code == 2, res.output
        assert "Traceback" not in res.output
        msg = res.stderr
        assert msg.startswith("error:")
        for fragment in expect:
            assert fragment in msg, msg
    assert not (tmp_path / "out").exists()


def test_unknown_defect_key_lists_the_defect_keys(tmp_path):
    text = SMALL + '[road]\n[[road.defects]]\nkind = "pothole"\nwidth = 0.3\n'
    res = runner.invoke(app, ["run", str(write(tmp_path, text)), "--json"])
    assert res.exit_code == 2
    allowed = res.stderr.split("allowed keys:")[1]
    for key in ("kind", "position", "depth", "height", "length", "ramp", "shape"):
        assert key in allowed, res.stderr
    assert "seed" not in allowed  # not the keys of [road]


def test_a_warning_every_tire_model_shares_is_printed_once(tmp_path):
    """A random road's ``one_realisation`` warning is the same for the four tire models: printed once,
    without a tire prefix (a new user saw it four times, each prefixed by the tire name); a warning of
    one model only keeps its prefix (``shared_warnings``)."""
    path = write(tmp_path, SMALL + '[road]\nclass = "A"\nseed = 2\nlength = 200.0\n')
    res = runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    lines = [t for t in res.stderr.splitlines() if "one road realisation" in t]
    assert len(lines) == 1 and lines[0].startswith("warning: ") and "tire " not in lines[0], res.stderr
    from vbikit.cli.execute import grouped_warnings

    assert grouped_warnings({"a": (["w1", "w2"], []), "b": (["w2", "w3"], [])}) == ["w2", "tire a: w1", "tire b: w3"]


BUMP = """
name = "HS20-44 over a 50 mm bump"
[bridge]
model = "beam"
span = 10.0
EI = 1e10
mass_per_length = 5000.0
n_modes = 3
[vehicle]
model = "hs20-44"
[crossing]
speed = 20.0
approach = 4.0
[road]
class = "none"
[[road.defects]]
kind = "bump"
position = 1.0
height = 0.05
"""


def test_per_wheel_warnings_of_every_tire_model_are_one_line_with_a_count(tmp_path):
    """A new user saw about 20 warning lines: each wheel's contact loss (left and right alike) for each
    tire model.  Now one line per distinct warning, with its count and the worst instance; every
    instance is kept in compare-tires.json (``grouped_warnings``)."""
    path = write(tmp_path, BUMP)
    out = tmp_path / "out"
    res = runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(out)])
    assert res.exit_code == 0, res.output
    table = json.loads((out / "compare-tires.json").read_text())
    every = [(row["label"], w) for row in table.values() for w in row["warnings"]]
    losses = [(label, w) for label, w in every if " lost contact with the road on the bridge" in w]
    assert len(losses) >= 12  # (20 today: six wheels for three models, two for the disk)
    lines = res.stderr.splitlines()
    assert all(line.startswith("warning: ") for line in lines), res.stderr
    assert len(lines) < len(every) / 4, res.stderr  # (4 lines for 31 warnings today)
    contact = [line for line in lines if "lost contact" in line]
    assert len(contact) == 1, res.stderr
    counts = ", ".join(f"{m} {sum(label == m for label, _ in losses)}" for m in dict.fromkeys(l for l, _ in losses))
    assert f"(×{len(losses)} over the tire models: {counts}; the worst shown, each in {out / 'compare-tires.json'})" \
        in contact[0]
    longest = max(float(w.split(", for ")[1].split(" s")[0]) for _, w in losses)  # the seconds off the road
    assert f"for {longest:.4f} s on the bridge" in contact[0]
    for kind in ("dominated by airborne wheels", "tire forces over a road feature", "strain not converged"):
        assert sum(kind in line for line in lines) == 1, (kind, res.stderr)


def test_grouped_warnings_by_flag_code_subject_and_text():
    from vbikit.cli.execute import grouped_warnings

    def flag(code, message, value=None, threshold=None, wheel=None, subject=None):
        return {"code": code, "message": message, "value": value, "threshold": threshold, "wheel": wheel,
                "subject": subject or (f"wheel {wheel}" if wheel else None)}

    small = [flag("small_static", f"Girder 1: share {v}", v, 0.2, subject="Girder 1") for v in (0.12, 0.10)]
    other = flag("small_static", "Girder 5: share 0.15", 0.15, 0.2, subject="Girder 5")
    loss = [flag("contact_loss", f"wheel {w} off for {t} s", t, wheel=w) for w, t in (("L", 0.01), ("R", 0.03))]
    runs = {"a": ([small[0]["message"], loss[0]["message"], loss[1]["message"], "road", "some"], [small[0], *loss]),
            "b": (["road", small[1]["message"], other["message"], "some", "twice", "twice"], [small[1], other]),
            "c": (["road"], [])}
    assert grouped_warnings(runs) == [
        "road",  # every run once in the same words: once, unprefixed, first
        "tire b: Girder 1: share 0.1 (×2 over the tire models: a 1, b 1; the worst shown)",  # smaller share worse
        "tire a: wheel R off for 0.03 s (×2 over the tire models: a 2; the worst shown)",  # wheels together
        "tire a, b: some",  # the same words from some runs: their labels
        "tire b: Girder 5: share 0.15",  # another girder: another warning; one run: its label
        "tire b: twice (×2)",  # the same words twice in one run
    ]
