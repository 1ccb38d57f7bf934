"""Two findings of a new user's lifetime trial.

1. A bootstrap lifetime run whose characteristic static value lies above the largest static effect
any event of its traffic can produce is flagged (a new user's trial: the 100-year Gumbel static
value came out above the heaviest possible configuration, without a word).

Independent numbers: the records are two-axle trucks with axles 20 m apart on a 10 m simply
supported span, so one axle is on it at a time and a truck's midspan moment peaks at P L / 4
(closed form): 50 kN m for the 20 kN axles of the light trucks, 250 kN m for the 100 kN axles of
the heavy ones.  The records' smallest headway is 2,000 s while a truck has a load on the deck
for (10 + 20) m / (80 km/h) = 1.35 s, so at most one truck is on the bridge at a time and the
traffic cannot produce more than 250 kN m.  The daily maxima are 50 or 250 kN m (days with and
without a heavy truck); a Gumbel fit of them puts the 1,000-year level far above 250 kN m.

2. A failure after the simulations (while building the dataset) did not say that they are kept
under out/work and that a rerun resumes.
"""
import json

import numpy as np
import pytest

from tests.lifetime.specs import SPAN, beam_spec
from vbikit.analysis.checks import dataset_has_flag
from vbikit.lifetime.run import run_lifetime

P_LIGHT, P_HEAVY = 20e3, 100e3

SPEC = beam_spec("light and heavy trucks", 3, 8, "[1, 1000]", "mix.csv", 12)


def _write(tmp_path, heavy_every: int):
    rows = ["id,time [s],lane,lateral_offset [m],direction,speed [km/h],model,axle_loads [kN],axle_spacings [m]"]
    for i in range(40):
        p = P_HEAVY if i % heavy_every == 0 else P_LIGHT
        rows.append(f"v{i:03d},{100 + 2000.0 * i:.1f},1,,+x,80,axles,{p / 1e3:g} {p / 1e3:g},20")
    (tmp_path / "mix.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "lt.toml").write_text(SPEC)
    return tmp_path / "lt.toml"


def test_characteristic_above_the_traffic_maximum_is_flagged(tmp_path):
    out = tmp_path / "out"
    ds = run_lifetime(_write(tmp_path, heavy_every=10), out, workers=1, figures=False)
    bound = P_HEAVY * SPAN / 4  # closed form (module docstring)
    assert ds["static_upper_bound"].values[0] == pytest.approx(bound, rel=1e-6)
    assert json.loads(ds.attrs["static_bound_vehicles_per_lane"]) == [1]
    daily = ds["daily_max_static"].values[:, 0]
    assert set(np.round(daily / 1e3, 6)) == {P_LIGHT * SPAN / 4e3, P_HEAVY * SPAN / 4e3}  # both kinds of day
    char = float(ds["characteristic_static"].values[0])
    assert char > bound
    assert ds["characteristic_static_above_bound"].values[0] == 1
    assert ds.attrs["above_static_bound"].startswith(f"M static: the characteristic value {char:.6g} N m exceeds 250000 N m")
    summary = json.loads((out / "summary.json").read_text())["load_effects"]["M"]
    assert summary["static_upper_bound"] == pytest.approx(bound, rel=1e-6)
    (flag,) = [f for f in summary["flags"] if f["code"] == "characteristic_above_static_bound"]
    assert (flag["output"], flag["subject"]) == ("characteristic static value", "M")
    assert flag["value"] == pytest.approx(char, rel=1e-12) and flag["threshold"] == pytest.approx(bound, rel=1e-6)
    for words in ("largest static effect any event of the traffic model", "exceeds what the traffic model can produce",
                  "unbounded tail", "bounded tail", "block maxima at 1000 years"):
        assert words in flag["message"]
    assert "! " + flag["message"] in (out / "report.txt").read_text()
    assert dataset_has_flag(ds.attrs, "characteristic_above_static_bound")
    assert "characteristic_above_static_bound" in str(ds["load_effect_flag_codes"].values[0]).split(",")


def test_a_failure_after_the_simulations_says_they_are_kept_and_a_rerun_resumes(tmp_path, monkeypatch):
    """A failure while building the dataset (here a disk error raised in its place) tells the user
    that the stages under out/work are kept and the same command resumes; the rerun then finishes
    from them.  A failure before any stage finished says nothing of the kind."""
    from typer.testing import CliRunner

    import vbikit.lifetime.results as results
    import vbikit.lifetime.run as run_module
    from vbikit.cli import app

    spec = _write(tmp_path, heavy_every=10)
    out = tmp_path / "out"
    build = results.build_dataset

    def disk_full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(results, "build_dataset", disk_full)
    res = CliRunner().invoke(app, ["lifetime", str(spec), "--out-dir", str(out), "--workers", "1", "--no-figures",
                                   "--no-progress"])
    assert res.exit_code == 2, res.output
    assert "error: [Errno 28] No space left on device" in res.stderr
    note = next(t for t in res.stderr.splitlines() if t.startswith("note: "))
    assert f"kept in {out / 'work'}" in note and "static" in note and "run the same command again to resume" in note
    # the rerun resumes: no stage is simulated again (the study runner would call its jobs' batches)
    monkeypatch.setattr(results, "build_dataset", build)
    monkeypatch.setattr("vbikit.study.run._compute", lambda *a, **k: pytest.fail("a finished stage was simulated again"))
    res = CliRunner().invoke(app, ["lifetime", str(spec), "--out-dir", str(out), "--workers", "1", "--no-figures",
                                   "--no-progress"])
    assert res.exit_code == 0, res.output
    # nothing finished yet: no note
    monkeypatch.setattr(run_module, "_run", lambda *a, **k: disk_full())
    with pytest.raises(OSError) as err:
        run_lifetime(spec, tmp_path / "fresh", workers=1, figures=False)
    assert not getattr(err.value, "__notes__", None)
