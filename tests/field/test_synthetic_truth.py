"""Synthetic field test with known truth: the workflow recovers the time shift, the accelerometer
offset and drift, reports errors at the noise floor against the true model, and the calibration
recovers the true stiffness factor within its reported uncertainty.

Independent references: the truth is a different code path (every E of the grillage × 1.10, modes
re-solved) from the fitted model (ωᵢ × √f on the nominal modes); the expected error floor is the
added white noise after the 40 Hz low-pass: σ_n √(f_c / (f_s/2)) (noise power in the pass band).
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vbikit.field import calibrate, compare_case, load_field_toml


def _spec(synthetic, **kw):
    out, truth = synthetic
    return dataclasses.replace(load_field_toml(out / "FIELD.toml"), **kw), truth


def test_truth_recovery(synthetic):
    spec, truth = _spec(synthetic, stiffness_factor=truth_f(synthetic), damping_ratio=synthetic[1].damping_ratio)
    case = dataclasses.replace(spec.cases[0], align="xcorr")  # ignore the trigger: find the shift by correlation
    cmp = compare_case(spec, case, ["multipoint"])
    tab = cmp.table()
    # time offset: recorder trigger recovered to a fraction of the 5 ms sampling interval
    assert tab["trigger_time_s"] == pytest.approx(truth.trigger_time["case1"], abs=1e-3)
    # accelerometer offset and drift (model-free fit on the quiet windows)
    d = tab["drift"]["G5_acc"]
    assert d["t_ref_s"] == pytest.approx(truth.t_ref["case1"])
    assert d["offset"] == pytest.approx(truth.acc_offset, abs=1e-3)
    assert d["drift_per_s"] == pytest.approx(truth.acc_drift, abs=3e-4)
    # near-zero error: at the noise floor of the record
    passband = np.sqrt(spec.lowpass_hz / (truth.sampling_rate / 2))
    for name, q in (("G5_disp", "displacement"), ("G5_acc", "acceleration"), ("G5_strain", "strain")):
        m = tab["metrics"]["multipoint"][name]
        floor = truth.noise[q] * passband / np.sqrt(np.mean(cmp.measured[name] ** 2))
        assert m["normalised_rms_error"] < 1.3 * floor, (name, m["normalised_rms_error"], floor)
        assert m["correlation"] > 0.99
        assert abs(m["peak_error"]) < 0.02
        assert m["psd_bands"][0]["amplitude_ratio"] == pytest.approx(1.0, abs=0.02)  # 0–5 Hz, signal-dominated


def truth_f(synthetic):
    return synthetic[1].stiffness_factor


def test_nominal_model_is_measurably_off(synthetic):
    """The metrics discriminate: the nominal (10 % softer) model misses the peak by > 4 %."""
    spec, _ = _spec(synthetic)
    cmp = compare_case(spec, spec.cases[0], ["point"])
    m = cmp.metrics["point"]["G5_disp"]
    assert m["peak_error"] > 0.04
    assert m["normalised_rms_error"] > 0.05


def test_calibration_recovers_stiffness_factor(synthetic):
    spec, truth = _spec(synthetic)
    cmp = compare_case(spec, spec.cases[0], ["multipoint"])
    cal = calibrate(spec, [cmp], tire="multipoint", max_nfev=20)
    assert abs(cal.stiffness_factor - truth.stiffness_factor) < 3 * cal.stiffness_factor_std
    assert cal.stiffness_factor == pytest.approx(truth.stiffness_factor, abs=1e-3)
    assert 0 < cal.stiffness_factor_std < 5e-3
    # damping: close to the truth, but the 1-σ from s²(JᵀJ)⁻¹ is optimistic for it (see docs/field.md)
    assert cal.damping_ratio == pytest.approx(truth.damping_ratio, abs=1e-3)


def test_model_based_drift_removal(synthetic):
    """drift = "model": the line through measured − simulated recovers the offset and drift too."""
    spec, truth = _spec(synthetic, stiffness_factor=synthetic[1].stiffness_factor,
                        damping_ratio=synthetic[1].damping_ratio, drift="model")
    d = compare_case(spec, spec.cases[0], ["multipoint"]).drift["G5_acc"]
    assert d.method == "model"
    assert d.offset == pytest.approx(truth.acc_offset, abs=1e-3)
    assert d.drift == pytest.approx(truth.acc_drift, abs=3e-4)
