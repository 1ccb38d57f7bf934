"""The run-time estimate made once the static pass is done: the count of events the screening is expected to
simulate against a count by hand, and a run refused there keeping its static pass for the same command to resume."""
import numpy as np
import pytest

from vbikit.lifetime import run as lifetime_run
from vbikit.lifetime.screening import EXPECTED_TOP_AMPLIFICATION, expected_dynamic_events
from vbikit.lifetime.spec import LifetimeError

from .test_cli import _cut_down


def _by_hand(static, signs, block, n_blocks, a, extra):
    """The events e with (1 + A)·s·R_st,e ≥ (1 + a_top)·max over e' of block(e) of s·R_st,e' for some effect,
    the largest of every block and effect, and ``extra``: written as loops over the events."""
    keep = set(int(e) for e in extra)
    for j, sign in enumerate(signs):
        for b in range(n_blocks):
            members = [e for e in range(len(block)) if block[e] == b]
            if not members:
                continue
            top = max(sign * static[e, j] for e in members)
            keep.add(max(members, key=lambda e: (sign * static[e, j], -e)))
            for e in members:
                if (1 + a) * sign * static[e, j] >= (1 + EXPECTED_TOP_AMPLIFICATION) * top:
                    keep.add(e)
    return len(keep)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_expected_events_count_as_by_hand(seed):
    """Two effects of opposite signs (a sagging moment, a hogging one: the rule reads s·R), four blocks of unequal
    sizes, one empty, a sample of three events: the count equals the loops' (and a wrong sign, a bound without the
    top event's amplification or the sample left out would change it)."""
    rng = np.random.default_rng(seed)
    n = 400
    block = rng.choice([0, 1, 3], size=n, p=[0.5, 0.3, 0.2])
    static = np.column_stack([rng.lognormal(0.0, 0.4, n), -rng.lognormal(0.0, 0.5, n)])
    signs = np.array([1.0, -1.0])
    extra = rng.choice(n, 3, replace=False)
    got = expected_dynamic_events(static, signs, block, 4, 0.3, extra)
    assert got == _by_hand(static, signs, block, 4, 0.3, extra)
    assert got != expected_dynamic_events(static, np.array([1.0, 1.0]), block, 4, 0.3, extra)
    assert expected_dynamic_events(static, signs, block, 4, 0.6, extra) > got  # (a larger A keeps more)


def test_a_run_over_budget_after_the_static_pass_stops_there_and_resumes(tmp_path, monkeypatch):
    """When the static peaks give more dynamics than budget_hours allows, the run stops after the static pass with
    a LifetimeError naming budget_hours, the estimate and the events; the static pass is kept, and the same call
    (the budget raised) runs the dynamics without running the static pass again."""
    spec = _cut_down(tmp_path)
    out = tmp_path / "out"
    monkeypatch.setattr(lifetime_run, "expected_dynamic_events", lambda *a, **k: 10**7)
    with pytest.raises(LifetimeError, match=r"budget_hours: after the static pass the dynamics are estimated at "
                                            r"[\d.]+ h on 1 worker\(s\) \(about 10,000,000 events") as err:
        lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    assert "run the same command again to resume" in "\n".join(getattr(err.value, "__notes__", []))
    assert (out / "work" / "static.nc").is_file() and not list((out / "work").glob("dynamic-*"))
    monkeypatch.undo()
    ran = []
    real = lifetime_run.Prepared.static_job

    def counted(self):
        job = real(self)
        ran.append(job)
        return job

    monkeypatch.setattr(lifetime_run.Prepared, "static_job", counted)
    stamp = (out / "work" / "static.nc").stat().st_mtime_ns
    ds = lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    assert (out / "work" / "static.nc").stat().st_mtime_ns == stamp  # (read back, not written again)
    assert ds.attrs["n_dynamic_events"] > 0


def test_the_estimate_from_the_static_pass_counts_the_events_the_run_simulates(tmp_path):
    """On the cut-down example the estimate's count is of the order of the events the run simulated: at least
    half of them and at most four times as many (the week-long benchmark runs: 1.06× on the beam, 2.1× on the deck)."""
    spec = _cut_down(tmp_path)
    out = tmp_path / "out"
    ds = lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    import xarray as xr

    with xr.open_dataset(out / "work" / "static.nc") as static:
        prep = lifetime_run.prepare(lifetime_run.read_lifetime(spec)[0], tmp_path)
        hours, events = lifetime_run.dynamics_estimate(prep, static.load())
    simulated = ds.attrs["n_dynamic_events"]
    assert 0.5 * simulated <= events <= 4 * simulated, (events, simulated)
    assert hours == pytest.approx(events * lifetime_run.DYNAMIC_SECONDS_PER_EVENT / 3600)
