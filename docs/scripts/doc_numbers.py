"""Recompute the numbers the docs quote and store them in docs/figures/numbers.json.

    python docs/scripts/doc_numbers.py        # recompute (about a minute), then: python docs/scripts/generate.py

The pages show these numbers through generated blocks (docs/scripts/generate.py renders them
from the JSON), and tests/docs/test_numbers.py recomputes them and fails when the code no longer
reproduces what the docs say, so a quoted number cannot go stale.

* ``fig9``: the paper's Fig. 9 case (examples/paper/fig9_tire_models.toml) with each tire model,
  as ``vbikit compare-tires`` runs it (docs/tires.md); its figure is docs/figures/fig9-tire-models.png.
* ``roughness``: the two readings of the paper's "poor" road (docs/model-data.md §4): mean IM
  over five seeds with ISO D and with φ(n0) = 64e-6 m³/cycle at n0 = 1/(2π) cycle/m.
* ``demo``: the crossing of ``vbikit demo`` (README and docs home); its figure is
  docs/figures/demo.png, which carries the impact factor it was drawn with in its PNG metadata
  (``Description``), so that the tests can tell a stale figure.
* ``field``: the synthetic field test of docs/field.md (``vbikit field … --calibrate``).
* ``examples``: load effects of the example scenarios that docs/bridges.md quotes (Bridge 2 at
  Girder 4, the three-span continuous deck, the 20° skew deck and the same deck square).
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
NUMBERS = ROOT / "docs" / "figures" / "numbers.json"
FIG9 = ROOT / "examples" / "paper" / "fig9_tire_models.toml"
TIRES = {"point": {"model": "point"}, "multipoint (n = 6)": {"model": "multipoint", "n_points": 6},
         "disk": {"model": "disk"}, "rigid disk": {"model": "rigid-disk"}}


def _crossing(scenario):
    from vbikit.analysis import point_response
    from vbikit.scenario import build
    from vbikit.solve import simulate

    built = build(scenario)
    result = simulate(built.crossing)
    return result, point_response(result, built.response_x, built.response_y)


def fig9(plot: Path | None = None) -> dict[str, dict[str, float]]:
    """Peaks and impact factors of the Fig. 9 case per tire model (SI units)."""
    from vbikit.scenario import load_scenario

    base = load_scenario(FIG9)
    table, responses = {}, {}
    for label, tire in TIRES.items():
        spec = base.model_copy(update={"tire": base.tire.model_copy(update=tire)})
        spec._base_dir = base.base_dir
        result, r = _crossing(spec)
        responses[label] = r
        table[label] = {
            "max_dynamic_displacement": r.displacement_impact.dynamic_peak,
            "impact_factor": r.displacement_impact.impact_factor,
            "strain_impact_factor": r.strain_impact.impact_factor,
            "max_abs_acceleration": float(abs(r.acceleration).max()),
            "min_tire_force": float(result.wheel_forces.min()),
        }
    if plot is not None:
        from vbikit.plot import plot_tire_comparison

        plot_tire_comparison(responses, plot, base.name)
    return table


def roughness(seeds: int = 5) -> dict[str, float]:
    """Mean displacement IM at Girder 4 of paper-bridge-2 (HS20-44, n = 6, 75 km/h) over ``seeds``
    roads: ISO class D against φ(n0) = 64e-6 m³/cycle at n0 = 1/(2π) cycle/m."""
    from vbikit.scenario import parse_scenario

    out = {}
    for label, road in (("iso_d", {"class": "D"}),
                        ("phi64_n0_1_over_2pi", {"class": "psd", "phi0": 64e-6, "n0": 1 / (2 * math.pi)})):
        ims = []
        for seed in range(1, seeds + 1):
            spec = parse_scenario({"bridge": {"model": "paper-bridge-2"}, "vehicle": {"model": "hs20-44"},
                                   "tire": {"model": "multipoint", "n_points": 6}, "road": {**road, "seed": seed},
                                   "crossing": {"speed_kmh": 75}, "response": {"girder": 4}})
            ims.append(_crossing(spec)[1].displacement_impact.impact_factor)
        out[label] = sum(ims) / len(ims)
    return out


DEMO_FIGURE = ROOT / "docs" / "figures" / "demo.png"


def demo(plot: Path | None = None) -> dict[str, float]:
    """The ``vbikit demo`` crossing: its impact factors and peaks (SI units); with ``plot``, its
    figure, as ``vbikit demo`` draws it, with the IM in the PNG's ``Description``."""
    import vbikit
    from vbikit.scenario import demo_scenario_text

    report = vbikit.run(demo_scenario_text())
    s = report.summary
    out = {"impact_factor": s["impact_factor"], "strain_impact_factor": s["strain_impact_factor"],
           "max_dynamic_displacement": s["max_dynamic_displacement"],
           "max_static_displacement": s["max_static_displacement"]}
    if plot is not None:
        from vbikit.plot import plot_crossing

        plot_crossing(report.result, report.response, plot, metadata={"Description": demo_figure_note(out)})
    return out


def demo_figure_note(numbers: dict[str, float]) -> str:
    """What docs/figures/demo.png records about itself (checked by tests/docs/test_numbers.py)."""
    return f"vbikit demo; impact_factor = {numbers['impact_factor']!r}"


EXAMPLES = {"bridge2_girder4": ("examples/paper/bridge2_hs20_girder4.toml", None),
            "three_span_grillage": ("examples/bridges/three_span_grillage_hs20.toml", None),
            "skew": ("examples/bridges/skew_grillage_hs20.toml", None),
            "skew_square": ("examples/bridges/skew_grillage_hs20.toml", {"skew": 0.0})}


def _effects(summary: dict, kind: str) -> list[dict[str, object]]:
    keep = ("x", "support", "hogging_region", "static_peak", "dynamic_peak", "impact_factor", "code_allowances")
    return [{k: e[k] for k in keep} for e in summary[kind]["sections"]]


def examples() -> dict[str, dict[str, object]]:
    """Deflection IM, f1, code allowances and every moment, shear and reaction of the example
    scenarios docs/bridges.md quotes (``skew_square``: the skew example with ``skew = 0``)."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib

    import vbikit

    out = {}
    for name, (path, deck) in EXAMPLES.items():
        spec = tomllib.loads((ROOT / path).read_text(encoding="utf-8"))
        spec["bridge"].setdefault("deck", {}).update(deck or {})
        s = vbikit.run(spec).summary
        out[name] = {"impact_factor": s["impact_factor"], "first_frequency": s["frequencies_hz"][0],
                     "response_x": s["response_x"], "design_code_allowances": s["design_code_allowances"],
                     **{kind: _effects(s, kind) for kind in ("moment", "shear", "reaction")}}
    return out


FIELD = ROOT / "examples" / "field" / "FIELD.toml"


def field() -> dict[str, object]:
    """``vbikit field examples/field/FIELD.toml --calibrate`` (point and multipoint tires): per case the
    accelerometer's removed offset [m/s²] and drift [m/s³]; the calibration (multipoint) with its 1σ;
    per tire model and channel quantity the peak error and normalised RMS error and correlation,
    nominal and calibrated (the largest |value| over the cases, the smallest correlation)."""
    import dataclasses
    import tempfile

    from vbikit.field.io import load_field_toml
    from vbikit.field.report import run_field
    from vbikit.field.workflow import compare_case

    with tempfile.TemporaryDirectory() as tmp:
        run = run_field(FIELD, tmp, ["point", "multipoint"], do_calibrate=True)
    cal = run.calibration
    # case 1 aligned by cross-correlation instead of its trigger time, with the true model (E × 1.10,
    # 2.5 % damping: examples/field/make_synthetic.py) and with the nominal one
    spec = load_field_toml(FIELD)
    case = dataclasses.replace(spec.cases[0], align="xcorr")
    xcorr = {label: compare_case(s, case, ["multipoint"]).table()["trigger_time_s"]
             for label, s in (("true", dataclasses.replace(spec, stiffness_factor=1.10, damping_ratio=0.025)),
                              ("nominal", spec))}
    out: dict[str, object] = {"xcorr_trigger": xcorr,
        "drift": [{"offset": d.offset, "drift": d.drift} for c in run.comparisons for d in c.drift.values()],
        "stiffness_factor": cal.stiffness_factor, "stiffness_factor_std": cal.stiffness_factor_std,
        "damping_ratio": cal.damping_ratio, "damping_ratio_std": cal.damping_ratio_std}
    for label, cmps in (("nominal", run.comparisons), ("calibrated", run.calibrated)):
        table: dict[str, dict[str, dict[str, list[float]]]] = {}
        for c in cmps:
            quantity = {ch.name: ch.quantity for ch in c.case.channels}
            for tire, chans in c.metrics.items():
                for name, m in chans.items():
                    row = table.setdefault(tire, {}).setdefault(quantity[name], {"peak_error": [], "nrms": [], "corr": []})
                    row["peak_error"].append(m["peak_error"])
                    row["nrms"].append(m["normalised_rms_error"])
                    row["corr"].append(m["correlation"])
        out[label] = table
    return out


def compute(plot: bool = False) -> dict[str, object]:
    return {"fig9": fig9(ROOT / "docs" / "figures" / "fig9-tire-models.png" if plot else None),
            "roughness": roughness(),
            "demo": demo(DEMO_FIGURE if plot else None),
            "examples": examples(),
            "field": field()}


if __name__ == "__main__":
    import matplotlib

    matplotlib.use("Agg")
    NUMBERS.write_text(json.dumps(compute(plot=True), indent=2) + "\n")
    print(f"wrote {NUMBERS.relative_to(ROOT)}; now run python docs/scripts/generate.py")
    sys.exit(0)
