"""The run-time estimate made once the static pass is done: the events the screening is expected to simulate
against a count by hand, the hours from them, and a run refused there keeping its static pass for the same command
to resume (and a finished run not refused again)."""
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from vbikit.lifetime import run as lifetime_run
from vbikit.lifetime.jobs import EVENT_STRIDE
from vbikit.lifetime.screening import EXPECTED_TOP_AMPLIFICATION, expected_dynamic_events
from vbikit.lifetime.spec import LifetimeError

from .test_cli import _cut_down


def _by_hand(static, signs, block, n_blocks, a, extra) -> set[int]:
    """The events e with (1 + A)·s·R_st,e ≥ (1 + a_top)·max over e' of block(e) of s·R_st,e' for some effect where
    that maximum is positive, the largest of every block and effect, and ``extra``: written as loops over events."""
    keep = set(int(e) for e in extra)
    for j, sign in enumerate(signs):
        for b in range(n_blocks):
            members = [e for e in range(len(block)) if block[e] == b]
            if not members:
                continue
            top = max(sign * static[e, j] for e in members)
            keep.add(max(members, key=lambda e: (sign * static[e, j], -e)))
            if top <= 0:
                continue
            for e in members:
                if (1 + a) * sign * static[e, j] >= (1 + EXPECTED_TOP_AMPLIFICATION) * top:
                    keep.add(e)
    return keep


def _events(seed: int):
    """Two effects of opposite signs (a sagging moment, a hogging one: the rule reads s·R), blocks 0, 1, 3 of unequal
    sizes and block 2 empty, block 3's second effect never loaded its way (0 or the wrong sign), a sample of three."""
    rng = np.random.default_rng(seed)
    n = 400
    block = rng.choice([0, 1, 3], size=n, p=[0.5, 0.3, 0.2])
    static = np.column_stack([rng.lognormal(0.0, 0.4, n), -rng.lognormal(0.0, 0.5, n)])
    static[block == 3, 1] = np.where(rng.random(np.sum(block == 3)) < 0.5, 0.0, 0.1)
    return static, np.array([1.0, -1.0]), block, rng.choice(n, 3, replace=False)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_expected_events_are_those_counted_by_hand(seed):
    """The events equal the loops' (a wrong sign, a bound without the top event's amplification, the sample left
    out or an unloaded effect counting all its zeros would change them); a larger A keeps more."""
    static, signs, block, extra = _events(seed)
    got = expected_dynamic_events(static, signs, block, 4, 0.3, extra)
    assert set(got.tolist()) == _by_hand(static, signs, block, 4, 0.3, extra)
    assert not np.array_equal(got, expected_dynamic_events(static, np.array([1.0, 1.0]), block, 4, 0.3, extra))
    assert expected_dynamic_events(static, signs, block, 4, 0.6, extra).size > got.size


def test_hours_are_the_events_left_at_the_cost_of_one_on_the_workers():
    """``dynamics_estimate`` on a static pass made by hand, 2 workers: the events counted by hand, less those marked
    done, × 0.03 s / 2 workers."""
    static, signs, block, extra = _events(5)
    sample = np.zeros(len(block), np.int8)
    sample[extra] = 1
    index = np.arange(len(block)) * 3 + 1  # (an event's index within its day: not its position in the pass)
    ds = xr.Dataset({"ev_static": (("event", "effect"), static), "ev_day": ("event", block),
                     "ev_index": ("event", index), "ev_sample": ("event", sample)})
    prep = SimpleNamespace(setup=SimpleNamespace(lines=[SimpleNamespace(sign=s) for s in signs]), n_days=4,
                           spec=SimpleNamespace(amplification=0.3), cores=2)
    expected = sorted(_by_hand(static, signs, block, 4, 0.3, extra))
    hours, events = lifetime_run.dynamics_estimate(prep, ds)
    assert events == len(expected)
    assert hours * 3600 == pytest.approx(len(expected) * lifetime_run.DYNAMIC_SECONDS_PER_EVENT / 2, rel=1e-12)
    done = np.isin(np.arange(len(block)), expected[:7])
    assert lifetime_run.dynamics_estimate(prep, ds, done)[1] == len(expected) - 7


def test_a_run_over_budget_after_the_static_pass_stops_there_and_resumes(tmp_path, monkeypatch):
    """When the static peaks give more dynamics than budget_hours allows, the run stops after the static pass with
    a LifetimeError naming budget_hours, the estimate and the events, and the resume note; the static pass is kept
    and the same call, with the estimate within the budget, runs the dynamics from it."""
    spec = _cut_down(tmp_path)
    out = tmp_path / "out"
    many = np.arange(10**7, dtype=np.int64)
    monkeypatch.setattr(lifetime_run, "expected_dynamic_events", lambda *a, **k: many)
    with pytest.raises(LifetimeError, match=r"budget_hours: after the static pass the dynamics are estimated at "
                                            r"[\d.]+ h on 1 worker\(s\) \(about 10,000,000 events") as err:
        lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    assert "run the same command again to resume" in "\n".join(getattr(err.value, "__notes__", []))
    assert (out / "work" / "static.nc").is_file() and not list((out / "work").glob("dynamic-*"))
    stamp = (out / "work" / "static.nc").stat().st_mtime_ns
    monkeypatch.undo()
    ds = lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    assert (out / "work" / "static.nc").stat().st_mtime_ns == stamp  # (read back, not written again)
    assert ds.attrs["n_dynamic_events"] > 0


def test_a_finished_run_is_not_refused_for_dynamics_it_has_done(finished_cut_down, monkeypatch):
    """The check after the static pass on a finished run's work (the cut-down example's, ``finished_cut_down``),
    every event it simulated expected and the cost of one raised a millionfold: not refused, its rounds hold them;
    with one event more expected it is, for that one."""
    spec, out, ds = finished_cut_down.spec, finished_cut_down.out, finished_cut_down.ds
    prep = lifetime_run.prepare(lifetime_run.read_lifetime(spec)[0], finished_cut_down.folder, workers=1)
    with xr.open_dataset(out / "work" / "static.nc") as static:
        static = static.load()
    gid = static["ev_day"].values * EVENT_STRIDE + static["ev_index"].values
    ran = np.flatnonzero(np.isin(gid, lifetime_run.finished_dynamics(out / "work")))
    assert ran.size >= ds.attrs["n_dynamic_events"] > 0
    monkeypatch.setattr(lifetime_run, "DYNAMIC_SECONDS_PER_EVENT", 3600.0 * 1e6)
    monkeypatch.setattr(lifetime_run, "expected_dynamic_events", lambda *a, **k: ran)
    lifetime_run.check_dynamics_budget(prep, static, out / "work")
    other = np.setdiff1d(np.arange(gid.size), ran)[:1]
    monkeypatch.setattr(lifetime_run, "expected_dynamic_events", lambda *a, **k: np.union1d(ran, other))
    with pytest.raises(LifetimeError, match=r"about 1 event the screening keeps"):
        lifetime_run.check_dynamics_budget(prep, static, out / "work")


def test_the_estimate_from_the_static_pass_counts_the_events_the_run_simulates(finished_cut_down):
    """On the cut-down example (a beam; its finished run, ``finished_cut_down``) the estimate's events are of the
    order of those the run simulated: at least half and at most 2.5 times as many (the week-long benchmark runs of
    docs/lifetime.md: 1.06× on the beam, 2.1× on the deck, where the rule's D_b of 1.1 times the top static peak is
    low)."""
    spec, out, ds = finished_cut_down.spec, finished_cut_down.out, finished_cut_down.ds
    with xr.open_dataset(out / "work" / "static.nc") as static:
        prep = lifetime_run.prepare(lifetime_run.read_lifetime(spec)[0], finished_cut_down.folder, workers=1)
        hours, events = lifetime_run.dynamics_estimate(prep, static.load())
    simulated = ds.attrs["n_dynamic_events"]
    assert 0.5 * simulated <= events <= 2.5 * simulated, (events, simulated)


def test_a_raised_screening_bound_is_checked_against_the_budget(tmp_path, monkeypatch):
    """The cut-down example's traffic amplifies an event above its A = 0.6, so the run raises A and screens again;
    when the events the raised bound keeps are estimated above budget_hours the run stops there, naming the
    amplification, both bounds and the estimate, with the rounds run so far kept (the resume note), and the same
    call without that estimate goes on from them to the end."""
    spec = _cut_down(tmp_path)
    out = tmp_path / "out"
    seen = []
    real = lifetime_run.check_rescreen_budget

    def costly(prep, static, bound, given, amplified, simulated):
        seen.append((bound, given, amplified, int(simulated.sum())))
        monkeypatch.setattr(lifetime_run, "DYNAMIC_SECONDS_PER_EVENT", 3600.0 * 1e6)
        return real(prep, static, bound, given, amplified, simulated)

    monkeypatch.setattr(lifetime_run, "check_rescreen_budget", costly)
    with pytest.raises(LifetimeError, match=r"budget_hours: an event's dynamic increment \(IM\) 0\.\d+ exceeded the "
                                            r"screening bound A = 0\.600, and with A raised to \d\.\d+ the dynamics left "
                                            r"are estimated at") as err:
        lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    bound, given, amplified, simulated = seen[0]
    assert given == pytest.approx(0.6) and amplified > given and bound == pytest.approx(1.25 * amplified)
    assert "run the same command again to resume" in "\n".join(getattr(err.value, "__notes__", []))
    rounds = sorted((out / "work").glob("dynamic-*.nc"))
    assert rounds and simulated > 0
    monkeypatch.undo()
    ds = lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    assert ds.attrs["n_dynamic_events"] > simulated


def test_a_resumed_run_is_not_refused_at_the_raised_bound_for_rounds_it_has_finished(tmp_path, monkeypatch):
    """Resumed on its finished work, with every event its rounds hold expected and the cost of one raised a
    millionfold once the bound is raised: the raised bound's check leaves out the rounds after it, which a resumed
    run reads back (a review found it refused 65 events already on disk)."""
    spec = _cut_down(tmp_path)
    out = tmp_path / "out"
    lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    with xr.open_dataset(out / "work" / "static.nc") as static:
        gid = static["ev_day"].values * EVENT_STRIDE + static["ev_index"].values
    ran = np.flatnonzero(np.isin(gid, lifetime_run.finished_dynamics(out / "work")))
    real = lifetime_run.check_rescreen_budget
    raised = []

    def costly(*args):
        raised.append(args[2])
        monkeypatch.setattr(lifetime_run, "DYNAMIC_SECONDS_PER_EVENT", 3600.0 * 1e6)
        return real(*args)

    monkeypatch.setattr(lifetime_run, "expected_dynamic_events", lambda *a, **k: ran)
    monkeypatch.setattr(lifetime_run, "check_rescreen_budget", costly)
    (out / "lifetime.nc").unlink()
    lifetime_run.run_lifetime(spec, out, workers=1, figures=False)
    assert raised  # (the cut-down example raises its bound: the check ran)
