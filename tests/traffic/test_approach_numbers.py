"""docs/traffic.md's "Start from rest and the approach" quotes docs/figures/approach-numbers.json, which
docs/scripts/approach_numbers.py computes (recomputed here in a slow test): the one-truck events' IM
statistics with the default 10 m approach against 100 m (and 200 m, the convergence), and the default approach
after a 90 m run-in (crossing.run_in) against 100 m, and how far the trucks must have driven (on Bridge 2 and on
beams of 15, 40 and 60 m)."""
from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
STORED = json.loads((ROOT / "docs" / "figures" / "approach-numbers.json").read_text())
PAGE = re.sub(r"\s+", " ", (ROOT / "docs" / "traffic.md").read_text())
HINT = "run python docs/scripts/approach_numbers.py and update docs/traffic.md"


def quoted() -> list[str]:
    b, c, r = STORED["B"], STORED["C"], STORED["run_in"]
    d, conv, dc = b["100_minus_10"], b["200_minus_100"], c["100_minus_10"]
    return [f"on the {b['events']} first one-truck events",
            f"is {b['im']['10']['mean']:.4f} with the 10 m approach against {b['im']['100']['mean']:.4f} with 100 m",
            f"difference {d['mean']:+.4f} ± {d['se']:.4f}, standard error; per event {d['rms']:.3f} root mean square",
            f"the 95th percentile {b['im']['10']['q95']:.4f} against {b['im']['100']['q95']:.4f}",
            f"with 200 m the mean is {b['im']['200']['mean']:.4f} (difference to 100 m {conv['mean']:+.4f} ± "
            f"{conv['se']:.4f}, per event {conv['rms']:.4f} root mean square)",
            f"On class C ({c['events']} events): mean {c['im']['10']['mean']:.4f} against {c['im']['100']['mean']:.4f} "
            f"(difference {dc['mean']:+.4f} ± {dc['se']:.4f}), 95th percentile {c['im']['10']['q95']:.4f} against "
            f"{c['im']['100']['q95']:.4f}",
            f"same {r['events']} class {r['road_class']} events the mean IM is then {r['im']['mean']:.4f} and the 95th "
            f"percentile {r['im']['q95']:.4f}, against the 100 m approach run coupled all the way: the IMs differ by "
            f"{r['minus_100']['rms']:.1e} root mean square, {r['minus_100']['max']:.1e} at most",
            f"the coupled run keeps the default's steps ({r['mean_steps']:,} on average)",
            f"crossing.run_in = {r['run_in_m']:g}",
            *_settling(), _spans(), *_transients()]


def _lighter() -> str:
    """The sentence on ``lighter_damped``: a vehicle outside the checked range."""
    ld = STORED["lighter_damped"]
    kept, d = ld["left_at_100_m"], ld["minus_400"]
    return (f"the {ld['preset']} preset in place of every truck (`lighter_damped`) keeps {kept['min']:g}–{kept['max']:g} of "
            f"its transient after 100 m ({kept['mean']:g} on average), and its {ld['events']} first one-vehicle events' IMs "
            f"differ from a 400 m start by {d['rms']:.2g} root mean square ({d['max']:.2g} at most)")


def test_a_vehicle_the_flag_names_does_err():
    """The lighter damped preset keeps more than SETTLED_TRANSIENT_LEFT after 100 m on every event, and its IMs err
    by more than the checked trucks' do at any share they kept up to 0.5: the flag marks real errors."""
    from vbikit.solve.run_in import SETTLED_TRANSIENT_LEFT

    ld = STORED["lighter_damped"]
    assert ld["left_at_100_m"]["min"] > SETTLED_TRANSIENT_LEFT
    assert ld["minus_400"]["rms"] > max(b["rms"] for b in STORED["transient_effect"]["bins"] if b["left"][1] <= 0.5)


def _transients() -> list[str]:
    """The sentences on the share of its start transient a truck keeps (``checked_transients``,
    ``transient_effect``) and the limit the start_unsettled flag reads (``SETTLED_TRANSIENT_LEFT``)."""
    from vbikit.solve.run_in import SETTLED_TRANSIENT_LEFT

    c, t = STORED["checked_transients"], STORED["transient_effect"]
    lo, hi = c["slowest_decay_rate_per_s"]
    kept = c["transient_left_at_100_m"]
    bins = {tuple(b["left"]): b for b in t["bins"]}
    shares = "; ".join(f"{b['left'][0]:g}–{b['left'][1]:g}: {b['rms']:.2g} ({b['max']:.2g} at most, {b['events']} runs)"
                       for b in t["bins"] if b["events"] >= 30)
    assert (0.0, 0.035) in bins and (0.035, 0.07) in bins  # (the page's reading at the limit)
    return [f"The {c['events']:,} one-truck events above that drove 100 m in all", f"have σ_min {lo:g}–{hi:g} per second and keep "
            f"{kept['mean']:g} of it on average, {kept['max']:g} at most",
            f"its root mean square by the share kept is {shares}",
            _lighter(),
            f"`SETTLED_TRANSIENT_LEFT` = {SETTLED_TRANSIENT_LEFT:g}"]


def _spans() -> str:
    """The sentence on the beams of ``settling_spans`` (SETTLED_APPROACH on other bridges)."""
    g = STORED["settling_spans"]
    lo, hi = g["slowest_truck_mode_hz"]
    cases = "; ".join(f"{c['span_m']:g} m at {c['f1_hz']:g} Hz, class {c['road_class']}: mean {c['minus_400']['100']['mean']:.2g} "
                      f"± {c['minus_400']['100']['se']:.2g}, per event {c['minus_400']['100']['rms']:.2g} root mean square "
                      f"({c['minus_400']['100']['max']:.2g} at most)" for c in g["cases"])
    worst = max(c["minus_400"]["50"]["rms"] for c in g["cases"])
    return (f"the trucks' slowest modes the road excites ({lo:g}–{hi:g} Hz), {g['cases'][0]['events']} one-truck events each, "
            f"100 m in all against 400 m: {cases}. With 50 m each event's IM still differs by up to {worst:.2g} root "
            "mean square")


def _settling() -> list[str]:
    g = STORED["settling"]
    d = g["minus_200"]
    totals = [f"{t:g}" for t in g["totals_m"][:-1]]
    return [f"{', '.join(totals[:-1])} and {totals[-1]} m in all against 200 m on the same events: the mean IM differs by "
            + ", ".join(f"{d[t]['mean']:.2g} ± {d[t]['se']:.2g}" for t in totals[:-1]) + f" and {d[totals[-1]]['mean']:.2g} ± "
            f"{d[totals[-1]]['se']:.2g}, each event's by " + ", ".join(f"{d[t]['rms']:.2g}" for t in totals[:-1])
            + f" and {d[totals[-1]]['rms']:.2g} root mean square (" + ", ".join(f"{d[t]['max']:.2g}" for t in totals[:-1])
            + f" and {d[totals[-1]]['max']:.2g} at most)"]


def test_the_page_quotes_the_stored_numbers():
    missing = [q for q in quoted() if q not in PAGE]
    assert not missing, f"{missing}: {HINT}"


def test_the_stored_numbers_say_what_the_page_concludes():
    """The 10 m approach's mean IM lies more than three standard errors below the 100 m one on class B,
    and 100 m has converged (200 m within 0.001 on the mean): if a change of the start made either
    false, the page's advice would be wrong."""
    b = STORED["B"]
    assert b["100_minus_10"]["mean"] > 3 * b["100_minus_10"]["se"]
    assert abs(b["200_minus_100"]["mean"]) < 1e-3 and b["200_minus_100"]["rms"] < 0.1 * b["100_minus_10"]["rms"]
    g = STORED["settling"]["minus_200"]  # SETTLED_APPROACH: each event's IM settled by 100 m, not by 50 m
    assert g["100"]["rms"] < 0.005 < g["50"]["rms"] and abs(g["100"]["mean"]) < 3 * g["100"]["se"] + 1e-4
    for case in STORED["settling_spans"]["cases"]:  # and so on beams above, on and below the trucks' body modes
        d = case["minus_400"]["100"]
        assert d["rms"] < 0.005 and d["max"] < 0.02 and abs(d["mean"]) < 3 * d["se"] + 1e-4, case
    from vbikit.solve.run_in import SETTLED_APPROACH

    assert SETTLED_APPROACH == 100.0
    r = STORED["run_in"]  # the run-in reaches the 100 m approach's IMs at the default's coupled steps
    assert r["minus_100"]["max"] < 1e-3 and r["minus_100"]["rms"] < 0.01 * b["100_minus_10"]["rms"]
    assert r["mean_steps"] == b["mean_steps"]["10"]


@pytest.mark.slow
def test_the_script_reproduces_the_stored_numbers():
    spec = importlib.util.spec_from_file_location("approach_numbers", ROOT / "docs" / "scripts" / "approach_numbers.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    _close(module.compute(), STORED, "")


def _close(now, stored, where: str) -> None:
    """Equal, numbers to 2e-4 (the stored ones are rounded to four decimals: a last digit may round the
    other way on another machine's floating point)."""
    if isinstance(stored, dict):
        assert set(now) == set(stored), f"{where}: {HINT}"
        for k in stored:
            _close(now[k], stored[k], f"{where}.{k}")
    elif isinstance(stored, (int, float)) and not isinstance(stored, bool):
        assert now == pytest.approx(stored, abs=2e-4, rel=1e-3), f"{where}: {HINT}"
    else:
        assert now == stored, f"{where}: {HINT}"
