"""Recompute the convergence study of the default integrator that docs/verification.md quotes
("Exact modal stepping: convergence") and store it in docs/figures/convergence-numbers.json;
docs/scripts/generate.py renders its tables and sentences into the page (``render_steps``,
``render_automatic``).

    python docs/scripts/convergence_numbers.py   # writes the JSON (under a minute once numba's cache is warm)
    python docs/scripts/generate.py              # then re-renders the page's blocks

For each case (``CASES``): the displacement impact factor IM at the response point of

* the reference: classical RK4 at its automatic step (``reference``), and RK4 at a quarter of that
  step (``refined_step_change`` = IM(RK4, dt/4) − IM(RK4, dt): the reference's own error);
* the default integrator (``"exact"``) at its automatic step (``automatic.im_change`` = IM(exact) −
  IM(reference); ``steps_out_of_contact``: its time points with a wheel off the road);
* the default integrator at each multiple of its automatic step in ``NEAR_STEPS`` (``near_steps``)
  and at ``COARSE_STEP`` times it (``coarse_step``), IM(exact) − IM(reference);
* for the cases of ``STEP_STUDY``, the default integrator at each fixed step of ``STEPS``
  (``steps``: IM(exact, dt) − IM(reference), in the order of ``STEPS``).

``BOUND`` is the page's claim for the automatic step: every case's |IM(exact) − IM(reference)| is
below it (tests/verification/test_convergence_numbers.py checks it on the stored numbers and
recomputes them). The crossings are those of tests/verification/test_exact_modal_stepping.py
(20 modes, seed 1, 75 km/h, the depression at its default place and size) and the two example
scenarios (Yang–Yau, the ``vbikit demo`` crossing).
"""
from __future__ import annotations

import dataclasses
import json
import sys
import time
from pathlib import Path
from typing import Any, Callable, NamedTuple

ROOT = Path(__file__).resolve().parents[2]
NUMBERS = ROOT / "docs" / "figures" / "convergence-numbers.json"

#: fixed steps [s] of the step study
STEPS = (8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4)
#: the page's bound on |IM(exact, automatic step) − IM(RK4 reference)| over the cases
BOUND = 5e-4
#: the cases whose IM is computed at every step of STEPS too
STEP_STUDY = ("yang-yau", "demo", "bridge2-D-point", "bridge2-D-rigid-disk")
#: RK4's reference step divided by this gives the step of the reference's own check
REFERENCE_REFINEMENT = 4
#: multiples of the automatic step at which every case runs too: how much the IM scatters with a step
#: a few per cent away from it
NEAR_STEPS = (0.96, 0.97, 0.98, 0.99, 1.01, 1.02, 1.03, 1.04)
#: a multiple of the automatic step at which every case runs too: 4.5 cm of road per step at 75 km/h
#: instead of the step rule's 3 cm (``vbikit.solve.timestep.EXACT_ROAD_LENGTH_PER_STEP``)
COARSE_STEP = 1.5

TIRES = {"point": ({"model": "point"}, "point"),
         "multipoint": ({"model": "multipoint", "n_points": 6}, "multipoint n = 6"),
         "disk": ({"model": "disk"}, "disk"),
         "rigid-disk": ({"model": "rigid-disk"}, "rigid disk")}


def _preset_case(bridge: str, vehicle: str, tire: dict, road_class: str, depression: bool = False,
                 girder: int | None = None) -> Callable[[], Any]:
    """A builder of the scenario of tests/verification/test_exact_modal_stepping.py."""
    def make():
        from vbikit.scenario import build, parse_scenario

        spec: dict[str, Any] = {"bridge": {"model": bridge, "n_modes": 20}, "vehicle": {"model": vehicle},
                                "tire": dict(tire), "road": {"class": road_class, "seed": 1},
                                "crossing": {"speed_kmh": 75}}
        if depression:
            spec["road"]["defects"] = [{"kind": "depression"}]
        if girder is not None:
            spec["response"] = {"girder": girder}
        return build(parse_scenario(spec))
    return make


def _yang_yau():
    from vbikit.scenario import build, load_scenario

    return build(load_scenario(ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"))


def _demo():
    from vbikit.scenario import build, demo_scenario_text, scenario_from_toml

    return build(scenario_from_toml(demo_scenario_text(), source="demo.toml"))


def _cases() -> dict[str, tuple[str, Callable[[], Any]]]:
    """name → (label, builder of the built scenario) in the page's order."""
    cases: dict[str, tuple[str, Callable[[], Any]]] = {
        "yang-yau": ("Yang–Yau (beam 25 m, sprung mass, 100 km/h)", _yang_yau),
        "demo": ("HS20-44, 16.76 m beam, class C, multipoint n = 6 (`vbikit demo`)", _demo),
    }
    for road_class in ("C", "D"):
        for key, (tire, words) in TIRES.items():
            cases[f"bridge2-{road_class}-{key}"] = (
                f"HS20-44, paper-bridge-2 Girder 4, class {road_class} + depression, {words}",
                _preset_case("paper-bridge-2", "hs20-44", tire, road_class, depression=True, girder=4))
    cases["cypress-bayou"] = ("dump truck, cypress-bayou, class C, multipoint n = 6",
                              _preset_case("cypress-bayou", "dump-truck", TIRES["multipoint"][0], "C"))
    return cases


CASES = _cases()


class Run(NamedTuple):
    """One crossing's displacement impact factor, its step and what its wheels did."""

    impact_factor: float
    dt: float  #: the integrator's step [s]
    n_steps: int
    steps_out_of_contact: int  #: time points at which at least one wheel's force is zero


def run(built, **crossing) -> Run:
    """``built``'s crossing with ``crossing``'s fields replaced (the integrator, the step), simulated."""
    from vbikit.analysis import point_response
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    plan = plan_run(dataclasses.replace(built.crossing, **crossing))
    res = simulate(plan.crossing, plan=plan)
    im = point_response(res, built.response_x, built.response_y).displacement_impact.impact_factor
    return Run(float(im), float(plan.dt), int(res.n_steps), int((res.wheel_forces <= 0.0).any(axis=1).sum()))


def case_numbers(name: str) -> dict[str, Any]:
    """The reference, its own error and the default integrator's IM changes of case ``name``."""
    label, make = CASES[name]
    built = make()
    assert built.crossing.integrator == "exact", "the study is of the default integrator"
    ref = run(built, integrator="rk4")
    finer = run(built, integrator="rk4", dt=ref.dt / REFERENCE_REFINEMENT)
    auto = run(built)

    def change(dt: float) -> float:
        return run(built, dt=dt).impact_factor - ref.impact_factor

    out: dict[str, Any] = {
        "label": label,
        "reference": {"impact_factor": ref.impact_factor, "dt": ref.dt, "n_steps": ref.n_steps,
                      "refined_step_change": finer.impact_factor - ref.impact_factor},
        "automatic": {"dt": auto.dt, "n_steps": auto.n_steps, "im_change": auto.impact_factor - ref.impact_factor,
                      "steps_out_of_contact": auto.steps_out_of_contact},
        "near_steps": [change(k * auto.dt) for k in NEAR_STEPS],
        "coarse_step": change(COARSE_STEP * auto.dt),
    }
    if name in STEP_STUDY:
        out["steps"] = [change(step) for step in STEPS]
    return out


def compute() -> dict[str, Any]:
    """Every case of ``CASES`` (``case_numbers``), with the study's parameters and the run's date and time."""
    t0 = time.perf_counter()
    cases = {name: case_numbers(name) for name in CASES}
    return {"date": time.strftime("%Y-%m-%d"), "wall_s": time.perf_counter() - t0, "steps": list(STEPS),
            "near_steps": list(NEAR_STEPS), "coarse_step": COARSE_STEP,
            "reference_refinement": REFERENCE_REFINEMENT, "cases": cases}


# ----------------------------------------------------------------------------- the page's blocks
def stored() -> dict[str, Any]:
    return json.loads(NUMBERS.read_text(encoding="utf-8"))


def _signed(x: float) -> str:
    """``+1.2e-04`` written ``+1.2e-4``, with a minus sign (−) in front of negative numbers."""
    mantissa, exponent = f"{abs(x):.1e}".split("e")
    return f"{'−' if x < 0 else '+'}{mantissa}e{int(exponent)}"


def _unsigned(x: float) -> str:
    mantissa, exponent = f"{abs(x):.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def bound_text() -> str:
    """``BOUND`` as the page writes it (``5e-4``)."""
    mantissa, exponent = f"{BOUND:.1e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def _ms(dt: float) -> str:
    return f"{dt * 1e3:.3g} ms"


def largest(numbers: dict[str, Any], change: Callable[[dict[str, Any]], float]) -> tuple[str, float]:
    """(case name, |change|) of the case with the largest |``change(case)``|."""
    name = max(numbers["cases"], key=lambda k: abs(change(numbers["cases"][k])))
    return name, abs(change(numbers["cases"][name]))


def automatic_change(case: dict[str, Any]) -> float:
    """IM(exact at the automatic step) − IM(reference) of a stored case."""
    return case["automatic"]["im_change"]


def near_change(case: dict[str, Any]) -> float:
    """The largest |IM(exact) − IM(reference)| of a stored case over the steps near the automatic one."""
    return max(abs(d) for d in case["near_steps"])


def coarse_change(case: dict[str, Any]) -> float:
    """IM(exact at ``COARSE_STEP`` × the automatic step) − IM(reference) of a stored case."""
    return case["coarse_step"]


def reference_change(case: dict[str, Any]) -> float:
    """IM(RK4 at a fraction of its step) − IM(reference) of a stored case: the reference's own error."""
    return case["reference"]["refined_step_change"]


def _fraction(k: int) -> str:
    return {2: "half", 4: "quarter"}.get(k, f"1/{k}")


def _near(numbers: dict[str, Any]) -> str:
    near = numbers["near_steps"]
    return f"{min(near):g}–{max(near):g}"


def render_steps(numbers: dict[str, Any] | None = None) -> str:
    """The step study's table: IM(exact, dt) − IM(reference) per fixed step and at the automatic step."""
    numbers = stored() if numbers is None else numbers
    k = numbers["reference_refinement"]
    rows = [f"| case | RK4 reference IM (steps) | RK4 at dt/{k} − reference | "
            + " | ".join(_ms(s) for s in numbers["steps"]) + " | automatic (dt, steps) |",
            "|---" * (len(numbers["steps"]) + 4) + "|"]
    for c in numbers["cases"].values():
        if "steps" not in c:
            continue
        r, a = c["reference"], c["automatic"]
        rows.append(f"| {c['label']} | {r['impact_factor']:.5f} ({r['n_steps']}) | {_signed(reference_change(c))} | "
                    + " | ".join(_signed(d) for d in c["steps"])
                    + f" | {_signed(a['im_change'])} ({_ms(a['dt'])}, {a['n_steps']}) |")
    rows += ["", f"*IM(exact, dt) − IM(RK4 at its automatic step); computed {numbers['date']} by "
                 f"`docs/scripts/convergence_numbers.py` (`docs/figures/convergence-numbers.json`).*"]
    return "\n".join(rows) + "\n"


def render_automatic(numbers: dict[str, Any] | None = None) -> str:
    """Every case at the automatic step, near it and at ``COARSE_STEP`` times it, then the largest
    changes against ``BOUND`` and the reference's own error."""
    numbers = stored() if numbers is None else numbers
    k, coarse, near = numbers["reference_refinement"], numbers["coarse_step"], _near(numbers)
    rows = ["| case | steps: default / RK4 reference | steps with a wheel off the road | ΔIM at the automatic step | "
            f"largest \\|ΔIM\\| at {near} × it | ΔIM at {coarse:g} × it | RK4 at dt/{k} − reference |",
            "|---" * 7 + "|"]
    for c in numbers["cases"].values():
        r, a = c["reference"], c["automatic"]
        rows.append(f"| {c['label']} | {a['n_steps']} / {r['n_steps']} | {a['steps_out_of_contact']} | "
                    f"{_signed(automatic_change(c))} | {_unsigned(near_change(c))} | {_signed(coarse_change(c))} | "
                    f"{_signed(reference_change(c))} |")
    label = {name: c["label"] for name, c in numbers["cases"].items()}
    auto, near_worst, coarse_worst, ref_worst = (largest(numbers, f) for f in (
        automatic_change, near_change, coarse_change, reference_change))

    def where(worst: tuple[str, float]) -> str:
        return f"{_unsigned(worst[1])} ({label[worst[0]]})"

    def within(value: float) -> str:
        return "within" if value <= BOUND else "above"

    rows += ["", f"At the automatic step the largest |ΔIM| is {where(auto)}: every case is {within(auto[1])} "
                 f"{bound_text()}. At {near} times the automatic step the largest is {where(near_worst)}, "
                 f"{within(near_worst[1])} {bound_text()}; at {coarse:g} times it {where(coarse_worst)}. The "
                 f"reference's own error, RK4 at a {_fraction(k)} of its step against it, is at most {where(ref_worst)}."]
    return "\n".join(rows) + "\n"


def main() -> None:
    numbers = compute()
    NUMBERS.write_text(json.dumps(numbers, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    print(render_steps(numbers))
    print(render_automatic(numbers))
    print(f"{numbers['wall_s']:.1f} s")


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "src"))
    main()
