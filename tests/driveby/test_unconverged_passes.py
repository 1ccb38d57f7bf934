"""A drive-by pass whose contact forces did not converge in some steps is unreliable, in words: its
identification is excluded (``identified_frequency_reliable`` 0, the reason naming the steps), the
dataset carries the ``contact_not_converged`` flag, and the report and summary JSON say so.

The unconverged passes are made as in tests/unit/test_unconverged_steps.py: the full implicit kernel
allowed one contact-law evaluation a step (``IMPLICIT_MAX_ITERATIONS`` = 1) on rigid-disk tyres, which
go to that kernel directly; on a rough road no step then settles to the solver's tolerance."""
from __future__ import annotations

import json
from importlib import import_module

import numpy as np

from vbikit.driveby.study import unconverged_reasons
from vbikit.solve import integrators

simulate_module = import_module("vbikit.solve.simulate")  # (the package exports the function of that name)


def test_the_reason_names_the_steps_and_keeps_the_identifications_own():
    reasons = unconverged_reasons(np.array(["", "peak below -6 dB", ""]), np.array([0.0, 3.0, np.nan]))
    assert reasons[0] == "" and reasons[2] == ""  # none, and not known (NaN), add nothing
    assert reasons[1].startswith("the contact forces did not converge in 3 time steps of this pass")
    assert reasons[1].endswith("; peak below -6 dB")


def test_a_rigid_disk_sweep_at_one_iteration_is_flagged_everywhere(tmp_path, monkeypatch):
    import xarray as xr

    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby.study import run_driveby

    monkeypatch.setattr(integrators, "IMPLICIT_MAX_ITERATIONS", 1)
    monkeypatch.setattr(simulate_module, "UNCONVERGED_HALVINGS", 0)  # counted at the step given, not run again
    spec = parse_driveby({
        "seed": 4, "tire": {"model": "rigid-disk"}, "road": {"class": "C", "length": 200.0},
        "bridge": {"model": "continuous-beam", "spans": [20.0], "EI": 2.4e10, "mass_per_length": 4800.0, "n_modes": 2},
        "crossing": {"approach": 5.0}, "sampling": {"rate": 200.0},
        "sensors": [{"name": "acc", "body": "body"}], "identification": {"band": [1.0, 20.0]},
        "variability": {"passes": 2, "speed": [8.0, 9.0]}})
    run_driveby(spec, tmp_path, workers=1, figures=False)
    ds = xr.open_dataset(tmp_path / "driveby.nc")
    counts = ds["unconverged_steps"].values
    assert counts.shape == (2,) and np.all(counts > 0)
    assert np.all(ds["identified_frequency_reliable"].values == 0)
    for i in range(2):
        assert str(ds["identified_frequency_reason"].values[i]).startswith(
            f"the contact forces did not converge in {int(counts[i])} time steps of this pass")
    assert "contact_not_converged" in ds.attrs["flag_codes"].split(",")
    assert "2 of 2 passes" in ds.attrs["warnings"]
    worst = int(np.argmax(counts))
    assert f"the most: {int(counts[worst])} steps in case {worst})" in ds.attrs["warnings"]
    report = (tmp_path / "driveby-report.txt").read_text()
    assert "! the contact forces did not converge" in report
    summary = json.loads((tmp_path / "driveby-summary.json").read_text())
    assert summary["warnings"] == [ds.attrs["warnings"]]  # a list of messages, each a flag record's
    assert [f["code"] for f in summary["flags"]] == ["contact_not_converged"]
    assert all(not case["reliable"] for case in summary["cases"])


def test_the_flag_counts_passes_and_names_the_worst_case():
    from vbikit.driveby.quality import unconverged_pass_flags

    assert unconverged_pass_flags(np.array([0.0, np.nan])) == []
    (flag,) = unconverged_pass_flags(np.array([0.0, 1.0, 0.0]))
    assert flag.code == "contact_not_converged" and "1 of 3 passes" in flag.message
    assert "the most: 1 step in case 1)" in flag.message
    (one,) = unconverged_pass_flags(np.array([4.0]))
    assert "1 of 1 pass " in one.message and "4 steps in case 0" in one.message
