"""The study file's ``outputs`` key: a study reduces and stores only the outputs it asks for
(names of the catalogue ``vbikit.outputs``), with the same values as the whole catalogue's study."""
from __future__ import annotations

import json

import numpy as np
import pytest

import vbikit.study.compute as compute
from vbikit.outputs import OUTPUTS
from vbikit.study import StudyError, parse_study, run_study
from vbikit.study.paper import PAPER_OUTPUTS, paper_study_dict


def _small(d: dict) -> dict:
    d["axes"] = {"tire.n_points": [1, 4], "road.seed": {"samples": 2}}  # 4 crossings, 2 batches
    return d


def _effects_counter(monkeypatch) -> list[tuple[str, ...]]:
    """Record the kinds of load effect every crossing of ``run_batch`` reduces."""
    seen: list[tuple[str, ...]] = []
    inner = compute.load_effect_responses

    def counting(result, effects, *args, **kw):
        seen.append(tuple(e.kind for e in effects))
        return inner(result, effects, *args, **kw)

    monkeypatch.setattr(compute, "load_effect_responses", counting)
    return seen


def test_asked_outputs_only_same_values(tmp_path, small_study_dict, monkeypatch):
    full = run_study(parse_study(_small(small_study_dict)), tmp_path / "full.nc", workers=1)
    seen = _effects_counter(monkeypatch)
    one = run_study(parse_study(_small(small_study_dict) | {"outputs": ["impact_factor"]}), tmp_path / "im.nc", workers=1)
    assert set(one.data_vars) == {"impact_factor", "unconverged_steps"}  # the crossing's quality always (QUALITY_OUTPUTS)
    assert set(full.data_vars) == set(OUTPUTS)  # without the key: the whole catalogue, as before
    np.testing.assert_array_equal(one["impact_factor"].values, full["impact_factor"].values)
    assert np.all(np.isfinite(one["impact_factor"].values))
    assert one["impact_factor"].attrs == full["impact_factor"].attrs
    assert all(kinds == () for kinds in seen)  # no moment, shear or reaction history was computed
    assert json.loads(one.attrs["study"])["outputs"] == ["impact_factor"]


def test_load_effect_output_reduces_its_kind_only(tmp_path, small_study_dict, monkeypatch):
    full = run_study(parse_study(_small(small_study_dict)), tmp_path / "full.nc", workers=1)
    seen = _effects_counter(monkeypatch)
    asked = ["moment_impact_factor", "n_steps", "strain_impact_factor"]
    ds = run_study(parse_study(_small(small_study_dict) | {"outputs": asked}), tmp_path / "m.nc", workers=1)
    assert list(ds.data_vars) == ["strain_impact_factor", "moment_impact_factor", "n_steps",
                                  "unconverged_steps"]  # catalogue order
    for name in asked:
        np.testing.assert_array_equal(ds[name].values, full[name].values, err_msg=name)
    assert seen and all(kinds == ("moment",) for kinds in seen)


def test_default_study_text_is_unchanged(small_study_dict):
    """A study without the key keeps its canonical JSON (finished datasets and parts stay valid)."""
    spec = json.loads(parse_study(small_study_dict).to_json())
    assert set(spec) == {"name", "seed", "batch_size", "histories", "base", "axes"}


@pytest.mark.parametrize("outputs, words", [
    (["impact_factor", "impact_factr"], "unknown output 'impact_factr'; allowed: impact_factor, "),
    ([], "give at least one output name"),
    (["dt", "dt"], "'dt' is listed more than once"),
    ("impact_factor", "outputs"),
    ([1], "outputs"),
])
def test_bad_outputs_are_refused(small_study_dict, outputs, words):
    with pytest.raises(StudyError) as err:
        parse_study(small_study_dict | {"outputs": outputs})
    assert words in str(err.value) and "outputs" in str(err.value)
    if "allowed" in words:
        assert all(name in str(err.value) for name in OUTPUTS)


def test_paper_studies_ask_for_what_their_figures_plot():
    d = paper_study_dict("fig10", 1)
    assert d["outputs"] == list(PAPER_OUTPUTS) and "impact_factor" in PAPER_OUTPUTS  # plot_paper_figure's variable
    assert not any(OUTPUTS[n].effect for n in PAPER_OUTPUTS)  # no moment, shear or reaction per crossing
    assert parse_study(d).output_names == (*PAPER_OUTPUTS, "unconverged_steps")  # and the quality output, always


def test_cli_study_file_with_outputs(tmp_path):
    from typer.testing import CliRunner

    from vbikit.cli import app

    study = ('name = "cli outputs"\nseed = 3\noutputs = ["n_steps", "min_tire_force"]\n'
             '[base.bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 4\n[base.vehicle]\nmodel = "two-axle"\n'
             '[base.road]\nclass = "C"\nlength = 200\n[base.crossing]\nspeed_kmh = 90\n'
             '[axes]\n"road.seed" = { samples = 2 }\n')
    (tmp_path / "s.toml").write_text(study)
    res = CliRunner().invoke(app, ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"),
                                   "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    assert "outputs stored: min_tire_force, n_steps" in res.output
    import xarray as xr

    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert set(ds.data_vars) == {"min_tire_force", "n_steps", "unconverged_steps"} and np.all(ds["n_steps"].values > 100)
    (tmp_path / "bad.toml").write_text(study.replace('"min_tire_force"', '"min_tyre_force"'))
    res = CliRunner().invoke(app, ["study", "validate", str(tmp_path / "bad.toml")])
    assert res.exit_code == 2 and "outputs: unknown output 'min_tyre_force'; allowed: impact_factor" in res.output
