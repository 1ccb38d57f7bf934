"""What a new user reads: help summaries, labels and units in the text reports and figures.
Expected texts are written out here from what each label must say (not taken from the code)."""
from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]


def test_study_help_summarises_each_paper_command_whole():
    # click's default summary is the docstring's first sentence, which ended at the "." of "Fig."
    res = runner.invoke(app, ["study", "--help"], env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.output
    lines = {line.split()[0]: line for line in res.output.splitlines() if line.strip().startswith("paper-")}
    assert set(lines) == {"paper-fig5", "paper-fig6", "paper-fig7", "paper-fig8", "paper-fig10", "paper-fig11", "paper-all"}
    assert "Fig. 6: IM vs number of points, HS20-44, Bridge 2" in lines["paper-fig6"]
    assert "Fig. 11: IM vs speed per tire model" in lines["paper-fig11"]
    assert "All six paper studies" in lines["paper-all"]


@pytest.mark.parametrize("n, text", [(1, "CSA S6 by 1 axle,"), (3, "CSA S6 by 3 axles,")])
def test_the_axle_count_beside_the_codes_is_explained_and_in_the_right_number(n, text, capsys):
    from vbikit.cli.render import print_codes

    print_codes({"loaded_length": 16.76, "first_frequency": 7.3, "n_axles": n, "aashto_lrfd": 0.33}, "codes")
    out = capsys.readouterr().out
    # CSA S6 3.8.4.5.3 counts the axles on the span at once, which the text says
    assert text in out and "on a span of the loaded length at once" in out and "1 axles" not in out


def _result(x_front: np.ndarray, forces: np.ndarray, span: float = 65.0):
    """The parts of a CrossingResult that contact_flags reads: one wheel at the front axle, on a square deck."""
    t = np.arange(x_front.size) * 0.01
    wheel = SimpleNamespace(name="axle1_left", stiffness=1e6, offset=0.0)
    bridge = SimpleNamespace(deck_extent=(0.0, span), span=span, span_coordinate=lambda x, y: np.broadcast_arrays(
        np.asarray(x, float), np.asarray(y, float))[0].copy())
    crossing = SimpleNamespace(vehicle=SimpleNamespace(wheels=[wheel]), bridge=bridge,
                               point_kinematics=lambda: (np.zeros(1), np.ones(1), np.zeros(1)),
                               contact=SimpleNamespace(wheel=np.zeros(1, np.int64)))
    return SimpleNamespace(wheel_forces=forces[:, None], dt=0.01, time=t, crossing=crossing,
                           wheel_positions=lambda: x_front[:, None])


def test_contact_lost_only_after_the_bridge_is_said_to_be_after_it():
    from vbikit.analysis.checks import contact_flags

    x = np.linspace(-10.0, 80.0, 91)            # 1 m per step
    f = np.where((x > 70.0) & (x < 75.0), 0.0, 5e4)  # airborne at 71 … 74 m, past the 65 m deck
    (text,) = [flag.message for flag in contact_flags(_result(x, f))]
    assert "only after the bridge" in text and "x = 71.000 m" in text


def test_contact_lost_on_the_bridge_is_located_on_it():
    from vbikit.analysis.checks import contact_flags

    x = np.linspace(-10.0, 80.0, 91)
    f = np.where(((x > 20.0) & (x < 23.0)) | ((x > 70.0) & (x < 75.0)), 0.0, 5e4)
    (text,) = [flag.message for flag in contact_flags(_result(x, f))]
    assert "on the bridge: first at x = 21.000 m" in text
    assert "for 0.0200 s on the bridge (and 0.0400 s off it)" in text


@pytest.mark.parametrize("cf, shown", [("km h-1", "km/h"), ("m s-1", "m/s"), ("m s-2", "m/s²"), ("N m2", "N·m²"),
                                       ("1", "-"), ("m", "m"), ("degrees", "degrees"), ("kg m-1 s-1", "kg/(m·s)")])
def test_dataset_units_are_written_for_readers_on_axes(cf, shown):
    from vbikit.plot.labels import unit_label

    assert unit_label(cf) == shown


def test_every_design_code_has_its_own_colour_and_marker():
    from vbikit.analysis.codes import code_allowances
    from vbikit.plot.styles import CODE_STYLES

    codes = code_allowances(16.76, 7.3, 3)
    assert set(codes) == set(CODE_STYLES)
    styles = list(CODE_STYLES.values())
    assert len({s.color for s in styles}) == len(styles) and len({s.marker for s in styles}) == len(styles)
    assert "k" not in {s.color for s in styles} and "black" not in {s.color for s in styles}


def test_compare_tires_names_the_tire_model_of_each_own_warning_and_the_units_of_each_column(tmp_path):
    # the Fig. 9 case (its 20 mm depression) gives warnings for some of the tire models
    res = runner.invoke(app, ["compare-tires", str(ROOT / "examples/paper/fig9_tire_models.toml"), "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    warnings = [line for line in res.output.splitlines() if line.startswith("warning:")]
    # a warning of one model names it; one every model shares (the random road's) is printed once, unprefixed
    shared = [line for line in warnings if not line.startswith("warning: tire ")]
    assert [line for line in shared if "one road realisation" in line] == shared and len(shared) == 1, warnings
    assert len(warnings) > 1 and all(line.startswith("warning: tire ") for line in warnings[1:]), warnings
    header = next(line for line in res.stdout.splitlines() if "tire model" in line)  # (stderr's counts say "tire models")
    for column in ("u_max [mm]", "IM [-]", "ε_max [µε]", "IM_ε [-]", "|a|max [m/s²]", "F_min [kN]", "run time [s]"):
        assert column in header


def test_the_field_table_gives_units(tmp_path):
    res = runner.invoke(app, ["field", str(ROOT / "examples/field/FIELD.toml"), "--out-dir", str(tmp_path), "--tires", "point"])
    assert res.exit_code == 0, res.output
    assert "peak err [%]" in res.output and "RMS err" in res.output
    rows = [line.split() for line in res.output.splitlines() if line.strip().startswith("point ")]
    units = {row[1].rsplit("_", 1)[1]: row[4] for row in rows}  # channel G5_disp → its RMS error's unit
    assert units == {"disp": "mm", "acc": "m/s²", "strain": "µε"}
