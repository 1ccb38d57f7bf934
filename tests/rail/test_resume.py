"""An interrupted ``vbikit rail`` sweep (kill -9 or Ctrl-C) keeps every finished train and, started
again, resumes to the same dataset as an unbroken run (on main a rail sweep kept nothing: an
interrupted run started from the first train again)."""
import os
import signal
import subprocess
import sys
import time

import pytest
import xarray as xr

from vbikit.rail.run import run_rail

TOML = """[bridge]
span = 20.0
EI = 7.9e10
mass_per_length = 25000.0
[trains]
presets = ["hslm-a"]
[speeds]
min = 150.0
max = 350.0
step = 10.0
[run]
workers = 1
"""
# the CLI as a terminal starts it: SIGINT raises KeyboardInterrupt (a shell's background job starts with SIGINT
# ignored, which Python keeps: Ctrl-C would then not reach the run)
CLI = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler); from vbikit.cli import main; main()"


def _interrupt(tmp_path, sig):
    spec = tmp_path / "rail.toml"
    spec.write_text(TOML)
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-c", CLI, "rail", str(spec), "--out-dir", str(out), "--no-figures",
                             "--no-progress"], start_new_session=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    work = out / "rail.parts"
    deadline = time.time() + 120
    while time.time() < deadline and len(list(work.glob("*.npz"))) < 2 and proc.poll() is None:
        time.sleep(0.005)
    os.killpg(proc.pid, sig)
    _, err = proc.communicate(timeout=60)
    done = sorted(work.glob("*.npz"))
    assert 2 <= len(done) < 10, "the sweep was not interrupted mid-way"
    assert not (out / "rail.nc").exists()
    return spec, out, proc.returncode, err, done


def _same(resumed, unbroken):
    """Every variable and coordinate equal (attributes hold the run time)."""
    xr.testing.assert_equal(resumed, unbroken)
    assert resumed.attrs.keys() == unbroken.attrs.keys()


def _resume_counting(spec, out, monkeypatch):
    """Run the sweep again; the trains it sweeps (not read back) and its result."""
    import vbikit.rail.run as rr

    swept = []
    real = rr.sweep_moving_forces
    monkeypatch.setattr(rr, "sweep_moving_forces", lambda setup, trains, *a: swept.extend(trains) or real(setup, trains, *a))
    resumed = run_rail(spec, out, figures=False)
    monkeypatch.setattr(rr, "sweep_moving_forces", real)
    return swept, resumed


@pytest.mark.slow
def test_kill_9_mid_sweep_keeps_finished_trains_and_resumes_identically(tmp_path, monkeypatch):
    spec, out, code, _, done = _interrupt(tmp_path, signal.SIGKILL)
    assert code == -signal.SIGKILL
    swept, resumed = _resume_counting(spec, out, monkeypatch)
    assert len(swept) == 10 - len(done)  # only the unfinished trains are swept again
    _same(resumed.dataset, run_rail(spec, None, figures=False).dataset)
    assert (out / "rail.nc").is_file() and not (out / "rail.parts").exists()  # finished: the kept trains are removed


@pytest.mark.slow
def test_ctrl_c_exits_130_names_the_resume_and_the_kept_trains_are_reused(tmp_path, monkeypatch):
    spec, out, code, err, done = _interrupt(tmp_path, signal.SIGINT)
    assert code == 130, err
    assert "Traceback" not in err and "run the same command again to resume" in err
    swept, resumed = _resume_counting(spec, out, monkeypatch)
    assert len(swept) == 10 - len(done)
    _same(resumed.dataset, run_rail(spec, None, figures=False).dataset)


def test_a_torn_stored_train_is_swept_again_not_trusted(tmp_path, monkeypatch):
    data = {"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0}, "trains": {"presets": ["hslm-a1", "hslm-a2"]},
            "speeds": {"min": 200.0, "max": 260.0, "step": 20.0}}
    out = tmp_path / "out"
    import vbikit.rail.run as rr

    saved = []
    real_clear = rr._Stored.clear
    monkeypatch.setattr(rr._Stored, "clear", lambda self: saved.extend(sorted(self.work.glob("*.npz"))))
    first = run_rail(data, out, figures=False)
    assert len(saved) == 2
    saved[0].write_bytes(saved[0].read_bytes()[:100])  # a file cut short (a full disk, a foreign copy)
    monkeypatch.setattr(rr._Stored, "clear", real_clear)
    again = run_rail(data, out, figures=False)
    _same(again.dataset, first.dataset)
    assert not (out / "rail.parts").exists()


def test_an_interrupt_after_two_trains_keeps_them_and_the_rerun_sweeps_only_the_rest(tmp_path, monkeypatch):
    """In-process and fast (the subprocess kill -9 / Ctrl-C tests above are slow): Ctrl-C while
    the third train is swept."""
    import vbikit.rail.run as rr

    data = {"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0},
            "trains": {"presets": ["hslm-a1", "hslm-a2", "hslm-a3", "hslm-a4"]}, "speeds": {"min": 200.0, "max": 260.0, "step": 20.0},
            "run": {"workers": 1}}  # (one train a group; the default, all cores, sweeps as many at once as there are cores)
    out = tmp_path / "out"
    real, calls = rr.sweep_moving_forces, []

    def interrupted(setup, trains, *a):
        calls.append(len(trains))
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(setup, trains, *a)

    monkeypatch.setattr(rr, "sweep_moving_forces", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_rail(data, out, figures=False, progress=lambda d, t: None)
    assert len(list((out / "rail.parts").glob("*.npz"))) == 2 and not (out / "rail.nc").exists()
    monkeypatch.setattr(rr, "sweep_moving_forces", real)
    swept, resumed = _resume_counting(data, out, monkeypatch)
    assert [t.name for t in swept] == ["HSLM-A3", "HSLM-A4"]
    _same(resumed.dataset, run_rail(data, None, figures=False).dataset)
