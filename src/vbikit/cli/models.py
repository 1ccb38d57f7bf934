"""``vbikit presets`` and ``vbikit bridge``: the models a scenario can name."""
from __future__ import annotations

from pathlib import Path
from typing import Any, Optional

import typer

from vbikit.cli.guard import figure_file_option, guard, out_dir_option


def presets() -> None:
    """List the bridge, vehicle, tire and road presets with their parameters."""
    from vbikit.bridge import BRIDGE_PRESETS, EulerBernoulliBeam
    from vbikit.outputs import report_unit
    from vbikit.road import ISO_CLASSES, PAPER_CLASSES
    from vbikit.scenario.bridge_spec import BeamSpec, ContinuousBeamSpec
    from vbikit.vehicle import TRAIN_PRESETS, VEHICLE_PRESETS

    typer.echo("Bridges ([bridge] model = ...; parameters in SI units, as a scenario takes them):")
    typer.echo("  beam                  Euler–Bernoulli beam: " + _keys(BeamSpec, ("span", "EI", "mass_per_length",
                                                                           "damping_ratio", "n_modes", "neutral_axis_depth")))
    typer.echo("  continuous-beam       beam over several spans: " + _keys(ContinuousBeamSpec, ("spans",))
               + " (list), " + _keys(ContinuousBeamSpec, ("EI",)) + " and " + _keys(ContinuousBeamSpec, ("mass_per_length",))
               + " (one or per span), " + _keys(ContinuousBeamSpec, ("support_stiffness", "rotational_stiffness"))
               + ", [[bridge.damage]]")
    typer.echo("  modes-file            modes imported from a vbikit-modes file (modes_file = ...; docs/bridges.md)")
    for p in BRIDGE_PRESETS.values():
        b = p.build()
        typer.echo(f"  {p.name:<21} {p.description}")
        if isinstance(b, EulerBernoulliBeam):
            typer.echo(f"  {'':<21} span {b.span} m, EI {b.EI:.4g} N·m², m {b.mass_per_length:.1f} kg/m, "
                       f"c {b.neutral_axis_depth:.3f} m, f1 {b.frequencies_hz[0]:.2f} Hz")
        else:  # slab-on-girder deck: geometry only (its modes are solved by `vbikit bridge NAME`)
            typer.echo(f"  {'':<21} span {b.span} m, deck {b.deck_width:.2f} m, default lateral_offset "
                       f"{b.default_lateral_offset} m, default response girder {b.default_girder}")
    typer.echo(f"Vehicles ([vehicle] model = ...; parameters in SI units, as a scenario takes them; static loads in "
               f"{report_unit('N')[0]}: per wheel for road vehicles, per axle for trains):")
    for p in VEHICLE_PRESETS.values():
        v = p.example_vehicle()
        train = p.name in TRAIN_PRESETS  # a train's wheel is one axle (train_vehicle)
        loads = _load_list(v.static_wheel_loads(), "axle" if train else "wheel")
        if p.required:
            params = (f"parameters: {', '.join(_named(k) for k in p.parameters)} (required: {', '.join(p.required)}); "
                      "example " + ", ".join(f"{k} = {val}{_unit_after(k)}" for k, val in p.example.items()))
        elif p.parameters:
            params = ", ".join(f"{k} = {val:g}{_unit_after(k)}" for k, val in v.parameters.items())
        else:  # what the fixed model states of itself, not keys a scenario can set (its loads: the line above)
            stated = ", ".join(f"{k} {val:g}{_unit_after(k)}" for k, val in v.parameters.items()
                               if k not in STATED_BY_LOADS)
            params = f"fixed parameters ({stated})" if stated else "fixed parameters"
        f = v.natural_frequencies()
        freq = f"; frequencies {f.min():.2f} … {f.max():.2f} Hz" if f.size else ""
        typer.echo(f"  {p.name:<14} {v.description}; {v.n_dof} DOF; {loads}{freq}")
        typer.echo(f"  {'':<14} {params}")
    typer.echo("Tires ([tire] model = ...):")
    from vbikit.contact import tire_catalogue

    for name, line in tire_catalogue():
        typer.echo(f"  {name:<14} {line}")
    typer.echo("  all tires: loss_of_contact = true (default; tires cannot pull) | false")
    typer.echo("Deck defects ([[road.defects]] kind = ...):")
    from vbikit.road import DEFECT_DEFAULTS

    for kind, (amp, length, ramp, shape) in DEFECT_DEFAULTS.items():
        size = "depth" if amp < 0 else "height"
        ramps = f"ramp {ramp:g} m" if ramp > 0 else "no ramp (ramp is for trapezoid and step shapes)"
        typer.echo(f"  {kind:<14} {size} {abs(amp):g} m, length {length:g} m, {ramps}, shape {shape}")
    typer.echo("Roads ([road] class = ...):")
    classes = ", ".join(f"{c} {v:.4g}" for c, v in ISO_CLASSES.items())
    typer.echo(f"  ISO 8608 Gd(n0 = 0.1 cycle/m) [m³/cycle]: {classes}")
    typer.echo(f"  paper names: {', '.join(f'{k} = {v}' for k, v in PAPER_CLASSES.items())}; none = smooth; "
               "psd = explicit phi0, n0, exponent; profile_file = measured CSV (x, elevation)")


def bridge(
    name: str = typer.Argument(..., metavar="PRESET|SCENARIO.toml",
                               help="Bridge preset (see `vbikit presets`), or a file (.toml) whose [bridge] is shown "
                               "(a scenario, a traffic base or a [bridge] alone; its [bridge.deck] overrides and "
                               "n_modes included, unless --modes is given)."),
    n_modes: Optional[int] = typer.Option(None, "--modes", min=1, max=500,
                                          help="Number of modes to solve and list (1 … 500; default 10, or the scenario's n_modes)."),
    out_dir: Optional[Path] = out_dir_option("Where to write the figure NAME-modes.png (default vbikit-out; not used "
                                             "with --plot or --no-plot).", default=None),
    plot: Optional[Path] = figure_file_option("Write the figure to this file instead."),
    no_plot: bool = typer.Option(False, "--no-plot", help="Do not write the figure."),
    as_json: bool = typer.Option(False, "--json", help="Print the frequencies, mode descriptions and mesh check as JSON "
                                 "on standard output (every other line on standard error)."),
) -> None:
    """Frequencies and mode descriptions of a bridge preset or of a scenario's bridge, and a figure of its
    first mode shapes."""
    import time

    from vbikit.cli.guard import check_out_dir, say, say_json, use_json

    use_json(as_json)

    if out_dir is None and plot is None and not no_plot:  # the default folder, checked only when it is written to
        out_dir = check_out_dir(Path("vbikit-out"))

    from vbikit.bridge import BRIDGE_PRESETS, DescribesModes, GirderDeck

    if name.endswith(".toml"):
        from vbikit._toml import read_toml
        from vbikit.errors import VbikitError
        from vbikit.scenario import ScenarioError
        from vbikit.scenario.build import build_bridge
        from vbikit.scenario.schema import parse_bridge

        def scenario_bridge():
            # the file's [bridge] alone: a scenario, a traffic stream's base (no vehicle) or a bridge-only file alike,
            # as vbikit traffic --bridge and a railway file's bridge.scenario read it
            data = read_toml(name, ScenarioError, "scenario file")
            table = data.get("bridge")
            if not isinstance(table, dict) or not table:
                raise ScenarioError(f"{name}: missing required table [bridge] (the bridge this command shows)")
            spec = parse_bridge(table if n_modes is None else {**table, "n_modes": n_modes})
            try:
                bridge_ = build_bridge(spec, Path(name).resolve().parent)
            except VbikitError:
                raise
            except ValueError as err:  # the bridge model's own check of the [bridge] inputs (as in scenario.build)
                raise ScenarioError(str(err)) from None
            title = data.get("name")
            return bridge_, spec.model, title if isinstance(title, str) and title else Path(name).stem

        from vbikit.cli.validate import check_kind

        # (the files whose [bridge] is a scenario's: a railway file's is its own, a field file's names a preset)
        check_kind(Path(name), "bridge", ("scenario", "traffic-base", "driveby", "lifetime"))
        b, model, label = guard(scenario_bridge, file=Path(name))
        skew = float(b.skew)
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
    labels = b.mode_descriptions() if isinstance(b, DescribesModes) else [f"bending, {k + 1} half-wave{'s' if k else ''} along the span" for k in range(freqs.size)]
    say(f"{name}: {description}")
    girders = {}
    if isinstance(b, GirderDeck):
        ys = ", ".join(f"{y:+.3f}" for y in b.girder_y)
        elements = getattr(b, "element_count", None)  # grillage models: their mesh
        say(f"  girders (1 … {b.n_girders}) at y = {ys} m" + (f"; {elements} elements along the span" if elements else ""))
        girders = {"girder_y": [float(y) for y in b.girder_y], **({"elements": int(elements)} if elements else {})}
    say(f"  modes solved (or read from cache) in {elapsed:.3f} s")
    for k, (f, label) in enumerate(zip(freqs, labels), start=1):
        say(f"  mode {k:>2}  {f:9.3f} Hz  {label}")
    check = mesh_check(b)
    if check is not None:  # how good the listed frequencies are: a grillage's mesh (a beam's modes are exact)
        finer, change = check
        say(f"  mesh check           with twice the elements ({finer}) the listed frequencies change by at most "
            f"{change:.1e} (relative); the mesh's own error is about 4/3 of that (O(h²) convergence, docs/bridges.md)")
    path = None
    if not no_plot:
        from vbikit.plot.bridge import plot_mode_shapes

        path = guard(lambda: plot_mode_shapes(b, plot or Path(out_dir) / f"{name}-modes.png", title=name))
        say(f"  figure              {path}")
    say_json({"bridge": name, "description": description, **girders,
              "frequencies_hz": [float(f) for f in freqs], "modes": list(labels),
              "mesh_check": None if check is None else {"elements_doubled": check[0], "largest_change": check[1]},
              **({"figure": str(path)} if path is not None else {}),
              "units": {"frequencies_hz": "Hz", "girder_y": "m", "largest_change": "1"}})


def mesh_check(bridge: Any) -> Optional[tuple[int, float]]:
    """(elements, change): a meshed deck (``n_elements``, e.g. ``GirderDeck``) solved again with twice its elements along
    the span, and the largest relative change of its listed frequencies; None for a bridge without a mesh (a beam's
    modes are closed-form).  The grillage converges as O(h²) (docs/bridges.md, "Mesh convergence"), so the mesh's
    own error is about 4/3 of this change (Richardson: e_h ≈ (f_h − f_h/2) · 2² / (2² − 1)).  (Twice, not half: an
    odd element count breaks the symmetry of the even default mesh, and its higher modes move by a percent.)"""
    import dataclasses

    import numpy as np

    if not dataclasses.is_dataclass(bridge) or "n_elements" not in {f.name for f in dataclasses.fields(bridge)} \
            or not hasattr(bridge, "element_count"):
        return None
    finer = dataclasses.replace(bridge, n_elements=2 * int(bridge.element_count))
    given, refined = np.asarray(bridge.frequencies_hz, float), np.asarray(finer.frequencies_hz, float)
    n = min(given.size, refined.size)
    return int(finer.element_count), float(np.max(np.abs(refined[:n] - given[:n]) / given[:n]))


#: numbers a vehicle states of itself that its load list already gives (count and total)
STATED_BY_LOADS = frozenset({"n_axles", "total_load", "gross_weight"})


def _keys(spec, names) -> str:
    """Scenario keys of a schema model, each with its SI unit from its description
    (``vbikit._words.split_unit``): "span [m], EI [N m²], damping_ratio"."""
    from vbikit._words import split_unit

    out = []
    for name in names:
        unit = split_unit(spec.model_fields[name].description or "")[1]
        out.append(f"{name} [{unit}]" if unit else name)
    return ", ".join(out)


def _unit_after(name: str) -> str:
    """" kg" after a vehicle parameter's value (``vbikit.vehicle.presets.PARAMETER_UNITS``; nothing for a
    dimensionless one)."""
    from vbikit.vehicle.presets import parameter_unit

    unit = parameter_unit(name)
    return f" {unit}" if unit and unit != "-" else ""


def _named(name: str) -> str:
    """A vehicle parameter's name with its SI unit: "axle_loads [N]" (dimensionless: the name alone)."""
    unit = _unit_after(name).strip()
    return f"{name} [{unit}]" if unit else name


#: a preset's static loads are listed one by one up to this many; a train's are summarised
LISTED_LOADS = 12


def _load_list(loads, per: str) -> str:
    """A preset's static loads [N] in the report's force unit (``vbikit.outputs.report_unit``: kN),
    one a ``per`` ("wheel": a road vehicle's, "axle": a train's), labelled so: "load per wheel [kN]:
    15.4, 15.4, …; total 300.9", each listed, or for more than ``LISTED_LOADS`` (the HSLM trains'
    36–50 axles) "load per axle [kN]: 50 axles, 170.0 each; total 8500"."""
    from vbikit.outputs import report_unit

    unit, k = report_unit("N")
    shown = [x * k for x in loads]
    if len(shown) <= LISTED_LOADS:
        return f"load per {per} [{unit}]: " + ", ".join(f"{x:.1f}" for x in shown) + f"; total {sum(shown):.1f}"
    low, high = min(shown), max(shown)
    each = f"{low:.1f} each" if high == low else f"{low:.1f} … {high:.1f}"
    return f"load per {per} [{unit}]: {len(shown)} {per}s, {each}; total {sum(shown):.0f}"
