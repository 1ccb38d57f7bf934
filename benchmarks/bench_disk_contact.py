"""How many of the disk tire's contact points a batch of the paper programme evaluates a step, against how many
touch: is the disk's share of the programme waste of the lanes' shared lazy test, or its contact?

    python benchmarks/bench_disk_contact.py                       # Fig. 10, class C, 15 km/h, ≈ 30 s
    python benchmarks/bench_disk_contact.py --figure fig11 --road B --speed 30

One batch of the study (the disk tire, the given road class and speed: its roads as lanes of one
``BatchSolver.run_many`` call, as ``bench_studies.py`` runs them) is simulated; then, from the lanes' own
results (travel, modal and vehicle histories) and the kernels' own inputs (``vbikit.solve.system.kernel_data``:
the Hermite mode tables read by ``tabulate.hermite_rows``, ``Modes.amp``, the points' gaps, wheels and tracks), each step's gated points are
counted, averaged over the steps:

* **loose**: those the many-lane kernel's shared lazy test evaluates, a lane's bound r_p − g_p − z_w + B
  positive in some lane, B = Σ_m amp_m |ξ_m| on the deck (``kernels.lean_lanes._law_lanes``);
* **tight**: the same test with a tighter deck term, the deck under the wheel's middle point u_c plus
  |x_p − x_c| Σ_m s_m |ξ_m| (s_m 1.5 × the largest tabulated slope of mode m: an estimate of what a per-wheel
  bound could reach, not a proven bound);
* **touching**: δ_p = r_p + φ_p·ξ − g_p − z_w > 0 in some lane (the points that must be evaluated), and the
  same per lane (mean over the lanes).

The road elevation under a point is interpolated linearly from its lane's profile, as the kernels do; the
states are those the results store at every step.  Prints the counts; writes nothing.
"""
from __future__ import annotations

import argparse
import logging

import numpy as np


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--figure", default="fig10", choices=("fig10", "fig11"))
    p.add_argument("--road", default="C", help="road class of the batch (default C)")
    p.add_argument("--speed", type=float, default=15.0, help="speed of the batch [km/h] (default 15)")
    args = p.parse_args()
    logging.disable(logging.WARNING)  # (the study's start notices)

    from vbikit.scenario import parse_scenario
    from vbikit.scenario.build import build
    from vbikit.solve.batch import BatchSolver
    from vbikit.solve.system import kernel_data
    from vbikit.solve.tabulate import hermite_rows
    from vbikit.study.compute import _road
    from vbikit.study.paper import paper_study

    study = paper_study(args.figure, 20)
    batch = next(b for b in study.batches() if (d := study.scenario_dict(b[0]))["tire"]["model"] == "disk"
                 and d["road"].get("class") == args.road and d["crossing"]["speed_kmh"] == args.speed)
    dicts = [study.scenario_dict(i) for i in batch]
    scenarios = [parse_scenario(d, study.base_dir) for d in dicts]
    roads = [_road(sc, d) for sc, d in zip(scenarios, dicts)]
    crossing = build(scenarios[0]).crossing
    results = BatchSolver(crossing).run_many(roads)
    data = kernel_data(crossing)
    pts, modes, wheel_rows = data.points, data.modes, data.vehicles.wheel_rows

    xp = pts.origin[None, :] + pts.direction[None, :] * results[0].travel[:, pts.vehicle]  # (n_t, n_cp)
    on = (xp >= modes.start[pts.track][None, :]) & (xp <= modes.end[pts.track][None, :])
    tracks = np.broadcast_to(pts.track, xp.shape).ravel()
    on_track = np.clip(xp.ravel(), modes.start[tracks], modes.end[tracks])  # (the points off the deck: zeroed below)
    phi = hermite_rows(modes.start, modes.grid_h, modes.values, modes.slopes, tracks, on_track,
                       with_slopes=False)[0].reshape(xp.shape + (-1,))
    phi[~on] = 0.0
    slope = 1.5 * np.abs(modes.slopes).max(axis=(0, 1))
    middle = np.zeros(pts.origin.size, int)
    for w in np.unique(pts.wheel):
        members = np.flatnonzero(pts.wheel == w)
        middle[members] = members[members.size // 2]
    gated = pts.gated
    loose = np.zeros(xp.shape, bool)
    tight = np.zeros(xp.shape, bool)
    touch = np.zeros(xp.shape, bool)
    per_lane = []
    for (left, right), res in zip(roads, results):
        r = np.interp(xp, left.x, left.z)
        if right is not None:
            r = np.where(pts.line[None, :] == 0, r, np.interp(xp, right.x, right.z))
        base = r - pts.gap[None, :] - (res.q @ wheel_rows.T)[:, pts.wheel]
        u = np.einsum("tpm,tm->tp", phi, res.xi)
        loose |= base + np.where(on, (np.abs(res.xi) @ modes.amp)[:, None], 0.0) > 0.0
        spread = np.abs(xp - xp[:, middle]) * (np.abs(res.xi) @ slope)[:, None]
        tight |= base + np.where(on, u[:, middle] + spread, 0.0) > 0.0
        lane_touch = base + u > 0.0
        touch |= lane_touch
        per_lane.append(lane_touch[:, gated].sum(axis=1).mean())
    print(f"{args.figure}, disk tire, class {args.road}, {args.speed:g} km/h: {len(results)} lanes, "
          f"{int(gated.sum())} gated points, {results[0].n_steps} steps, {modes.values.shape[2]} modes")
    print(f"  points evaluated a step (mean): shared lazy test {loose[:, gated].sum(axis=1).mean():.1f}, "
          f"with the tighter deck term {tight[:, gated].sum(axis=1).mean():.1f}; touching in some lane "
          f"{touch[:, gated].sum(axis=1).mean():.1f}, in each lane {np.mean(per_lane):.1f}")


if __name__ == "__main__":
    main()
