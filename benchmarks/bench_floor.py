"""The demo crossing against its floor: what the arithmetic of a crossing costs without anything else.

    python benchmarks/bench_floor.py               # ≈ 30 s with a warm numba cache
    python benchmarks/bench_floor.py --repeat 21

The floor is a minimal numba loop (``floor_loop`` below, written for this script) that does a
crossing's arithmetic once a step with the library's own inputs — the mode-shape tables along the
wheel tracks, the exact modal and vehicle step maps, the contact points and the road that
``vbikit.solve.simulate`` hands to its kernel (captured from one ``simulate`` call): per step the
point positions, the free deck and vehicle responses, the modal load and end-of-step state of the
extrapolated contact forces, **one contact-law evaluation** (mode shapes by cubic Hermite, road by
linear interpolation and its rate as the secant over the step, as the library reads it; deck displacement, velocity and convective rate, the tire law with its
gate), one quasi-Newton update of the forces through the vehicles (a factorisation made once,
before the loop), the end state and the stored histories.  No Python per step, no checks, one lane.

Reported, each as thread CPU time (``time.thread_time``, robust to other load on a shared
machine), minimum of ``--repeat`` runs after a warm-up:

* **kernel**: the library's full step loop (``kernels.implicit``, generic over lanes) inside
  ``simulate`` (``integrators.USE_LEAN`` off);
* **lean**: the one-lane step loop ``simulate`` runs by default (``kernels.lean_quadratic``, the variant
  the default integrator names, ``_args.default_step_loops``; it hands a
  crossing to ``kernels.implicit`` only at a step it does not take — none here);
* **whole**: what ``vbikit run`` does for the crossing — ``simulate`` (default: lean) and the
  response point's history with its static reference and impact factor;
* **floor**: ``floor_loop`` on the same inputs;
* **lanes**: the crossing on 32 roads (the demo road scaled by 0.5 … 1.5) as lanes of one call
  (``BatchSolver.run_many``, the batched studies' runner): the many-lane lean kernel
  (``kernels.lean_lanes_quadratic``, default) and the many-lane ``kernels.implicit`` (``USE_LEAN`` off), each
  per crossing (the call's time / 32);

and the ratios kernel / floor, whole / floor and lanes / floor, with the floor's midspan displacement against
the library's (max difference / peak: the floor solves the same equations, one update a step).

* **traffic lanes** (``--traffic-lanes N``, default 6; 0: skip): the first N one-truck events of
  ``bench_traffic.py``'s stream, each event's truck on 32 roads (its road scaled by 0.5 … 1.5) as lanes of
  one call (``BatchSolver.run_many``: ``kernels.lean_lanes_quadratic``) against the event alone (``simulate``:
  ``kernels.lean_quadratic``), kernel time per crossing: what running a stream's events as lanes of one kernel
  could gain at best — lanes that share the motion, shapes and steps, which events of a stream do not
  (each has its own truck, speed and step).

Then every workload of ``bench_per_crossing.py`` named by ``--workloads`` (default: demo via
``vbikit.run``, the 3D example, the Fig. 10 32-lane batches of each tire, a traffic event, a lifetime
dynamic event; ``paper`` on request) against its own floor, per crossing or event: the workload's
whole round (default kernels) against ``floor_loop`` run on the inputs of every kernel call of a
round (lane 0 of each call, counted once per lane).  The floor evaluates every contact point once
a step, gated or not, so a disk tire's 366 points make its floor large.

The case is the ``vbikit demo`` scenario: HS20-44 on the 16.76 m beam (20 modes), multipoint
tire n = 6 (36 contact points), ISO class C road, 75 km/h, exact modal stepping at the automatic
step (1,914 steps).
"""
from __future__ import annotations

import copy
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402

#: the workloads of ``bench_per_crossing.py`` set against their floors by default (``paper``, the
#: whole programme at 3 profiles, only on request: it takes minutes)
WORKLOADS = ("demo", "3d", "fig10-32", "traffic", "lifetime")


def _floor_loop():
    """The compiled floor (built on first use, so that ``--cold`` applies before numba loads)."""
    import numpy as np
    from numba import njit

    @njit(cache=True, fastmath=True, error_model="numpy")
    def floor_loop(travel, speed, modes_start, modes_end, grid_h, values, slopes, a11, a12, a21, a22, b1, b2, c1, c2,
                   d1, d2, transition, load0, load_past, constant, settle, response, wheel_q, wheel_v, wheel_rows, wheel_k, wheel_c, v_inv,
                   origin, direction, vehicle, track, line, kk, cc, f0, gap, gated, wheel, stations, elevations, span,
                   x0, v0, z0, fstart, xi_out, q_out, wf_out):
        n_steps = xi_out.shape[0] - 1
        n_m = x0.size
        n_cp = origin.size
        n_w = wheel_rows.shape[0]
        n_d = wheel_rows.shape[1]
        n_grid = values.shape[1]
        n_s = stations.size
        x = x0.copy(); v = v0.copy(); z = z0.copy()
        p0 = np.zeros(n_m); p = np.zeros(n_m); pm = np.zeros(n_m)  # (pm: the deck's load a step before, the hold)
        xf = np.zeros(n_m); vf = np.zeros(n_m); x1 = np.zeros(n_m); v1 = np.zeros(n_m)
        zf = np.zeros(2 * n_d); zb = np.zeros(2 * n_d); z1 = np.zeros(2 * n_d)
        g0 = np.zeros(n_w); gm = np.zeros(n_w); fw = np.zeros(n_w); bq = np.zeros(n_w); bv = np.zeros(n_w); t = np.zeros(n_w)
        f = fstart.copy(); fo = fstart.copy(); fp = fstart.copy(); law = np.zeros(n_cp)
        phi = np.zeros((n_cp, n_m)); dphi = np.zeros((n_cp, n_m)); onb = np.zeros(n_cp, np.bool_)
        xp = np.zeros(n_cp); vxp = np.zeros(n_cp); idx = np.zeros(n_cp, np.int64)
        for k in range(n_cp):  # the initial wheel loads G = F + k_w z_w + c_w ż_w
            g0[wheel[k]] += f[k]
        for w in range(n_w):
            for j in range(n_d):
                g0[w] += wheel_rows[w, j] * (wheel_k[w] * z[j] + wheel_c[w] * z[n_d + j])
            gm[w] = g0[w]  # (the wheel loads before the start: held at the start's, as the library's hold)
        for n in range(n_steps):
            row = 2 * n + 2
            for k in range(n_cp):  # positions and mode shapes (cubic Hermite)
                xp[k] = origin[k] + direction[k] * travel[row, vehicle[k]]
                vxp[k] = direction[k] * speed[row, vehicle[k]]
                tr = track[k]
                onb[k] = modes_start[tr] <= xp[k] <= modes_end[tr]
                if onb[k]:
                    u = (xp[k] - modes_start[tr]) / grid_h
                    i = min(int(u), n_grid - 2)
                    s = u - i
                    s2 = s * s
                    s3 = s2 * s
                    h00 = 2 * s3 - 3 * s2 + 1
                    h10 = (s3 - 2 * s2 + s) * grid_h
                    h01 = -2 * s3 + 3 * s2
                    h11 = (s3 - s2) * grid_h
                    d00 = (6 * s2 - 6 * s) / grid_h
                    d10 = 3 * s2 - 4 * s + 1
                    d11 = 3 * s2 - 2 * s
                    for m in range(n_m):
                        va = values[tr, i, m]
                        vb = values[tr, i + 1, m]
                        sa = slopes[tr, i, m]
                        sb = slopes[tr, i + 1, m]
                        phi[k, m] = h00 * va + h10 * sa + h01 * vb + h11 * sb
                        dphi[k, m] = d00 * (va - vb) + d10 * sa + d11 * sb
            for m in range(n_m):  # free deck response
                xf[m] = a11[m] * x[m] + a12[m] * v[m] + b1[m] * p0[m] + d1[m] * pm[m]
                vf[m] = a21[m] * x[m] + a22[m] * v[m] + b2[m] * p0[m] + d2[m] * pm[m]
                pm[m] = p0[m]
            for i in range(2 * n_d):  # free vehicle response, then settled on the nominal tires
                a = constant[i]
                for j in range(2 * n_d):
                    a += transition[i, j] * z[j]
                for w in range(n_w):  # (+ the wheel loads a step before: the library's quadratic hold, Lp ≠ 0)
                    a += load0[i, w] * g0[w] + load_past[i, w] * gm[w]
                zf[i] = a
            for i in range(2 * n_d):
                a = 0.0
                for j in range(2 * n_d):
                    a += settle[i, j] * zf[j]
                zb[i] = a
            for k in range(n_cp):  # first guess: linear extrapolation
                f[k] = 2.0 * fo[k] - fp[k]
            for it in range(2):  # it 0: the state of the guess; it 1: the end state of the updated forces
                for m in range(n_m):
                    p[m] = 0.0
                for w in range(n_w):
                    fw[w] = 0.0
                for k in range(n_cp):
                    fw[wheel[k]] += f[k]
                    if onb[k]:
                        for m in range(n_m):
                            p[m] -= phi[k, m] * f[k]
                for m in range(n_m):
                    x1[m] = xf[m] + c1[m] * p[m]
                    v1[m] = vf[m] + c2[m] * p[m]
                for i in range(2 * n_d):
                    a = zb[i]
                    for w in range(n_w):
                        a += response[i, w] * fw[w]
                    z1[i] = a
                if it == 1:
                    break
                for k in range(n_cp):  # the one contact-law evaluation
                    w = wheel[k]
                    zw = 0.0
                    dzw = 0.0
                    for j in range(n_d):
                        zw += wheel_rows[w, j] * z1[j]
                        dzw += wheel_rows[w, j] * z1[n_d + j]
                    xk = xp[k]
                    i = idx[k]
                    while i < n_s - 2 and stations[i + 1] <= xk:
                        i += 1
                    while i > 0 and stations[i] > xk:
                        i -= 1
                    idx[k] = i
                    zr = elevations[line[k]]
                    slope = (zr[i + 1] - zr[i]) / (stations[i + 1] - stations[i])
                    s = zr[i] + slope * (xk - stations[i])
                    sd = slope * vxp[k]
                    if span > 0.0:  # the implicit integrators' road rate: the secant over x ± |v| span
                        a = abs(vxp[k]) * span
                        ia = i
                        while ia > 0 and stations[ia] > xk - a:
                            ia -= 1
                        ib = i
                        while ib < n_s - 2 and stations[ib + 1] <= xk + a:
                            ib += 1
                        ra = zr[ia] + (zr[ia + 1] - zr[ia]) * (xk - a - stations[ia]) / (stations[ia + 1] - stations[ia])
                        rb = zr[ib] + (zr[ib + 1] - zr[ib]) * (xk + a - stations[ib]) / (stations[ib + 1] - stations[ib])
                        sd = vxp[k] * (rb - ra) / (2.0 * a)
                    dr = 0.0
                    if onb[k]:
                        for m in range(n_m):
                            s += phi[k, m] * x1[m]
                            dr += phi[k, m] * v1[m]
                            sd += vxp[k] * dphi[k, m] * x1[m]
                    pen = s - gap[k] - zw
                    fl = kk[k] * pen + cc[k] * (sd + dr - dzw) + f0[k]
                    law[k] = fl if not gated[k] or (pen > 0.0 and fl > 0.0) else 0.0
                for w in range(n_w):  # one quasi-Newton update through the vehicles: (I + S U) t = S b
                    aq = 0.0
                    av = 0.0
                    for w2 in range(n_w):
                        aq += wheel_q[w, w2] * fw[w2]
                        av += wheel_v[w, w2] * fw[w2]
                    bq[w] = aq
                    bv[w] = av
                    t[w] = 0.0
                for k in range(n_cp):
                    t[wheel[k]] += law[k] + kk[k] * bq[wheel[k]] + cc[k] * bv[wheel[k]]
                for w in range(n_w):
                    a = 0.0
                    for w2 in range(n_w):
                        a += v_inv[w, w2] * t[w2]
                    fw[w] = a
                for w in range(n_w):
                    aq = 0.0
                    av = 0.0
                    for w2 in range(n_w):
                        aq += wheel_q[w, w2] * fw[w2]
                        av += wheel_v[w, w2] * fw[w2]
                    bq[w] -= aq
                    bv[w] -= av
                for k in range(n_cp):
                    on = law[k] != 0.0 or not gated[k]
                    f[k] = law[k] + kk[k] * bq[wheel[k]] + cc[k] * bv[wheel[k]] if on else 0.0
            for w in range(n_w):  # end of step: wheel loads, outputs, shift
                gm[w] = g0[w]
                g0[w] = fw[w]
                for j in range(n_d):
                    g0[w] += wheel_rows[w, j] * (wheel_k[w] * z1[j] + wheel_c[w] * z1[n_d + j])
                wf_out[n + 1, w] = fw[w]
            for m in range(n_m):
                x[m] = x1[m]
                v[m] = v1[m]
                p0[m] = p[m]
                xi_out[n + 1, m] = x1[m]
            for i in range(2 * n_d):
                z[i] = z1[i]
            for j in range(n_d):
                q_out[n + 1, j] = z1[j]
            for k in range(n_cp):
                fp[k] = fo[k]
                fo[k] = f[k]

    return floor_loop


def floor_inputs(args: tuple):
    """The floor's arguments from one captured ``kernels.implicit`` call (lane 0), and its outputs."""
    import numpy as np

    (dt, motion, modes, vehicles, points, road, unilateral, step, vstep, xi, dxi, q, dq, ddxi, ddq, wheel_force,
     wheel_len) = args[:17]  # (then the hold's loads before the start, resume, x_past, tol, iterations, lanes, stride)
    # the road rate's secant half-width [s] of the steps (the captured call's span is negative: it starts at the
    # run's start, whose state the floor takes as given)
    span = abs(float(args[25])) if len(args) > 25 else 0.0
    n_w = vehicles.wheel_rows.shape[0]
    ksum = np.bincount(points.wheel, weights=points.stiffness, minlength=n_w)
    csum = np.bincount(points.wheel, weights=points.damping, minlength=n_w)
    v_inv = np.linalg.inv(np.eye(n_w) + ksum[:, None] * vstep.wheel_q + csum[:, None] * vstep.wheel_v)
    gated = points.gated | (bool(unilateral) & (points.stiffness > 0.0))
    n_t = motion.travel.shape[0] // 2 + 1
    outs = (np.zeros((n_t, xi.shape[2])), np.zeros((n_t, q.shape[2])), np.zeros((n_t, n_w)))
    c = np.ascontiguousarray
    fstart = np.zeros(points.origin.size)  # the static start's point forces: its wheel loads spread by stiffness
    for k in range(points.origin.size):
        w = points.wheel[k]
        fstart[k] = wheel_force[0, 0, w] * points.stiffness[k] / ksum[w] if ksum[w] > 0 else 0.0
    inputs = (c(motion.travel), c(motion.speed), modes.start, modes.end, modes.grid_h, modes.values, modes.slopes,
              step.a11, step.a12, step.a21, step.a22, step.b1, step.b2, step.c1, step.c2, step.d1, step.d2, vstep.transition,
              vstep.load0, np.ascontiguousarray(vstep.load_past), vstep.constant, vstep.settle, vstep.response, vstep.wheel_q, vstep.wheel_v,
              vehicles.wheel_rows, vehicles.wheel_stiffness, vehicles.wheel_damping, v_inv, points.origin,
              points.direction, points.vehicle, points.track, np.minimum(points.line, road.elevations.shape[0] - 1),
              points.stiffness, points.damping,
              points.fixed_load, points.gap, gated, points.wheel, road.stations, c(road.elevations[:, :, 0]), span,
              c(xi[0, 0]), c(dxi[0, 0]), np.concatenate([q[0, 0], dq[0, 0]]), fstart)
    return inputs, outs


def workload_floor(name: str, repeat: int) -> dict:
    """One workload of ``bench_per_crossing.py`` (``_workload``) against its floor, per crossing or
    event [ms]: ``whole`` = its round with the default kernels (min of ``repeat``, thread CPU time)
    divided by its crossings; ``floor`` = ``floor_loop`` on lane 0 of every kernel call of one
    round (captured with ``USE_LEAN`` off, so that each call hands ``kernels.implicit`` its
    inputs), counted once per lane of that call, divided by the same crossings.  A study batch's
    lanes differ only in their roads, so lane 0 stands for each of them."""
    from bench_per_crossing import _workload

    from vbikit.solve import integrators, kernels

    run, n = _workload(name)
    run()  # warm-up: compile or load the kernels, build the caches
    whole = []
    for _ in range(repeat):
        t0 = time.thread_time()
        run()
        whole.append(time.thread_time() - t0)
    calls: list[tuple] = []
    original = kernels.implicit

    def capture(*a, **k):
        calls.append(a)
        return original(*a, **k)

    kernels.implicit = capture
    integrators.USE_LEAN = False
    try:
        run()
    finally:
        kernels.implicit = original
        integrators.USE_LEAN = True
    floor_loop = _floor_loop()
    floor = 0.0
    points = []
    for a in calls:
        inputs, outs = floor_inputs(a)
        floor_loop(*inputs, *outs)  # compiled (or loaded) for these argument types
        t = []
        for _ in range(repeat):
            t0 = time.thread_time()
            floor_loop(*inputs, *outs)
            t.append(time.thread_time() - t0)
        floor += min(t) * a[9].shape[0]  # xi: (lanes, rows, modes)
        points.append(inputs[29].size)
    return {"workload": name, "whole_ms": min(whole) / n * 1e3, "floor_ms": floor / n * 1e3, "crossings": n,
            "calls": len(calls), "points": (min(points), max(points)) if points else (0, 0)}


def main() -> None:
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workloads", nargs="*", default=list(WORKLOADS),
                        help="bench_per_crossing.py workloads to set against their floors after the demo's detail "
                             f"(default: {' '.join(WORKLOADS)}; none: only the demo)")
    parser.add_argument("--traffic-lanes", type=int, default=6,
                        help="one-truck traffic events run as 32 lanes against alone (default 6; 0: skip)")
    args = benchmark_args(__doc__, "timed runs after the warm-up (minimum reported)", parser)
    import datetime
    import os

    import numpy as np

    from vbikit.analysis import point_response
    from vbikit.scenario import demo_scenario_text, scenario_from_toml
    from vbikit.scenario.preflight import preflight
    from vbikit.solve import integrators, kernels, simulate

    from _args import default_step_loops

    built = preflight(scenario_from_toml(demo_scenario_text(), source="demo.toml")).built
    one_lane = default_step_loops()[0]  # (the lean kernel's variant the default integrator runs)
    originals = {name: getattr(kernels, name) for name in ("implicit", one_lane)}
    spent: dict[str, list[float]] = {name: [] for name in originals}
    captured: dict[str, tuple] = {}

    def timed(name):
        def kernel(*a, **k):
            t0 = time.thread_time()
            out = originals[name](*a, **k)
            spent[name].append(time.thread_time() - t0)
            captured[name] = (a, out)
            return out
        return kernel

    def whole():  # a new crossing object each run, as `vbikit run` makes one: nothing kept by a crossing (Crossing.kept)
        res = simulate(copy.copy(built.crossing))
        return res, point_response(res, built.response_x, built.response_y)

    def timed_runs(use_lean: bool) -> tuple[list[float], float]:
        """Thread CPU times of ``whole`` and the first call's wall time, with or without the lean kernel."""
        integrators.USE_LEAN = use_lean
        t0 = time.perf_counter()
        whole()
        warm = time.perf_counter() - t0
        for times in spent.values():
            times.clear()
        out = []
        for _ in range(args.repeat):
            t0 = time.thread_time()
            whole()
            out.append(time.thread_time() - t0)
        return out, warm

    for name in originals:
        setattr(kernels, name, timed(name))
    try:
        t_whole, warm = timed_runs(True)
        t_lean = list(spent[one_lane])
        t_whole_implicit, _ = timed_runs(False)
        t_kernel = list(spent["implicit"])
        res, resp = whole()
    finally:
        for name, fn in originals.items():
            setattr(kernels, name, fn)
        integrators.USE_LEAN = True
    if not t_lean or integrators.LEAN_COUNTS["fallback"]:
        raise SystemExit("bench_floor: the demo crossing did not run through the lean kernel")
    call, (unsettled, evaluations) = captured["implicit"]
    lean_evaluations = captured[one_lane][1][1]
    floor_loop = _floor_loop()
    inputs, outs = floor_inputs(call)
    t0 = time.perf_counter()
    floor_loop(*inputs, *outs)
    floor_warm = time.perf_counter() - t0
    t_floor = []
    for _ in range(args.repeat):
        t0 = time.thread_time()
        floor_loop(*inputs, *outs)
        t_floor.append(time.thread_time() - t0)
    phi = built.crossing.bridge.mode_shapes(*([c] for c in res.point(built.response_x, built.response_y)))[0]
    u_lib = res.xi @ phi
    u_floor = outs[0][: u_lib.size] @ phi
    agree = float(np.max(np.abs(u_floor[1:] - u_lib[1:])) / np.max(np.abs(u_lib)))
    k, ln, w, wi, f = min(t_kernel), min(t_lean), min(t_whole), min(t_whole_implicit), min(t_floor)
    n = res.n_steps
    print(f"bench_floor: the vbikit demo crossing ({n} steps, {res.xi.shape[1]} modes, {inputs[29].size} contact "
          f"points), {datetime.date.today()}, {os.cpu_count()} CPUs, thread CPU time, min of {args.repeat}")
    print(f"  first calls (numba cache load or compile): crossing {warm:.2f} s, floor {floor_warm:.2f} s wall")
    print(f"  kernel (kernels.implicit)      {k * 1e3:7.2f} ms   {evaluations / n:.2f} contact-law evaluations a step, "
          f"{unsettled} unconverged steps")
    print(f"  lean (kernels.{one_lane}, default) {ln * 1e3:7.2f} ms   {lean_evaluations / n:.2f} contact-law evaluations a "
          f"step, no fallback")
    print(f"  whole crossing (simulate + IM) {w * 1e3:7.2f} ms   IM = {resp.displacement_impact.impact_factor:.4f} "
          f"(with kernels.implicit: {wi * 1e3:.2f} ms)")
    print(f"  floor (one evaluation a step)  {f * 1e3:7.2f} ms   midspan displacement within {agree:.1e} of the "
          f"library's peak")
    print(f"  kernel / floor = {k / f:.1f}   lean / floor = {ln / f:.1f}   whole / floor = {w / f:.1f}")
    lanes, lanes_full, frozen = _lanes(built.crossing, args.repeat)
    print(f"  lanes, 32 roads a call: kernels.lean_lanes {lanes * 1e3:.2f} ms a crossing ({frozen} lanes handed to "
          f"kernels.implicit), many-lane kernels.implicit {lanes_full * 1e3:.2f} ms a crossing; lanes / floor = "
          f"{lanes / f:.2f}")

    if args.workloads:
        print(f"workloads against their floors (per crossing or event, thread CPU time, min of {args.repeat}):")
        print(f"  {'workload':10s} {'whole ms':>9s} {'floor ms':>9s} {'whole/floor':>12s}  contact points, kernel calls")
        for name in args.workloads:
            r = workload_floor(name, args.repeat)
            print(f"  {name:10s} {r['whole_ms']:9.2f} {r['floor_ms']:9.2f} {r['whole_ms'] / r['floor_ms']:12.1f}  "
                  f"{r['points'][0]}–{r['points'][1]} points, {r['calls']} calls for {r['crossings']} crossings",
                  flush=True)
    if args.traffic_lanes > 0:
        print("traffic events, kernel time a crossing: the event alone (the lean kernel) against its truck on 32 roads as "
              f"lanes of one call (the many-lane lean kernel), min of {args.repeat}:")
        for r in traffic_lanes(args.traffic_lanes, args.repeat):
            print(f"  event {r['event']:3d} ({r['points']:2d} contact points, {r['steps']} steps): alone {r['alone_ms']:.2f} ms, "
                  f"as a lane {r['lane_ms']:.2f} ms -> {r['alone_ms'] / r['lane_ms']:.2f}x ({r['handed_over']} of 32 lanes handed "
                  "to kernels.implicit)", flush=True)


def traffic_lanes(n_events: int, repeat: int) -> list[dict]:
    """For the first ``n_events`` one-truck events of ``bench_traffic.py``'s stream: the thread CPU time
    of the event's step loop alone (the default's lean kernel inside ``simulate``, min of ``repeat``) and per lane
    of its truck on 32 roads (the event's road scaled by 0.5 … 1.5) as lanes of one call
    (the default's many-lane lean kernel inside ``BatchSolver.run_many``, min of ``repeat`` / 32), and how many lanes
    ``lean_lanes`` handed to the full kernel (their time is not counted: 0 keeps the comparison fair)."""
    from dataclasses import replace

    import numpy as np
    from bench_traffic import _base, _stream

    from vbikit.solve import integrators, kernels, simulate
    from vbikit.solve.batch import BatchSolver
    from vbikit.traffic.study import traffic_study

    from _args import default_step_loops

    job = traffic_study(_stream(40 * n_events, 600.0), _base(0.01), batch_size=16)
    events = [e for e in range(job.size) if len(job.events[e]) == 1][:n_events]
    one_lane, many = default_step_loops()  # (the lean kernels' variants the default integrator runs)
    spent: dict[str, list[float]] = {one_lane: [], many: []}
    originals = {name: getattr(kernels, name) for name in spent}

    def timed(name):
        def kernel(*a, **k):
            t0 = time.thread_time()
            out = originals[name](*a, **k)
            spent[name].append(time.thread_time() - t0)
            return out
        return kernel

    out = []
    for name in spent:
        setattr(kernels, name, timed(name))
    try:
        for e in events:
            crossing = job.crossing(e)
            roads = [replace(crossing.road, z=crossing.road.z * s) for s in np.linspace(0.5, 1.5, 32)]
            alone, lanes = [], []
            for _ in range(repeat + 1):
                spent[one_lane].clear()
                res = simulate(crossing)
                alone.append(sum(spent[one_lane]))
            solver = BatchSolver(crossing)
            before = integrators.LEAN_COUNTS["lanes_fallback"]
            for _ in range(repeat + 1):
                spent[many].clear()
                solver.run_many(roads)
                lanes.append(sum(spent[many]) / len(roads))
            out.append({"event": e, "points": int(crossing.point_vehicle.size), "steps": res.n_steps,
                        "alone_ms": min(alone[1:]) * 1e3, "lane_ms": min(lanes[1:]) * 1e3,
                        "handed_over": (integrators.LEAN_COUNTS["lanes_fallback"] - before) // (repeat + 1)})
    finally:
        for name, fn in originals.items():
            setattr(kernels, name, fn)
    return out


def _lanes(crossing, repeat: int) -> tuple[float, float, int]:
    """Thread CPU time a crossing of ``kernels.lean_lanes`` and of the many-lane ``kernels.implicit``
    (min of ``repeat`` runs / 32; the lean one without the ``implicit`` calls of lanes it hands over) on
    32 roads, and how many lanes it handed over."""
    from dataclasses import replace

    import numpy as np

    from vbikit.solve import integrators, kernels
    from vbikit.solve.batch import BatchSolver

    roads = [replace(crossing.road, z=crossing.road.z * s) for s in np.linspace(0.5, 1.5, 32)]
    solver = BatchSolver(crossing)
    out = []
    from _args import default_step_loops

    for name, use_lean in ((default_step_loops()[1], True), ("implicit", False)):
        original = getattr(kernels, name)
        spent: list[float] = []

        def kernel(*a, **k):
            t0 = time.thread_time()
            res = original(*a, **k)
            spent.append(time.thread_time() - t0)
            return res

        setattr(kernels, name, kernel)
        integrators.USE_LEAN = use_lean
        before = integrators.LEAN_COUNTS["lanes_fallback"]
        runs = []  # the kernel's time of each run (``lean_lanes`` runs in chunks of steps: their sum)
        try:
            for _ in range(repeat + 1):
                spent.clear()
                solver.run_many(roads)
                runs.append(sum(spent))
        finally:
            setattr(kernels, name, original)
            integrators.USE_LEAN = True
        out.append(min(runs[1:]) / len(roads))
        if use_lean:
            frozen = (integrators.LEAN_COUNTS["lanes_fallback"] - before) // (repeat + 1)
    return out[0], out[1], frozen


if __name__ == "__main__":
    main()
