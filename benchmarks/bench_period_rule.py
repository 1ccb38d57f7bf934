"""What the exact integrator's first-period rule (steps per period of the first bridge mode,
``vbikit.solve.timestep.EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD``: 100 for every result, 50 for runs that resolve
deflections only, as the paper programme's) costs the paper programme, and what it buys.

    python benchmarks/bench_period_rule.py              # seven cells of the programme, ≈ 1 min
    python benchmarks/bench_period_rule.py --per 100 50 25 12.5
    python benchmarks/bench_period_rule.py --hold linear     # the wheel loads linear on every step
    python benchmarks/bench_period_rule.py --programme-steps # the programme's step count at the library's rules

The paper programme (``bench_studies.py``) is bound by its step count: its lanes run at or below the
floor (README, targets).  On Bridge 1 (f₁ = 25 Hz) every speed's step is set by the first bridge period
(0.399 ms, against 2.4 ms of 3 cm of road at 45 km/h); on Bridge 2 (7.3 Hz) the speeds up to 75 km/h on
classes B and C, and up to 53 km/h on class D and with Fig. 11's depression (2 cm of road a step).  For
seven cells of the programme (the paper's 3D bridges at Girder 4, first road profile of the cell), each
crossing is run at the automatic step the rule gives with ``--per`` steps a first period, and at an eighth
of the step of 100 (the reference, the same for every rule and hold); printed per cell and rule: the step, the number of steps, the thread
CPU time of ``simulate`` and the displacement IM's difference from the reference.  The programme's
accuracy criterion is 1e-3 per crossing against converged RK4 (docs/verification.md, "The paper
programme against RK4"); the automatic step's own bound in the convergence table is 5e-4.

``--hold`` sets how the exact integrator holds the vehicles' wheel loads over a step, reference included:
``linear`` on every step, ``hybrid`` (the library's default: quadratic on the lean kernels' steps, a
landing's step taken again with the linear hold's loads, linear in the full kernel:
``vbikit.solve.builtin_integrators.QUADRATIC_WHEEL_LOADS``) or ``quadratic`` in both kernels (``modal_step.vehicle_step``'s
``QUADRATIC`` for the full kernel's map too: a trial);
``--vehicle-steps`` changes the vehicle term of the step rule (benchmarks/README.md).

Writes nothing but numba's cache.
"""
from __future__ import annotations

import argparse
import dataclasses
import itertools
import time

#: (figure, (tire model, multipoint n, speed [km/h], road class)) of the cells measured
CELLS = (("fig5", ("multipoint", 1, 45, "C")), ("fig5", ("multipoint", 6, 45, "B")),
         ("fig5", ("multipoint", 1, 45, "D")), ("fig6", ("multipoint", 6, 45, "C")),
         ("fig10", ("disk", None, 15, "C")), ("fig10", ("multipoint", None, 30, "B")),
         ("fig11", ("point", None, 15, "B")))


def _scenario(fig: str, key: tuple):
    from vbikit.scenario import build, parse_scenario
    from vbikit.study.paper import paper_study

    study = paper_study(fig, 1)
    for idx in itertools.product(*(range(n) for n in study.shape)):
        d = study.scenario_dict(idx)
        have = (d["tire"].get("model"), d["tire"].get("n_points"), d["crossing"]["speed_kmh"], d["road"]["class"])
        if all(want is None or want == got for want, got in zip(key, have)):
            return build(parse_scenario(d))
    raise SystemExit(f"no cell {key} in {fig}")


def _run(built, dt: float) -> tuple[float, int, float]:
    """(displacement IM, steps, thread CPU s of ``simulate``) of ``built``'s crossing at step ``dt``."""
    from vbikit.analysis import point_response
    from vbikit.solve import simulate

    t0 = time.thread_time()
    result = simulate(dataclasses.replace(built.crossing, dt=dt))
    spent = time.thread_time() - t0
    im = point_response(result, built.response_x, built.response_y).displacement_impact.impact_factor
    return im, int(result.n_steps), spent


def _programme_steps() -> None:
    """The paper programme's step count, one road profile a cell (the library's automatic steps, each cell's
    duration over its step: ``Crossing.exit_time`` plus its free vibration), by figure and in all."""
    import logging

    import numpy as np

    from vbikit.scenario import build, parse_scenario
    from vbikit.study.paper import paper_study
    from vbikit.study.run import batch_steps

    logging.disable(logging.WARNING)
    total = 0.0
    for fig in ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11"):
        study = paper_study(fig, 1)
        cells = list(itertools.product(*(range(n) for n in study.shape)))
        steps = 0.0
        for idx, dt in zip(cells, batch_steps(study, cells)):
            c = build(parse_scenario(study.scenario_dict(idx))).crossing
            free = c.free_vibration if c.free_vibration is not None else 2 * np.pi / c.bridge.omega.min()
            steps += (c.exit_time() + free) / dt
        total += steps
        print(f"{fig}: {steps:,.0f} steps", flush=True)
    print(f"programme, one profile a cell: {total:,.0f} steps")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--per", type=float, nargs="+", default=[100.0, 50.0, 25.0],
                   help="steps per first bridge period to compare (default 100 50 25; the library's: 100, 50 for "
                        "deflections only)")
    p.add_argument("--hold", choices=("linear", "hybrid", "quadratic"), default="hybrid",
                   help="the vehicles' wheel loads over a step (the library's: hybrid; see the docstring)")
    p.add_argument("--vehicle-steps", type=float, default=None,
                   help="steps per period of the highest vehicle mode (the library's: 20)")
    p.add_argument("--programme-steps", action="store_true",
                   help="only count the programme's steps (one profile a cell) at the library's rules, by figure")
    args = p.parse_args()
    if args.programme_steps:
        _programme_steps()
        return

    import logging

    import vbikit.solve.timestep as ts

    logging.disable(logging.WARNING)  # (the rough roads' start-at-rest notes)
    default = ts.EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD
    if args.vehicle_steps is not None:
        ts.EXACT_STEPS_PER_VEHICLE_PERIOD = args.vehicle_steps
    import vbikit.solve.builtin_integrators as builtin

    builtin.QUADRATIC_WHEEL_LOADS = args.hold != "linear"
    if args.hold == "quadratic":  # the exact integrator's vehicle maps with G quadratic (modal_step.QUADRATIC)
        import vbikit.solve.modal_step as modal_step

        any_map = modal_step.vehicle_step
        modal_step.vehicle_step = lambda vehicles, h, hold=modal_step.LINEAR: any_map(vehicles, h, modal_step.QUADRATIC)
    for fig, key in CELLS:
        built = _scenario(fig, key)
        assert built.crossing.run_in == 0  # (a run-in's recursion reads the linear map only: --hold would not reach it)
        steps = {}
        for per in args.per:
            ts.EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD = dict.fromkeys(default, per)
            steps[per] = ts.implicit_time_step(built.crossing)
        ts.EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD = default
        _run(built, steps[args.per[0]])  # warm-up (kernels, the cell's tables)
        ref = _run(built, ts.implicit_time_step(dataclasses.replace(built.crossing, resolve="effects")) / 8)[0]
        cells = []
        for per, dt in steps.items():
            im, n, spent = _run(built, dt)
            cells.append(f"{per:g}/period: dt {dt * 1e3:.3g} ms, {n} steps, {spent * 1e3:.1f} ms, ΔIM {im - ref:+.1e}")
        tire = key[0] + (f" n = {key[1]}" if key[1] else "")
        print(f"{fig} {tire}, {key[2]} km/h, class {key[3]}: " + "; ".join(cells), flush=True)


if __name__ == "__main__":
    main()
