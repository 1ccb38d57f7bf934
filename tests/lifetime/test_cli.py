"""``vbikit lifetime`` on a cut-down of the example, resuming, errors before any computation."""
import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from vbikit.lifetime.spec import LifetimeError
from vbikit.lifetime.run import prepare, run_lifetime

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "lifetime"


def _cut_down(tmp_path: Path) -> Path:
    """The example with 5 days of 60 trucks a day (the records file copied beside it)."""
    shutil.copy(EXAMPLE / "wim.csv", tmp_path / "wim.csv")
    text = (EXAMPLE / "lifetime.toml").read_text()
    text = text.replace("days = 7", "days = 5").replace('mode = "fitted"', 'mode = "fitted"\ntrucks_per_day = 60')
    text = text.replace("dynamic_sample = 0.02", "dynamic_sample = 0.05").replace("n_modes = 4", "n_modes = 3")
    path = tmp_path / "lifetime.toml"
    path.write_text(text)
    return path


def test_cli_cut_down_example_and_resume(tmp_path, summary_on_stdout):
    """The example's file (5 days, 60 trucks a day) through the CLI: lifetime.nc holds the
    contract's variables with units, fatigue_damage by detail, the figures and report are
    written; a second run reuses the stored stages and gives the same dataset."""
    spec = _cut_down(tmp_path)
    out = tmp_path / "out"
    cmd = [sys.executable, "-c", "from vbikit.cli import main; main()", "lifetime", str(spec), "--out-dir", str(out), "--workers", "1",
           "--no-progress"]
    first = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert first.returncode == 0, first.stderr
    assert "ADR" in first.stdout
    with xr.open_dataset(out / "lifetime.nc") as ds:
        ds = ds.load()
    # one parseable unit per variable (CF): the example's effects have several (N m, m), so a variable over them
    # names the coordinate of each effect's unit instead (a trial found "N m; m; N", which cf_units refuses)
    assert len(set(ds["load_effect_units"].values)) > 1
    for name in ("characteristic_static", "characteristic_total"):
        assert ds[name].dims == ("load_effect",) and "units" not in ds[name].attrs
        assert ds[name].attrs["units_by_load_effect"] == "load_effect_units"
    assert ds["assessment_dynamic_ratio"].attrs["units"] == "1"
    for name, var in ds.variables.items():  # every unit a single one: no packed list
        assert ";" not in str(var.attrs.get("units", "")), name
    assert ds["fatigue_damage"].dims == ("detail",)
    assert list(ds["detail"].values) == ["flange_EN36", "flange_AASHTO_E"]
    assert np.all(np.isfinite(ds["assessment_dynamic_ratio"].values))
    assert 0 < ds.attrs["fraction_dynamic"] < 1
    for fig in ("lifetime-gumbel.png", "lifetime-adr.png", "lifetime-fatigue.png", "lifetime-traffic.png", "report.txt"):
        assert (out / fig).is_file(), fig
    # it says what it wrote, one line a file, as every command that writes a folder
    wrote = sorted(line.removeprefix("wrote ") for line in first.stdout.splitlines() if line.startswith("wrote "))
    assert wrote == sorted(str(out / n) for n in ("lifetime.nc", "report.txt", "summary.json", "lifetime-gumbel.png",
                                                  "lifetime-adr.png", "lifetime-fatigue.png", "lifetime-traffic.png"))
    # --json: standard output is the summary's object alone, the report goes to standard error
    js = summary_on_stdout(["lifetime", str(spec), "--out-dir", str(out), "--workers", "1", "--no-progress",
                            "--no-figures"], out / "summary.json")
    assert "ADR" in js.stderr and json.loads(js.stdout)["load_effects"]["M_mid"]["units"] == "N m"
    # every fatigue number with its unit, as the dataset writes it (a trial's summary gave a stress range in Pa, unsaid)
    detail = json.loads(js.stdout)["fatigue"]["flange_EN36"]
    assert detail["units"]["equivalent_stress_range"] == "Pa" and detail["units"]["remaining_life"] == "year"
    assert detail["units"]["fatigue_damage"] == "1" and set(detail["units"]) <= set(detail)
    # every load effect's flags at the top too, as every summary gives them, each naming its effect
    whole = json.loads(js.stdout)
    expected = [(name, f["code"], f["message"]) for name, e in whole["load_effects"].items() for f in e["flags"]]
    assert [(f["load_effect"], f["code"], f["message"]) for f in whole["flags"]] == expected
    assert whole["warnings"] == [f"{name}: {message}" for name, _, message in expected]
    (out / "lifetime.nc").unlink()
    again = run_lifetime(spec, out, workers=1, figures=False)
    for name in ("characteristic_static", "characteristic_total", "fatigue_damage", "event_total"):
        np.testing.assert_array_equal(again[name].values, ds[name].values)


@pytest.mark.parametrize("change, message", [
    ({"days": 0}, "days: expected an integer in [1, 73000], got 0"),
    ({"amplification": -1}, "amplification: expected a number in [0.01, "),
    ({"colour": 3}, "colour: unknown key; allowed: name, seed, days"),
    ({"load_effects": [{"kind": "torque"}]}, "load_effects[1].kind"),
    ({"fatigue": {"details": [{"name": "d", "effect": "nope", "section_modulus": 0.1, "category": "EN 71"}]}},
     "fatigue.details[1].effect: 'nope' is not a load effect; allowed: M"),
    ({"fatigue": {"details": [{"name": "d", "effect": "M", "section_modulus": 0.1, "category": "EN x"}]}},
     "fatigue.details[1].category: 'EN x' is not a detail category"),
    ({"days": 3}, "days: 3 day(s) give 3 daily maxima; a gumbel fit needs at least 5"),
    ({"years": 100, "days": None}, "budget_hours: the run is estimated at"),
    ({"traffic": {"records": "missing.csv"}}, "traffic.records"),
])
def test_errors_name_the_key_before_any_computation(change, message):
    spec = {"days": 5, "traffic": {"records": "examples/lifetime/wim.csv"},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
            "load_effects": [{"kind": "moment", "x": 4.0, "name": "M"}]}
    spec.update(change)
    spec = {k: v for k, v in spec.items() if v is not None}
    with pytest.raises(LifetimeError, match=__import__("re").escape(message)):
        prepare(spec, ".")
