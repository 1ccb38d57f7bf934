"""`vbikit study` commands: run, validate, errors naming the key, paper study spec."""
from __future__ import annotations

import json

import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

STUDY = """
name = "cli study"
seed = 3
[base.bridge]
model = "paper-bridge-2-beam"
n_modes = 4
[base.vehicle]
model = "two-axle"
[base.road]
class = "C"
length = 200
[base.crossing]
speed_kmh = 90
[axes]
"crossing.speed_kmh" = [60, 90]
"road.seed" = { samples = 2 }
"""


def test_study_run_and_validate(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY)
    res = runner.invoke(app, ["study", "validate", str(tmp_path / "s.toml")])
    assert res.exit_code == 0 and "4 crossings" in res.output
    res = runner.invoke(app, ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"),
                              "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    assert "4 crossings" in res.output and "impact factor" in res.output
    ds = xr.open_dataset(tmp_path / "r.nc")
    assert ds.sizes == {"crossing_speed_kmh": 2, "sample": 2}
    # each swept axis's mean over the road samples (the axis named by its key; not the samples' own line)
    im = ds["impact_factor"].values  # (speed, sample)
    assert ds["crossing_speed_kmh"].values.tolist() == [60, 90] and abs(im[0].mean() - im[1].mean()) > 1e-3
    se = im.std(axis=1, ddof=1) / 2**0.5  # over the 2 road samples
    assert (f"mean by crossing.speed_kmh: 60 {im[0].mean():.4f} ± {se[0]:.4f}, 90 {im[1].mean():.4f} ± {se[1]:.4f}"
            in res.output) and "(± the standard error over the road samples; a difference's paired over the same roads)" in res.output
    assert "mean by road.seed" not in res.output and "mean by sample" not in res.output
    paired = im[1] - im[0]  # 90 against 60 km/h on the same two roads
    assert f"    difference from 60: 90 {paired.mean():+.4f} ± {paired.std(ddof=1) / 2**0.5:.4f}\n" in res.output
    ds.close()
    # how good its step is: the base crossing's half-step check, as `vbikit run` of that crossing states it
    from vbikit.scenario import run as run_scenario
    from vbikit.study.spec import load_study

    study = load_study(tmp_path / "s.toml")
    base = run_scenario(study.scenario_dict((0, 0)), base_dir=tmp_path).summary["step_check"]
    assert (f"step check of the base crossing (the other cells are not checked): at half the step ({base['dt']:.3e} s) "
            f"the deflection and strain IMs change by at most {base['largest_change']:.1e}") in res.output
    # and the dataset carries the check it printed (a dataset read later says how good its step is)
    from vbikit.study.check import stored_step_check

    with xr.open_dataset(tmp_path / "r.nc") as ds:
        stored = stored_step_check(ds.attrs)
    assert stored["largest_change"] == base["largest_change"] and stored["dt"] == base["dt"]


def test_a_study_at_a_given_step_says_its_step_check_is_not_run(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY.replace("speed_kmh = 90\n[axes]", "speed_kmh = 90\ndt = 0.002\n[axes]"))
    res = runner.invoke(app, ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"),
                              "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    from vbikit.scenario.step_check import DT_GIVEN_WORDS

    assert f"step check of the base crossing: {DT_GIVEN_WORDS}" in res.output
    assert "not run: crossing.dt is given" in DT_GIVEN_WORDS  # (the words vbikit run and compare-tires print too)


def test_study_of_one_road_says_its_means_have_no_standard_error(tmp_path):
    """`{ samples = 1 }`: the means by speed are one road's IMs; the output says there is no ± and how
    to get one, instead of printing bare means that read as settled (before 2026-12-06: nothing said)."""
    (tmp_path / "s.toml").write_text(STUDY.replace("{ samples = 2 }", "{ samples = 1 }"))
    res = runner.invoke(app, ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"),
                              "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        im = ds["impact_factor"].values.reshape(2)  # (speed,) over the one sample
    assert f"mean by crossing.speed_kmh: 60 {im[0]:.4f}, 90 {im[1]:.4f}\n" in res.output  # no ± after a mean
    assert "(± the standard error" not in res.output
    assert ('(one road profile per value: no standard error; a "road.seed" = { samples = N } axis, N ≥ 2, '
            "gives one)") in res.output


def test_study_errors_name_the_key(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY.replace('"crossing.speed_kmh" = [60, 90]', '"crossing.speed_kmh" = [60, -1]'))
    res = runner.invoke(app, ["study", "validate", str(tmp_path / "s.toml")])
    assert res.exit_code == 2
    assert "crossing.speed_kmh = -1" in res.output and "crossing.speed_kmh" in res.output
    res = runner.invoke(app, ["study", "run", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "r.nc")])
    assert res.exit_code == 2 and "study file not found" in res.output
    (tmp_path / "ok.toml").write_text(STUDY)
    res = runner.invoke(app, ["study", "run", str(tmp_path / "ok.toml"), "--out", str(tmp_path / "r.zip")])
    assert res.exit_code == 2 and "--out must be a NetCDF" in res.output


def test_paper_spec_printout():
    res = runner.invoke(app, ["study", "paper-fig11", "--samples", "2", "--print-spec"])
    assert res.exit_code == 0
    spec = json.loads(res.output)
    assert spec["axes"]["tire.model"] == ["point", "multipoint", "disk"]
    assert spec["axes"]["crossing.speed_kmh"] == [15, 30, 45, 60, 75, 90, 105, 120]
    assert spec["base"]["road"]["defects"] == [{"kind": "depression", "position": 0.0}]
    assert spec["base"]["bridge"]["model"] == "paper-bridge-2"  # the 3D deck, response at Girder 4
    assert spec["base"]["response"] == {"girder": 4}
    res = runner.invoke(app, ["study", "paper-fig11", "--samples", "2", "--print-spec", "--beam"])
    spec = json.loads(res.output)
    assert spec["base"]["bridge"]["model"] == "paper-bridge-2-beam" and "response" not in spec["base"]


def test_paper_study_end_to_end_small(tmp_path):
    """One paper study from one command (1 profile per point): dataset and figure."""
    res = runner.invoke(app, ["study", "paper-fig8", "--samples", "1", "--workers", "1", "--no-progress",
                              "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "paper-fig8-1samples.png").stat().st_size > 10_000
    ds = xr.open_dataset(tmp_path / "paper-fig8-1samples.nc")
    assert ds.sizes == {"tire_n_points": 8, "crossing_speed_kmh": 3, "road_class": 3, "sample": 1}
    assert "two-axle" in ds.attrs["study"]
    ds.close()


def test_paper_all_runs_every_figure(tmp_path):
    """`vbikit study paper-all`: the six paper studies one after another, each with its dataset
    and figure (1 profile per point to keep it short)."""
    res = runner.invoke(app, ["study", "paper-all", "--print-spec"])
    assert res.exit_code == 0
    names = [json.loads(line)["name"] for line in res.output.splitlines() if line.strip()]
    assert names == [f"paper-{f}" for f in ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11")]
    res = runner.invoke(app, ["study", "paper-all", "--samples", "1", "--workers", "2", "--no-progress",
                              "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    for f in ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11"):
        assert (tmp_path / f"paper-{f}-1samples.png").stat().st_size > 10_000
        with xr.open_dataset(tmp_path / f"paper-{f}-1samples.nc") as ds:
            assert ds.sizes["sample"] == 1 and ds["impact_factor"].notnull().all()


def test_study_run_prints_twelve_values_of_a_long_axis_and_counts_the_rest(tmp_path):
    speeds = list(range(40, 105, 5))  # 13 values
    (tmp_path / "s.toml").write_text(STUDY.replace('"crossing.speed_kmh" = [60, 90]', f'"crossing.speed_kmh" = {speeds}')
                                     .replace('"road.seed" = { samples = 2 }', '"road.seed" = { samples = 1 }'))
    res = runner.invoke(app, ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"),
                              "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    line = next(x for x in res.output.splitlines() if "mean by crossing.speed_kmh:" in x)
    assert line.count(",") == 12 and " 95 " in line and " 100 " not in line and line.endswith("… (1 more in the dataset)")


def test_the_study_output_quoted_in_docs_is_the_example_study_s(tmp_path):
    """docs/studies.md quotes `study run`'s closing lines for examples/studies/modes_sensitivity.toml."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    res = runner.invoke(app, ["study", "run", str(root / "examples" / "studies" / "modes_sensitivity.toml"), "--out",
                              str(tmp_path / "r.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    start = res.output.index("impact factor over all crossings")
    lines = res.output[start:].strip().splitlines()
    assert len(lines) == 9 and lines[1].startswith("  mean by bridge.model: ") and lines[-1].startswith("step check")
    assert "\n".join(lines) in (root / "docs" / "studies.md").read_text()


def test_out_equal_to_the_input_file_is_refused_as_such(tmp_path):
    """`--out` naming the study (or records) file itself: refused as the input, not as "not this study's
    finished dataset; delete it" (before 2026-12-06), which told the user to delete their input."""
    study = tmp_path / "s.nc"  # a study file with a NetCDF name, given as its own --out
    study.write_text(STUDY)
    res = runner.invoke(app, ["study", "run", str(study), "--out", str(study), "--workers", "1", "--no-progress"])
    assert res.exit_code == 2 and f"--out {study}: is the input file {study}; writing it would replace the input" in res.output
    assert "delete it" not in res.output and study.read_text() == STUDY
    records = tmp_path / "r.nc"
    records.write_text("x")  # (refused before it is read)
    res = runner.invoke(app, ["traffic", str(records), "--bridge", "paper-bridge-2", "--out", str(records)])
    assert res.exit_code == 2 and f"--out {records}: is the input file {records}" in res.output


def test_a_one_crossing_study_is_counted_in_the_singular(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY.replace('"crossing.speed_kmh" = [60, 90]', '"crossing.speed_kmh" = [60]')
                                     .replace('"road.seed" = { samples = 2 }', '"road.seed" = { samples = 1 }'))
    res = runner.invoke(app, ["study", "validate", str(tmp_path / "s.toml")])
    assert res.exit_code == 0, res.output
    assert "1 crossing (crossing.speed_kmh (1) × road.seed (1)) in 1 batch" in res.output and "1 crossings" not in res.output


def test_study_run_json_is_the_summary_alone_on_standard_output(tmp_path):
    """``study run --json``: one JSON object on standard output — the impact factors by axis value with their
    standard errors, as the text gives them, the base crossing's step check and the flags — and every other line
    (the run's count, the text) on standard error, as every command with --json."""
    import json

    import numpy as np

    (tmp_path / "s.toml").write_text(STUDY)
    argv = ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"), "--workers", "1", "--no-progress"]
    text = runner.invoke(app, argv)
    res = runner.invoke(app, [*argv, "--json"])  # (the finished dataset read back)
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    assert "impact factor over all crossings" in res.stderr and "step check of the base crossing" in res.stderr
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        im = ds["impact_factor"].values  # (speed, sample)
        assert summary["vbikit_version"] == ds.attrs["vbikit_version"] and summary["outputs"] == list(ds.data_vars)
    (row,) = summary["impact_factor"]
    assert row["mean"] == float(im.mean()) and row["max"] == float(im.max())
    (axis,) = row["axes"]
    assert axis["key"] == "crossing.speed_kmh" and axis["values"] == [60, 90]
    np.testing.assert_allclose(axis["means"], im.mean(axis=1), rtol=1e-12)
    np.testing.assert_allclose(axis["standard_error"], im.std(axis=1, ddof=1) / 2**0.5, rtol=1e-12)
    assert summary["step_check"]["largest_change"] >= 0 and summary["units"]["impact_factor"] == "1"
    assert f"{summary['step_check']['largest_change']:.1e}" in text.stdout


def test_a_load_effect_study_states_its_halving_and_validate_simulates_nothing_more(tmp_path, monkeypatch):
    """A study asking for moments runs its base through the load effects' halving (``converge_step``); the step check
    says so, as `vbikit run` of that crossing records it (a review found "not run (the base gives crossing.dt)" for
    a study that gave none).  ``study validate`` of a study without load effects runs no crossing."""
    from vbikit.scenario import run as run_scenario
    from vbikit.study.spec import load_study

    (tmp_path / "m.toml").write_text(STUDY.replace("[axes]", "[base.response]\nmoment = [8.0]\n[axes]"))
    res = runner.invoke(app, ["study", "run", str(tmp_path / "m.toml"), "--out", str(tmp_path / "m.nc"),
                              "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    base = run_scenario(load_study(tmp_path / "m.toml").scenario_dict((0, 0)), base_dir=tmp_path).summary["step_check"]
    assert base["halvings"] >= 1 and base["for"] == "load effects"
    assert (f"step check of the base crossing (the other cells are not checked): halved {base['halvings']}× to "
            f"{base['dt']:.3e} s for its load effects: the last halving changed the impact factors by at most "
            f"{base['largest_change']:.1e}") in res.output
    import vbikit.scenario.pipeline

    def no_run(*args, **kwargs):
        raise AssertionError("study validate ran a crossing")

    monkeypatch.setattr(vbikit.scenario.pipeline, "run_planned", no_run)
    (tmp_path / "s.toml").write_text(STUDY)
    res = runner.invoke(app, ["study", "validate", str(tmp_path / "s.toml")])
    assert res.exit_code == 0, res.output
