"""The ``vbikit`` command line.  Only this module prints; the library logs."""
from __future__ import annotations

import logging
from pathlib import Path
from typing import Any, Optional

import numpy as np
import typer

app = typer.Typer(
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # plain help texts: "[tire]" or "[m]" stay as written
    help="vbikit — vehicle–bridge coupled vibration: run scenarios, list presets, run the demo.\n\n"
         "Commands that write files write them into --out-dir (default vbikit-out/); options that name "
         "one file (--out, --plot, --summary) take that path as given.",
)

_STATE = {"debug": False, "quiet": False}

from vbikit.study import commands as study_commands  # noqa: E402
from vbikit.study.commands import app as study_app  # noqa: E402

app.add_typer(study_app, name="study")
from vbikit.traffic.commands import traffic_cmd  # noqa: E402

app.command("traffic")(traffic_cmd)


def _version(value: bool) -> None:
    if value:
        from vbikit import __version__

        typer.echo(f"vbikit {__version__}")
        raise typer.Exit()


@app.callback(invoke_without_command=True)
def _main(
    ctx: typer.Context,
    verbose: int = typer.Option(0, "--verbose", "-v", count=True, help="More log messages (-v info, -vv debug)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Only errors: no warnings, no progress bars."),
    debug: bool = typer.Option(False, "--debug", help="Show full tracebacks and debug logs."),
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version and exit."),
) -> None:
    _STATE["debug"], _STATE["quiet"] = debug, quiet
    study_commands.QUIET["on"] = quiet
    level = logging.DEBUG if debug or verbose > 1 else logging.INFO if verbose else logging.ERROR if quiet else logging.WARNING
    logging.basicConfig(level=level, format="%(levelname)s %(name)s: %(message)s", force=True)
    if not quiet:
        logging.getLogger("vbikit.solve.compile").setLevel(logging.INFO)  # "compiling kernels, first run only"
    if quiet:
        import warnings

        warnings.simplefilter("ignore")
    if ctx.invoked_subcommand is None:  # bare `vbikit`: the help, exit code 0
        typer.echo(ctx.get_help())
        raise typer.Exit()


def _json(obj: object, indent: int | None = None) -> str:
    """Strict JSON (no NaN/Infinity: those are null, see vbikit._files.json_safe)."""
    from vbikit._files import json_text

    return json_text(obj, indent)


def _limits(max_memory: Optional[str], max_steps: Optional[float]) -> Any:
    from vbikit.solve.budget import Limits, parse_size

    kw: dict[str, Any] = {}
    if max_memory is not None:
        kw["max_memory"] = _guard(lambda: parse_size(max_memory))
    if max_steps is not None:
        kw["max_steps"] = int(max_steps)
    return Limits(**kw)


def _warn(warnings: list[str]) -> None:
    if _STATE["quiet"]:
        return
    for text in warnings:
        typer.echo(f"warning: {text}", err=True)


_MAX_MEMORY = typer.Option(None, "--max-memory", help="Memory budget of the run (e.g. 8GiB; default 4GiB): "
                                                      "estimated before it starts, refused above.")
_MAX_STEPS = typer.Option(None, "--max-steps", min=1, help="Time-step budget of the run (default 5e6).")


def _guard(action: Any) -> Any:
    """Run ``action``; a user error (bad input, unwritable output) exits with code 2 and one message."""
    try:
        return action()
    except (ValueError, OSError) as err:  # ScenarioError, RoadFileError, UnstableTimeStepError are ValueErrors
        if _STATE["debug"]:
            raise
        typer.echo(f"error: {err}", err=True)
        raise typer.Exit(code=2) from None
    except MemoryError:
        if _STATE["debug"]:
            raise
        typer.echo("error: out of memory; lower --max-memory to be refused before starting, or reduce the inputs "
                   "named in the budget message of `vbikit validate`", err=True)
        raise typer.Exit(code=2) from None


def _write_text(path: Path, text: str) -> None:
    from vbikit._files import write_text

    write_text(path, text)


def _execute(load: Any, limits: Any = None) -> Any:
    """Check and run the scenario ``load()`` returns (:func:`vbikit.scenario.pipeline.run_planned`, every
    check of the preflight first); user errors exit with code 2.  Returns the Report."""
    from vbikit.scenario.preflight import preflight
    from vbikit.scenario.pipeline import run_planned

    report = _guard(lambda: run_planned(preflight(load(), limits), limits))
    _warn(report.summary["warnings"])
    return report


def _print_summary(run: Any) -> None:
    s = run.summary
    if run.name:
        typer.echo(run.name)
    inp = s.get("inputs")
    if inp:
        road = inp["road"]
        road_text = (f"class {road['class']} (phi0 {road['phi0']:.4g} m³/cycle at n0 {road['n0']:g} cycle/m, "
                     f"exponent {road['exponent']:g}), seed {road['seed']}" if "seed" in road else
                     f"measured {road['profile_file']}" if "profile_file" in road else "smooth")
        if road.get("defects"):
            road_text += f"; defects: {', '.join(road['defects'])}"
        deck = "".join(f", {k} {v}" for k, v in inp.get("bridge_deck", {}).items())
        typer.echo(f"  bridge               {inp['bridge']} (span {inp['span']:g} m, {inp['n_modes']} modes, "
                   f"damping {inp['damping_ratio']:.3g}{deck})")
        several = "vehicles" in inp
        for i, v in enumerate(inp["vehicles"] if several else [inp], start=1):
            motion = f", {v['direction']}, entering at {v['entry_time']:g} s, y = {v['lateral_offset']:g} m" if several else ""
            typer.echo(f"  {f'vehicle {i}' if several else 'vehicle':<20} {v['vehicle']}, {v['speed_kmh']:.4g} km/h = "
                       f"{v['speed_m_s']:.4g} m/s" + (f", acceleration {v['acceleration']:g} m/s²" if v["acceleration"] else "")
                       + motion)
        typer.echo(f"  tire                 {inp['tire']}")
        typer.echo(f"  road                 {road_text}")
        typer.echo(f"  vbikit               {inp['vbikit_version']}")
    typer.echo(f"  bridge f1..f3        {', '.join(f'{f:.2f}' for f in s['frequencies_hz'][:3])} Hz")
    girder = f" (Girder {s['response_girder']})" if s.get("response_girder") else ""
    typer.echo(f"  response point       x = {s['response_x']:.3f} m, y = {s['response_y']:.3f} m{girder}")
    typer.echo(f"  max displacement     dynamic {s['max_dynamic_displacement'] * 1e3:+.4f} mm, "
               f"static {s['max_static_displacement'] * 1e3:+.4f} mm")
    typer.echo(f"  max strain           dynamic {s['max_dynamic_strain'] * 1e6:+.3f} µε, static {s['max_static_strain'] * 1e6:+.3f} µε")
    typer.echo(f"  max |acceleration|   {s['max_abs_acceleration']:.4f} m/s²")
    typer.echo(f"  time steps           {s['n_steps']} × {s['dt']:.3e} s ({s['integrator']})")
    typer.echo(f"  IMPACT FACTOR        IM = {s['impact_factor']:.4f}  (strain IM = {s['strain_impact_factor']:.4f})")
    for i, v in enumerate(s.get("vehicles", []), start=1):
        loads = " / ".join(f"{f / 1e3:.1f}" for f in v["static_wheel_loads"].values())
        typer.echo(f"  vehicle {i:<12} {v['model']}, {v['direction']} at {v['speed'] * 3.6:.1f} km/h, enters at "
                   f"t = {v['entry_time']:.3f} s, y = {v['lateral_offset']:+.3f} m; wheel loads [kN] {loads}"
                   f"{'; lost contact' if v['contact_loss'] else ''}")
    if "governing_girder" in s:
        if "vehicles" not in s:
            typer.echo(f"  vehicle lateral      y = {s['lateral_offset']:.3f} m")
        typer.echo("  girder               " + "  ".join(f"{g:>7d}" for g in range(1, len(s["girder_y"]) + 1)))
        typer.echo("  static max [mm]      " + "  ".join(f"{v * 1e3:+7.3f}" for v in s["girder_max_static_displacement"]))
        typer.echo("  IM                   " + "  ".join(f"{v:7.4f}" for v in s["girder_impact_factors"]))
        typer.echo(f"  governing girder     {s['governing_girder']} (IM = {s['governing_girder_impact_factor']:.4f})")
    _print_codes(s["design_code_allowances"], "deflection IM beside")
    _print_load_effects(s)


_CODE_LABELS = {"aashto_lrfd": "AASHTO LRFD", "aashto_standard": "AASHTO Std", "csa_s6": "CSA S6",
                "ohbdc_1983": "OHBDC 1983", "jtg_d60_2015": "JTG D60-2015"}


def _print_codes(c: dict[str, Any], title: str) -> None:
    values = "  ".join(f"{label} {c[k]:.3f}" for k, label in _CODE_LABELS.items() if k in c)
    typer.echo(f"  {title:<20} {values}")
    typer.echo(f"  {'':<20} (loaded length {c['loaded_length']:.2f} m, f1 = {c['first_frequency']:.2f} Hz, "
               f"{c['n_axles']} axles)")


def _print_load_effects(s: dict[str, Any]) -> None:
    rows = [(kind, e) for kind in ("moment", "shear", "reaction") if kind in s for e in s[kind]["sections"]]
    if not rows:
        return
    method = next(s[k]["method"] for k in ("moment", "shear", "reaction") if k in s)
    typer.echo(f"  load effects ({method}; kN m / kN; IM beside AASHTO Std / JTG D60 / OHBDC)")
    for kind, e in rows:
        unit = 1e-3
        where = f"support {e['support']}" if kind == "reaction" else f"x = {e['x']:.2f} m"
        if e.get("girder"):
            where += f", girder {e['girder']}"
        c = e.get("code_allowances", {})
        typer.echo(f"    {kind:<8} {where:<24} static {e['static_peak'] * unit:+10.2f}  dynamic {e['dynamic_peak'] * unit:+10.2f}"
                   f"  IM {e['impact_factor']:7.4f}   codes {c.get('aashto_standard', float('nan')):.3f} / "
                   f"{c.get('jtg_d60_2015', float('nan')):.3f} / {c.get('ohbdc_1983', float('nan')):.3f}")


def _outputs(run: Any, as_json: bool, out: Optional[Path], plot: Optional[Path], summary_path: Optional[Path]) -> None:
    if out is not None:
        _guard(lambda: run.write_csv(out))
    if plot is not None:
        _guard(lambda: run.plot(plot))
    if summary_path is not None:
        _guard(lambda: _write_text(summary_path, _json(run.summary, indent=2) + "\n"))
    if as_json:
        typer.echo(_json(run.summary))
    else:
        _print_summary(run)
        for label, path in (("time histories", out), ("figure", plot), ("summary", summary_path)):
            if path is not None:
                typer.echo(f"  {label:<20} {path}")


@app.command()
def run(
    scenario: Path = typer.Argument(..., help="TOML scenario file."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object (the summary) on stdout."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write time histories to this CSV file."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write a figure (PNG/PDF/SVG) of the response."),
    summary_path: Optional[Path] = typer.Option(None, "--summary", help="Write the JSON summary to this file."),
    max_memory: Optional[str] = _MAX_MEMORY,
    max_steps: Optional[float] = _MAX_STEPS,
    out_dir: Optional[Path] = typer.Option(None, "--out-dir", help="Write all three (SCENARIO.csv, SCENARIO.png, "
                                           "SCENARIO.json) into this folder."),
) -> None:
    """Simulate one crossing described by a scenario file (writes files only when asked)."""
    from vbikit.scenario import load_scenario

    if out_dir is not None:
        stem = scenario.stem
        out, plot, summary_path = (out or out_dir / f"{stem}.csv", plot or out_dir / f"{stem}.png",
                                   summary_path or out_dir / f"{stem}.json")
    limits = _limits(max_memory, max_steps)
    _outputs(_execute(lambda: load_scenario(scenario), limits), as_json, out, plot, summary_path)


@app.command()
def validate(
    scenario: Path = typer.Argument(..., help="TOML scenario file."),
    max_memory: Optional[str] = _MAX_MEMORY,
    max_steps: Optional[float] = _MAX_STEPS,
) -> None:
    """Check a scenario file without running it: every check `vbikit run` makes before it
    integrates (files, parameters, time step and stability limit, memory and step budgets)."""
    from vbikit.scenario import load_scenario
    from vbikit.scenario.preflight import preflight
    from vbikit.solve.budget import human

    limits = _limits(max_memory, max_steps)
    plan = _guard(lambda: preflight(load_scenario(scenario), limits))
    _warn(plan.warnings)
    est = plan.estimate
    typer.echo(f"{scenario}: ok — {est.n_steps} steps of {est.dt:.3e} s ({plan.built.crossing.integrator}), "
               f"≈ {human(est.memory)}")


@app.command()
def cite(
    scenario: Path = typer.Argument(..., help="TOML scenario file."),
    bibtex: bool = typer.Option(False, "--bibtex", help="Print BibTeX entries instead of citations."),
) -> None:
    """Print the publications behind the models a scenario uses (docs/references.md has them all)."""
    from vbikit.references import bibtex as to_bibtex
    from vbikit.scenario import load_scenario
    from vbikit.scenario.cite import scenario_models, scenario_references

    spec = _guard(lambda: load_scenario(scenario))
    refs = scenario_references(spec)
    if bibtex:
        typer.echo(to_bibtex(refs), nl=False)
        return
    typer.echo(f"{scenario}: models {', '.join(scenario_models(spec))}")
    for r in refs:
        typer.echo(f"  [{r.key}] {r.text()}")


@app.command()
def demo(
    out_dir: Path = typer.Option(Path("vbikit-out"), "--out-dir", help="Where to write the figure and the JSON summary."),
    as_json: bool = typer.Option(False, "--json", help="Print the JSON summary instead of the text report."),
) -> None:
    """HS20-44 truck over the 16.76 m beam (Bridge 2 stand-in), ISO class C road, multipoint tires, 75 km/h."""
    from vbikit.scenario import demo_scenario_text, scenario_from_toml

    run_ = _execute(lambda: scenario_from_toml(demo_scenario_text(), source="demo.toml"))
    _outputs(run_, as_json, None, out_dir / "demo.png", out_dir / "demo.json")


@app.command("compare-tires")
def compare_tires(
    scenario: Path = typer.Argument(..., help="TOML scenario file (its [tire] section is replaced by each model)."),
    out_dir: Path = typer.Option(Path("vbikit-out"), "--out-dir", help="Where to write the figure and the table."),
    n_points: int = typer.Option(6, "--n-points", min=1, help="Points of the multi-point tire."),
    as_json: bool = typer.Option(False, "--json", help="Print the table as JSON."),
) -> None:
    """Run one crossing with each tire model (point, multipoint, disk, rigid disk); figure like the
    paper's Fig. 9 and a table of peaks and impact factors."""
    import time

    from vbikit.plot import plot_tire_comparison
    from vbikit.scenario import load_scenario

    base = _guard(lambda: load_scenario(scenario))
    models = {
        "point": {"model": "point"},
        f"multipoint (n = {n_points})": {"model": "multipoint", "n_points": n_points},
        "disk": {"model": "disk"},
        "rigid disk": {"model": "rigid-disk"},
    }
    responses, table = {}, {}
    for label, tire in models.items():
        spec = base.model_copy(update={"tire": base.tire.model_copy(update=tire)})
        spec._base_dir = base.base_dir
        t0 = time.perf_counter()
        run_ = _execute(lambda spec=spec: spec)
        s = run_.summary
        responses[label] = run_.response
        table[label] = {
            "max_dynamic_displacement": s["max_dynamic_displacement"],
            "impact_factor": s["impact_factor"],
            "max_dynamic_strain": s["max_dynamic_strain"],
            "strain_impact_factor": s["strain_impact_factor"],
            "max_abs_acceleration": s["max_abs_acceleration"],
            "min_tire_force": min(s["min_wheel_force"].values()),
            "contact_lost": any(v["lost"] for v in s["contact_loss"].values()),
            "seconds": time.perf_counter() - t0,
        }
    fig = _guard(lambda: plot_tire_comparison(responses, out_dir / "compare-tires.png", base.name))
    _guard(lambda: _write_text(out_dir / "compare-tires.json", _json(table, indent=2) + "\n"))
    if as_json:
        typer.echo(_json(table))
        return
    if base.name:
        typer.echo(base.name)
    typer.echo(f"  {'tire model':<20} {'u_max [mm]':>10} {'IM':>7} {'ε_max [µε]':>11} {'IM_ε':>7} {'|a|max':>8} {'F_min [kN]':>10} {'time [s]':>8}")
    for label, row in table.items():
        typer.echo(f"  {label:<20} {row['max_dynamic_displacement'] * 1e3:10.4f} {row['impact_factor']:7.4f} "
                   f"{row['max_dynamic_strain'] * 1e6:11.3f} {row['strain_impact_factor']:7.4f} "
                   f"{row['max_abs_acceleration']:8.4f} {row['min_tire_force'] / 1e3:10.2f} {row['seconds']:8.2f}")
    typer.echo(f"  figure {fig}; table {out_dir / 'compare-tires.json'}")


@app.command()
def presets() -> None:
    """List the bridge, vehicle, tire and road presets with their parameters."""
    from vbikit.bridge import BRIDGE_PRESETS
    from vbikit.road import ISO_CLASSES, PAPER_CLASSES
    from vbikit.vehicle import VEHICLE_PRESETS

    typer.echo("Bridges ([bridge] model = ...):")
    typer.echo("  beam                  Euler–Bernoulli beam: span, EI, mass_per_length, damping_ratio, n_modes, neutral_axis_depth")
    typer.echo("  continuous-beam       beam over several spans: spans (list), EI and mass_per_length (one or per span), "
               "support_stiffness, rotational_stiffness, [[bridge.damage]]")
    typer.echo("  modes-file            modes imported from a vbikit-modes file (modes_file = ...; docs/bridges.md)")
    for p in BRIDGE_PRESETS.values():
        b = p.build()
        typer.echo(f"  {p.name:<21} {p.description}")
        if hasattr(b, "EI"):
            typer.echo(f"  {'':<21} span {b.span} m, EI {b.EI:.4g} N·m², m {b.mass_per_length:.1f} kg/m, "
                       f"c {b.neutral_axis_depth:.3f} m, f1 {b.frequencies_hz[0]:.2f} Hz")
        else:  # slab-on-girder deck: geometry only (its modes are solved by `vbikit bridge NAME`)
            typer.echo(f"  {'':<21} span {b.span} m, deck {b.deck_width:.2f} m, default lateral_offset "
                       f"{b.default_lateral_offset} m, default response girder {b.default_girder}")
    typer.echo("Vehicles ([vehicle] model = ...):")
    for p in VEHICLE_PRESETS.values():
        v = p.example_vehicle()
        loads = ", ".join(f"{x / 1e3:.1f}" for x in v.static_wheel_loads())
        if p.required:
            params = (f"parameters: {', '.join(p.parameters)} (required: {', '.join(p.required)}); example "
                      + ", ".join(f"{k} = {val}" for k, val in p.example.items()))
        else:
            params = ", ".join(f"{k} = {val:g}" for k, val in v.parameters.items()) or "fixed parameters"
        f = v.natural_frequencies()
        freq = f"; frequencies {f.min():.2f} … {f.max():.2f} Hz" if f.size else ""
        typer.echo(f"  {p.name:<14} {v.description}; {v.n_dof} DOF; wheel loads [kN]: {loads}{freq}")
        typer.echo(f"  {'':<14} {params}")
    typer.echo("Tires ([tire] model = ...):")
    typer.echo("  point          single-point contact")
    typer.echo("  multipoint     n_points (default 6), contact_length (default 0.254 m), layout = ends | cells (paper Eq. 6)")
    typer.echo("  disk           deformable disk of radial springs, radius (default 0.5 m), disk_spacing (default 0.01 m)")
    typer.echo("  rigid-disk     rigid disk following the surface envelope, radius, disk_spacing")
    typer.echo("  all tires: loss_of_contact = true (default; tires cannot pull) | false")
    typer.echo("Deck defects ([[road.defects]] kind = ...):")
    from vbikit.road import DEFECT_DEFAULTS

    for kind, (amp, length, ramp, shape) in DEFECT_DEFAULTS.items():
        size = "depth" if amp < 0 else "height"
        typer.echo(f"  {kind:<14} {size} {abs(amp):g} m, length {length:g} m, ramp {ramp:g} m, shape {shape}")
    typer.echo("Roads ([road] class = ...):")
    classes = ", ".join(f"{c} {v:.4g}" for c, v in ISO_CLASSES.items())
    typer.echo(f"  ISO 8608 Gd(n0 = 0.1 cycle/m) [m³/cycle]: {classes}")
    typer.echo(f"  paper names: {', '.join(f'{k} = {v}' for k, v in PAPER_CLASSES.items())}; none = smooth; "
               "psd = explicit phi0, n0, exponent; profile_file = measured CSV (x, elevation)")


@app.command()
def bridge(
    name: str = typer.Argument(..., help="Bridge preset (see `vbikit presets`), or a scenario file (.toml) whose [bridge] "
                               "is shown (its [bridge.deck] overrides and n_modes included, unless --modes is given)."),
    n_modes: Optional[int] = typer.Option(None, "--modes", min=1, max=500,
                                          help="Number of modes to solve and list (1 … 500; default 10, or the scenario's n_modes)."),
    out_dir: Path = typer.Option(Path("vbikit-out"), "--out-dir", help="Where to write the figure NAME-modes.png."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the figure to this file instead."),
    no_plot: bool = typer.Option(False, "--no-plot", help="Do not write the figure."),
) -> None:
    """Frequencies and mode descriptions of a bridge preset or of a scenario's bridge, and a figure of its
    first mode shapes."""
    import time

    from vbikit.bridge import BRIDGE_PRESETS

    if name.endswith(".toml"):
        from vbikit.scenario import load_scenario
        from vbikit.scenario.build import build_bridge

        def scenario_bridge():
            scenario = load_scenario(name)
            spec = scenario.bridge if n_modes is None else scenario.bridge.model_copy(update={"n_modes": n_modes})
            return build_bridge(spec, scenario.base_dir), scenario.bridge.model, scenario.name or Path(name).stem

        b, model, label = _guard(scenario_bridge)
        skew = float(getattr(b, "skew", 0.0))
        description = f"[bridge] of {name} (model {model!r}{f', skew {skew:g}°' if skew else ''})"
        name = Path(name).stem
    elif name not in BRIDGE_PRESETS:
        typer.echo(f"error: unknown bridge preset {name!r}; allowed: {', '.join(BRIDGE_PRESETS)} (or a scenario .toml file)",
                   err=True)
        raise typer.Exit(code=2)
    else:
        b = BRIDGE_PRESETS[name].build(n_modes=10 if n_modes is None else n_modes)
        description = BRIDGE_PRESETS[name].description
    t0 = time.perf_counter()
    freqs = b.frequencies_hz
    elapsed = time.perf_counter() - t0
    describe = getattr(b, "mode_descriptions", None)
    labels = describe() if describe else [f"bending, {k + 1} half-wave{'s' if k else ''} along the span" for k in range(freqs.size)]
    typer.echo(f"{name}: {description}")
    if hasattr(b, "girder_y"):
        ys = ", ".join(f"{y:+.3f}" for y in b.girder_y)
        typer.echo(f"  girders (1 … {b.n_girders}) at y = {ys} m; {b.element_count} elements along the span")
    typer.echo(f"  modes solved (or read from cache) in {elapsed:.3f} s")
    for k, (f, label) in enumerate(zip(freqs, labels), start=1):
        typer.echo(f"  mode {k:>2}  {f:9.3f} Hz  {label}")
    if not no_plot:
        from vbikit.plot.bridge import plot_mode_shapes

        path = _guard(lambda: plot_mode_shapes(b, plot or out_dir / f"{name}-modes.png", title=name))
        typer.echo(f"  figure              {path}")


@app.command("field")
def field_(
    field_file: Path = typer.Argument(..., help="FIELD.toml describing the measured crossings (docs/field.md)."),
    out_dir: Path = typer.Option(Path("vbikit-out"), "--out-dir", help="Where to write the figures and the metrics tables."),
    tires: str = typer.Option("point,multipoint", "--tires", help="Comma-separated tire models: point, multipoint, disk, rigid-disk."),
    calibrate: bool = typer.Option(False, "--calibrate", help="Fit a stiffness factor and damping ratio (least squares)."),
) -> None:
    """Compare measured bridge responses with the simulated crossing per tire model; optionally calibrate."""
    from vbikit.field.report import run_field
    from vbikit.field.workflow import parse_tires

    names = _guard(lambda: parse_tires(tires))
    run_ = _guard(lambda: run_field(field_file, out_dir, names, calibrate))
    typer.echo(run_.spec.name)
    for label, cmps in (("nominal model", run_.comparisons), ("calibrated model", run_.calibrated or [])):
        for c in cmps:
            typer.echo(f"  [{label}] {c.case.name}: time shift {c.shift:+.4f} s (trigger {c.t_entry - c.shift:.4f} s), "
                       f"low-pass {c.lowpass_hz or 'none'} Hz")
            for ch, d in c.drift.items():
                typer.echo(f"    {ch}: removed offset {d.offset:+.4g}, drift {d.drift:+.4g} /s ({d.method})")
            typer.echo(f"    {'tire':<11} {'channel':<16} {'peak err':>9} {'RMS err':>11} {'nRMS':>7} {'corr':>7}")
            for tire, chans in c.metrics.items():
                for name, m in chans.items():
                    typer.echo(f"    {tire:<11} {name:<16} {m['peak_error']:+9.3%} {m['rms_error']:11.4g} "
                               f"{m['normalised_rms_error']:7.4f} {m['correlation']:7.4f}")
    cal = run_.calibration
    if cal is not None:
        typer.echo(f"  calibration ({cal.tire} tire, {cal.evaluations} runs, {cal.seconds:.1f} s): stiffness factor "
                   f"{cal.stiffness_factor:.5f} ± {cal.stiffness_factor_std:.2g}, damping ratio {cal.damping_ratio:.5f} "
                   f"± {cal.damping_ratio_std:.2g} (1σ, correlation {cal.correlation:+.2f})")
    typer.echo(f"  figures {', '.join(str(f) for f in run_.figures)}; tables {run_.json_path}, {run_.csv_path}")


def main() -> None:
    """Console-script entry point."""
    app()


if __name__ == "__main__":  # pragma: no cover
    main()
