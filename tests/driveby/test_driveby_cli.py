"""`vbikit driveby` end to end (a cut-down of examples/driveby/DRIVEBY.toml through the CLI), the
dataset contract, resumption, and errors naming keys."""
from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vbikit.driveby.spec import DriveByError, parse_driveby
from vbikit.driveby.study import check_cases, run_driveby

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "driveby" / "DRIVEBY.toml"
F1 = (math.pi / 25.0) ** 2 * math.sqrt(2.4e10 / 4800.0) / (2 * math.pi)  # closed form of the example's span, 5.6199 Hz


def _cut_down(tmp_path: Path) -> Path:
    text = EXAMPLE.read_text().replace('speed = [5.0, 8.0, 10.0]', 'speed = [8.0]').replace(
        'road_class = ["none", "A"]', 'road_class = ["none"]')
    path = tmp_path / "DRIVEBY.toml"
    path.write_text(text)
    return path


def test_cli_writes_the_dataset_contract(tmp_path, summary_on_stdout):
    path = _cut_down(tmp_path)
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.run([sys.executable, "-c", "from vbikit.cli import main; main()", "driveby", str(path), "--out-dir", str(out), "--no-progress"],
                          capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stderr
    import xarray as xr

    with xr.open_dataset(out / "driveby.nc") as ds:
        assert ds.sizes["case"] == 2
        f_id = ds["identified_frequency_hz"].values
        f_true = ds["bridge_frequency_hz"].values
        assert f_true[0] == pytest.approx(F1, rel=1e-6)  # healthy span: the closed form (40 Hermite elements)
        assert np.all(np.abs(f_id / f_true - 1) < 0.01)  # smooth road, 8 m/s
        assert ds["damage_severity"].values.tolist() == [0.0, 0.3]
        assert ds["identified_frequency_shift"].values[1] < 0
        assert ds["sensor_history"].shape[:2] == (2, 1)
        assert ds["mode_shape_squared"].shape == (2, 41)
        assert np.nanmax(ds["mode_shape_squared"].values) == pytest.approx(1.0, abs=0.05)
        assert ds["mode_shape_mac"].values[0] == pytest.approx(1.0)  # the healthy case against itself
        assert 0.9 < ds["mode_shape_mac"].values[1] <= 1.0
        assert ds["identified_frequency_hz"].attrs["units"] == "Hz"
        # one acceleration sensor: its records and noise in its unit, CF spelled (a trial found "see sensor_units" and
        # "sensor unit", which no unit parser reads)
        assert ds["sensor_units"].values.tolist() == ["m s-2"]
        assert ds["sensor_history"].attrs["units"] == ds["noise_std"].attrs["units"] == ds["noise_rms"].attrs["units"] == "m s-2"
    for name in ("driveby-report.txt", "driveby-summary.json", "driveby-spectrogram.png", "driveby-frequency-vs-speed.png", "driveby-damage.png"):
        assert (out / name).is_file(), name
    # it says what it wrote, one line a file, as every command that writes a folder
    wrote = sorted(line.removeprefix("wrote ") for line in proc.stdout.splitlines() if line.startswith("wrote "))
    assert wrote == sorted(str(out / n) for n in ("driveby.nc", "driveby-report.txt", "driveby-summary.json",
                                                  "driveby-spectrogram.png", "driveby-frequency-vs-speed.png",
                                                  "driveby-damage.png"))
    # --json (the finished cases read back): the summary's object alone on standard output, the report on stderr
    summary_on_stdout(["driveby", str(path), "--out-dir", str(out), "--no-progress", "--no-figures"],
                      out / "driveby-summary.json")


def test_python_entry_point_resumes_an_interrupted_sweep(tmp_path):
    from vbikit._toml import read_toml

    data = read_toml(_cut_down(tmp_path), DriveByError)
    data["batch_size"] = 1
    spec = parse_driveby(data, EXAMPLE.parent)
    from vbikit.driveby.study import DriveByStudy
    from vbikit.study.run import spec_checksum
    from vbikit.study.storage import parts_dir, save_part
    from vbikit._files import write_text

    job = DriveByStudy(spec)
    out = tmp_path / "py"
    parts = parts_dir(out / "driveby.nc")
    parts.mkdir(parents=True)
    write_text(parts / "study.json", job.to_json())
    first = job.run_batch((0,))
    save_part(parts, 0, first, spec_checksum(job))  # as if the run had been killed after batch 0
    ds = run_driveby(spec, out, figures=False)
    assert ds["identified_frequency_hz"].values[0] == first["identified_frequency_hz"][0]
    fresh = run_driveby(spec, tmp_path / "fresh", figures=False)
    assert np.array_equal(fresh["identified_frequency_hz"].values, ds["identified_frequency_hz"].values)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["sweep"].update(speed=[8.0, "fast"]), r"sweep\.speed: expected a number in \[0\.001, 300\] \[m/s\], got str .fast."),
    (lambda d: d["sensors"][0].update(body="roof"), r"sensors\.cart_acc\.body: 'roof'"),
    (lambda d: d["identification"].update(sensor="gyro"), r"identification\.sensor: 'gyro'"),
    (lambda d: d["bridge"].update(EI=-1.0), r"bridge\.EI"),
    (lambda d: d.update(max_steps=100), r"max_steps: the sweep needs about"),
    (lambda d: d["sweep"].update(damage_severity=[0.0, 1.5]), r"sweep\.damage_severity"),
    (lambda d: d.update(colour="red"), r"colour: unknown key"),
])
def test_errors_name_the_key_before_any_computation(change, message):
    from vbikit._toml import read_toml

    data = read_toml(EXAMPLE, DriveByError)
    change(data)
    with pytest.raises(DriveByError, match=message):
        check_cases(parse_driveby(data, EXAMPLE.parent))


def test_example_finishes_quickly_and_identifies_on_smooth_roads(tmp_path):
    """The whole example (12 cases) in-process: ≈ 3 s on one core (measured 2026-12-02)."""
    ds = run_driveby(EXAMPLE, tmp_path, figures=False)
    smooth = ds["road_class"].values == "none"
    assert np.all(np.abs(ds["frequency_error"].values[smooth]) < 0.01)
