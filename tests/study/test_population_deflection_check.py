"""A study's and a traffic stream's dataset carry the single run's implausible-deflection check
(``vbikit.analysis.checks.implausible_deflection_dataset_flags``, one threshold
``IMPLAUSIBLE_DEFLECTION_FRACTION`` and one wording with ``implausible_deflection_flags``).

Independent numbers: a moving constant force P = 100 kN (the ``moving-force`` preset) on a smooth
road over a simply supported beam of span L = 25 m; the static reference at midspan peaks when the
force stands there, P L³ / (48 EI) (closed form of the simply supported beam under a central point
load; the runs' 4 modes sum 99.77 % of it, ``_four_modes``): with EI = 8.323e9 N m² (the Yang–Yau beam) 3.91 mm = L/6390 (not flagged), with the kN m²
mistake EI = 8.323e6 3.91 m = L/6.39 (flagged above L/100).
"""
from __future__ import annotations

import numpy as np
import pytest
from typer.testing import CliRunner

from vbikit.analysis.checks import IMPLAUSIBLE_DEFLECTION_ADVICE, IMPLAUSIBLE_DEFLECTION_FRACTION
from vbikit.cli import app
from vbikit.study.run import run_study
from vbikit.study.spec import parse_study
from vbikit.traffic.records import VehicleRecord
from vbikit.traffic.study import traffic_study

P, L = 100e3, 25.0
GOOD_EI, BAD_EI = 8.323e9, 8.323e6
runner = CliRunner()


def _base(EI: float) -> dict:
    return {"bridge": {"model": "beam", "span": L, "EI": EI, "mass_per_length": 2303.0, "n_modes": 4},
            "vehicle": {"model": "moving-force"}, "road": {"class": "none"},
            "crossing": {"speed_kmh": 60, "approach": 1.0, "free_vibration": 0.1}}


def _closed_form(EI: float) -> float:
    return P * L**3 / (48 * EI)  # midspan deflection under a central point load [m]


def _four_modes(EI: float) -> float:
    """The closed form as the runs' 4 modes sum it: P L³/(48 EI) = Σ_n odd 2 P L³/(π⁴ n⁴ EI) (the modal
    series of the central load, Σ_n odd n⁻⁴ = π⁴/96); modes 1 and 3 carry it at midspan."""
    return _closed_form(EI) * 96 / np.pi**4 * (1 + 3.0**-4)


def _study(EI: float, tmp_path, name: str):
    study = parse_study({"name": name, "seed": 1, "batch_size": 2, "base": _base(EI),
                         "axes": {"crossing.speed_kmh": [40, 60, 80]}}, tmp_path)
    return run_study(study, tmp_path / f"{name}.nc", workers=1)


def test_a_study_on_a_beam_with_ei_in_kilonewtons_says_so(tmp_path):
    ok = _study(GOOD_EI, tmp_path, "ok")
    assert -ok["max_static_displacement"].values == pytest.approx(_four_modes(GOOD_EI), rel=1e-4)
    assert _closed_form(GOOD_EI) < IMPLAUSIBLE_DEFLECTION_FRACTION * L
    # (its four modes' strain is flagged, as vbikit run flags it: strain_not_converged; not an implausible deflection)
    assert "implausible_deflection" not in ok.attrs.get("flag_codes", "")
    assert "implausible" not in ok.attrs.get("warnings", "")
    bad = _study(BAD_EI, tmp_path, "bad")
    assert -bad["max_static_displacement"].values == pytest.approx(_four_modes(BAD_EI), rel=1e-4)
    assert _closed_form(BAD_EI) > IMPLAUSIBLE_DEFLECTION_FRACTION * L
    assert bad.attrs["flag_codes"].split(",")[0] == "implausible_deflection"  # (first: the likely cause of the rest)
    text = bad.attrs["warnings"]
    assert "in 3 of 3 crossings" in text and IMPLAUSIBLE_DEFLECTION_ADVICE in text
    assert f"L/{L / _four_modes(BAD_EI):.3g}" in text  # the largest as a fraction of the span: L/6.39
    assert "the crossing at crossing.speed_kmh = " in text  # which crossing, by its axis value


def _stream(EI: float, tmp_path, name: str):
    records = [VehicleRecord(time=0.0, direction="+x", speed=20.0, model="moving-force", lane=1, id="f1"),
               VehicleRecord(time=30.0, direction="-x", speed=15.0, model="moving-force", lane=1, id="f2")]
    job = traffic_study(records, _base(EI), lanes=[0.0], seed=3, batch_size=1, name=name)
    assert job.size == 2  # two events of one force each
    return run_study(job, tmp_path / f"{name}.nc", workers=1)


def test_a_traffic_stream_on_a_beam_with_ei_in_kilonewtons_says_so(tmp_path):
    ok = _stream(GOOD_EI, tmp_path, "ok")
    assert -ok["max_static_displacement"].values == pytest.approx(_four_modes(GOOD_EI), rel=1e-4)
    # (no deflection warning; its two events cannot bound the 95 % quantile's interval: that flag alone)
    assert ok.attrs["flag_codes"] == "interval_not_bounded" and "deflection" not in ok.attrs["warnings"]
    bad = _stream(BAD_EI, tmp_path, "bad")
    assert -bad["max_static_displacement"].values == pytest.approx(_four_modes(BAD_EI), rel=1e-4)
    # (its governing events, whose deflections are 1000 times too large, also move at half the step)
    assert bad.attrs["flag_codes"].split(",")[0] == "implausible_deflection"
    text = bad.attrs["warnings"]
    assert "in 2 of 2 events" in text and IMPLAUSIBLE_DEFLECTION_ADVICE in text
    assert f"L/{L / _four_modes(BAD_EI):.3g}" in text


def test_the_study_command_prints_the_dataset_warning(tmp_path, study_toml):
    path = tmp_path / "bad.toml"
    path.write_text(study_toml({"name": "bad", "seed": 1, "batch_size": 2, "base": _base(BAD_EI),
                                "axes": {"crossing.speed_kmh": [40, 80]}}))
    res = runner.invoke(app, ["study", "run", str(path), "--out", str(tmp_path / "bad.nc"), "--workers", "1",
                              "--no-progress"])
    assert res.exit_code == 0, res.output
    assert "warning: implausible static deflection in 2 of 2 crossings" in res.output


def test_the_dataset_rule_is_the_single_run_rule():
    """Span/100 exactly as ``implausible_deflection_flags`` judges it (0.21 m on 20 m flagged, on 22 m
    not), per crossing against its own span; a crossing without a span (NaN) is not judged; the
    largest share names its point."""
    from vbikit.analysis.checks import (Flag, dataset_flag_attrs, dataset_has_flag, implausible_deflection_dataset_flags,
                                        implausible_deflection_flags)

    peaks = np.array([[-0.05, -0.21], [-0.21, -0.01], [-0.9, -0.9]])  # (crossings, points) [m]
    spans = np.array([20.0, 22.0, np.nan])
    (flag,) = implausible_deflection_dataset_flags(peaks, spans, ["a", "b"])
    assert "in 1 of 3 crossings" in flag.message and flag.point == "b"
    assert flag.value == pytest.approx(0.21 / 20.0)
    assert flag.value == implausible_deflection_flags(20.0, [("point b", -0.21, None, "b")])[0].value
    assert implausible_deflection_dataset_flags(peaks[1:2], spans[1:2], ["a", "b"]) == []  # L/105
    small = Flag("small_static", "point a: small")
    attrs = dataset_flag_attrs([flag, small])
    assert attrs["flag_codes"] == "implausible_deflection,small_static"
    assert attrs["warnings"].startswith("implausible static deflection") and attrs["warnings"].endswith("point a: small")
    assert dataset_flag_attrs([]) == {}
    assert dataset_has_flag(attrs, "small_static") and dataset_has_flag(attrs, "implausible_deflection")
    only_small = dataset_flag_attrs([small])
    assert not dataset_has_flag(only_small, "implausible_deflection") and not dataset_has_flag({}, "small_static")
    with pytest.raises(ValueError, match="not one of"):
        dataset_has_flag(attrs, "no_such_code")


def _traffic_cli(ei: float, tmp_path, name: str):
    """``vbikit traffic`` of one moving force on the beam of flexural rigidity ``ei`` (a --bridge file):
    the result and its line of IM statistics."""
    bridge = "\n".join(f"[{k}]\n" + "\n".join(f"{n} = {v!r}".replace("'", '"') for n, v in t.items())
                       for k, t in _base(ei).items() if k != "vehicle")
    (tmp_path / f"{name}.toml").write_text(bridge + "\n")
    res = runner.invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / f"{name}.toml"), "--out",
                              str(tmp_path / f"{name}.nc"), "--lanes", "0", "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    return res, next(x for x in res.output.splitlines() if x.startswith("impact factor of all events"))


def test_the_traffic_command_prints_the_dataset_warning(tmp_path):
    from vbikit.traffic import write_records

    records = [VehicleRecord(time=0.0, direction="+x", speed=20.0, model="moving-force", lane=1, id="f1")]
    write_records(records, tmp_path / "r.csv")
    res, stats = _traffic_cli(BAD_EI, tmp_path, "bad")
    assert "warning: implausible static deflection in 1 of 1 events" in res.output
    assert "mean" in stats and "!" in stats and "! not meaningful: implausible static deflections" in res.output
    res, stats = _traffic_cli(GOOD_EI, tmp_path, "good")
    assert "!" not in stats and "not meaningful" not in res.output and "implausible" not in res.output
