"""A study's dataset carries the step check `vbikit study run` states (attribute ``step_check``) and flags a step that
check finds not converged (``step_not_converged`` in ``warnings`` and ``flag_codes``), so that a dataset read later
says how good its time step is; before 2026-12-08 only the printed line and ``--json`` said it, and a study whose base
crossing changed by 2 % at half the step wrote a dataset with no word of it."""
from __future__ import annotations

import json

import xarray as xr

from vbikit.analysis.checks import dataset_flags
from vbikit.analysis.effect_step import STEP_TOLERANCE
from vbikit.scenario.step_check import step_check_words
from vbikit.study.check import check_study, store_step_check, stored_step_check, study_step_flags
from vbikit.study.run import run_study
from vbikit.study.spec import parse_study
from vbikit.study.summary import study_summary

HALF = {"dt": 1e-3, "largest_change": 0.0, "output": "impact_factor", "acceleration_change": 0.0,
        "acceleration_output": None, "accelerations_not_converged": [], "study_dt": 2e-3}


def test_a_half_step_change_above_the_tolerance_is_flagged_and_one_below_is_not():
    assert study_step_flags(HALF | {"largest_change": 0.9 * STEP_TOLERANCE}) == []
    record = HALF | {"largest_change": 1.1 * STEP_TOLERANCE}
    (flag,) = study_step_flags(record)
    assert flag.code == "step_not_converged" and flag.output == "impact_factor" and flag.subject == "base crossing"
    assert flag.value == 1.1 * STEP_TOLERANCE and flag.threshold == STEP_TOLERANCE
    assert step_check_words(record) in flag.message and "set a smaller crossing.dt in the base" in flag.message


def test_a_halving_flags_a_step_coarser_than_the_one_it_settled_at_or_no_settling():
    halving = {"halvings": 2, "converged": True, "for": "load effects", "dt": 5e-4, "largest_change": 1e-3,
               "output": "moment_x20", "study_dt": 2e-3}
    (flag,) = study_step_flags(halving)  # settled at 0.5 ms; the study's crossings ran at 2 ms
    assert "the study's crossings ran at 0.002 s: set crossing.dt = 0.0005 in the base" in flag.message
    assert flag.output == "moment_x20"
    assert study_step_flags(halving | {"dt": 2e-3}) == []  # settled at the study's own step
    (flag,) = study_step_flags(halving | {"converged": False})
    assert ", not converged" in flag.message and "raise --max-steps" in flag.message
    assert study_step_flags({**HALF, "largest_change": None, "note": "not run: above the budget"}) == []
    assert study_step_flags(None) == []


def test_the_check_is_stored_after_the_datasets_own_flags():
    attrs = {"title": "t", "warnings": "first; second", "flag_codes": "small_static"}
    record = HALF | {"largest_change": 0.02}
    out = store_step_check(attrs, record)
    (flag,) = study_step_flags(record)
    assert out["warnings"] == f"first; second; {flag.message}"
    assert out["flag_codes"] == "small_static,step_not_converged" and out["title"] == "t"
    assert dataset_flags(out)[1] == ["first; second", flag.message]  # (the older messages kept, as one)
    assert stored_step_check(out) == record
    # its record too (a dataset written with records keeps them, the new one after)
    records = [{"code": "small_static", "message": "first; second"}]
    (old, new), _ = dataset_flags(store_step_check(attrs | {"flags": json.dumps(records)}, record))
    assert old == records[0] and new["code"] == "step_not_converged" and new["value"] == 0.02
    passed = store_step_check(attrs, HALF)
    assert {k: v for k, v in passed.items() if k != "step_check"} == attrs and stored_step_check(passed) == HALF
    assert store_step_check(attrs, None) == attrs and stored_step_check(attrs) is None


def test_a_study_whose_load_effects_settle_only_at_a_finer_step_writes_the_flag(tmp_path):
    """The case of test_step_advice.py (two 20 m spans on elastic bearings, pier moment, 40 modes): the base's halving
    settles at a step finer than the automatic step the study's crossings run at."""
    bridge = {"model": "continuous-beam", "spans": [20.0, 20.0], "EI": 4.865e10, "mass_per_length": 18358.0,
              "support_stiffness": [5e8, 2e8, 5e8], "rotational_stiffness": [2e9, 2e9], "damping_ratio": 0.0,
              "n_modes": 40}
    base = {"bridge": bridge, "vehicle": {"model": "quarter-car"}, "tire": {"model": "point"},
            "road": {"class": "none"}, "crossing": {"speed_kmh": 70}, "response": {"moment": [20.0]}}
    study = parse_study({"name": "elastic", "base": base, "axes": {"crossing.speed_kmh": [70, 80]}})
    check = check_study(study, step_check=True).step_check
    assert check["halvings"] >= 1 and check["dt"] < check["study_dt"]
    run_study(study, tmp_path / "e.nc", workers=1, step_check=check)
    with xr.open_dataset(tmp_path / "e.nc") as ds:
        assert stored_step_check(ds.attrs) == check
        assert "step_not_converged" in ds.attrs["flag_codes"].split(",")
        summary = study_summary(ds)  # (no check given: the dataset's own)
    assert summary["step_check"] == check and "step_not_converged" in summary["flag_codes"]
    (flag,) = [f for f in summary["flags"] if f["code"] == "step_not_converged"]
    assert f"set crossing.dt = {check['dt']:.3g} in the base" in flag["message"] and flag["message"] in summary["warnings"]
    run_study(study, tmp_path / "plain.nc", workers=1)  # the Python path without a check: none stored, none said
    with xr.open_dataset(tmp_path / "plain.nc") as ds:
        assert "step_check" not in ds.attrs and study_summary(ds)["step_check"] is None
