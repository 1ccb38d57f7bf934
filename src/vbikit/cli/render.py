"""Output of the scenario commands: the text report, JSON, the CSV of time histories and the
files ``--out``, ``--plot`` and ``--summary`` ask for."""
from __future__ import annotations

import math

from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional

import typer

from vbikit.cli.guard import guard, say

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.scenario.report import Report as Run

#: design codes of the text report, in the order printed
CODE_LABELS = {"aashto_lrfd": "AASHTO LRFD", "aashto_standard": "AASHTO Std", "csa_s6": "CSA S6",
               "ohbdc_1983": "OHBDC 1983", "jtg_d60_2015": "JTG D60-2015"}


def json_text(obj: object, indent: int | None = None) -> str:
    """Strict JSON (no NaN/Infinity: those are null, see vbikit._files.json_safe)."""
    from vbikit._files import json_text as strict_json

    return strict_json(obj, indent)


def write_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    from vbikit._files import write_text as atomic_text

    atomic_text(path, text)


def print_summary(run: Run) -> None:
    """The text report of one crossing (``vbikit run`` without ``--json``)."""
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
        deck = "".join(f", {k} {v}" for k, v in inp.get("bridge_deck", {}).items() if k != "span")  # (span: below)
        several_spans = len(inp.get("bridge_deck", {}).get("spans", [])) > 1
        length = f"length {inp['span']:g} m" if several_spans else f"span {inp['span']:g} m"  # (the deck's whole length)
        typer.echo(f"  bridge               {inp['bridge']} ({length}, {inp['n_modes']} modes, "
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
    from vbikit.outputs import report_unit

    (length_unit, to_length), (force_unit, to_force) = report_unit("m"), report_unit("N")  # mm, kN
    typer.echo(f"  max displacement     dynamic {s['max_dynamic_displacement'] * to_length:+.4f} {length_unit}, "
               f"static {s['max_static_displacement'] * to_length:+.4f} {length_unit}")
    from vbikit.analysis.checks import find_flag, has_flag

    # the marks come from the flags' codes (vbikit.analysis.checks.FLAG_CODES), never from the warnings' words
    airborne, strain_off = has_flag(s, "airborne_wheels"), has_flag(s, "strain_not_converged")
    strain_mark = "!" if strain_off else ""  # the modes' strain peaks are off too, not only their IM
    typer.echo(f"  max strain           dynamic {s['max_dynamic_strain'] * 1e6:+.3f} µε{strain_mark}, static "
               f"{s['max_static_strain'] * 1e6:+.3f} µε{strain_mark}")
    typer.echo(f"  max |acceleration|   {s['max_abs_acceleration']:.4f} m/s²{'!' if acceleration_in_doubt(s, 0) else ''} "
               "(the deck's, at the response point)")
    typer.echo(f"  time steps           {s['n_steps']} × {s['dt']:.3e} s ({s['integrator']})")
    step_line(s)
    start_line(s)
    coarse = coarse_step(s)
    implausible = has_flag(s, "implausible_deflection")
    doubt, strain_doubt = impact_doubts(s)
    typer.echo(f"  IMPACT FACTOR        IM = {im_text(s['impact_factor'])}{'!' if doubt else ''}  "
               f"(strain IM = {im_text(s['strain_impact_factor'])}{'!' if strain_doubt else ''})")
    if implausible:
        typer.echo(f"  {'':<20} ! implausible: the static deflection is far beyond any bridge's under this load — "
                   "check the units of the bridge's stiffness and mass (see the first warning); no result of this "
                   "run is meaningful")
    if airborne:
        typer.echo(f"  {'':<20} ! unreliable: wheels left the road on the bridge; the IM is dominated by their "
                   "landing impacts, not a design value — see the warning")
    if coarse:
        typer.echo(f"  {'':<20} ! unreliable: the given crossing.dt is too coarse for this crossing (leave it out for "
                   "the automatic step) — see the warning")
    if strain_off:
        typer.echo(f"  {'':<20} ! unreliable strain and strain IM: the strain is not converged in the modes — see "
                   "the warning (what to do: more modes on a beam; on a girder deck sign with the moment IM, not the deflection IM)")
        moment = _moment_at(s, s["response_x"])
        if "governing_girder" in s and moment is not None:
            girder = f", girder {moment['girder']}" if moment.get("girder") else ""
            typer.echo(f"  {'':<20}   the moment IM at x = {moment['x']:.2f} m{girder}: {im_text(moment['impact_factor'])}")
    realisation = find_flag(s, "one_realisation")
    if realisation is not None:
        seed = "" if realisation.get("value") is None else f" (seed {realisation['value']:.0f})"
        typer.echo(f"  {'':<20} note: one realisation of the random road{seed}; other seeds give other IMs — "
                   "`vbikit run --random` for the mean, σ and quantiles")
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION

    # the run's one judgement of the small static references: its small_static flags (girders and points)
    small_girders = [has_flag(s, "small_static", output="impact_factor", girder=g)
                     for g in range(1, len(s.get("girder_max_static_displacement", [])) + 1)]
    small_points = [has_flag(s, "small_static", output="impact_factor", point=p["name"]) for p in s["points"]]
    if len(s["points"]) > 1:
        print_points(s["points"], small_points, [acceleration_in_doubt(s, i) for i in range(len(s["points"]))])
    for i, v in enumerate(s.get("vehicles", []), start=1):
        loads = " / ".join(f"{f * to_force:.1f}" for f in v["static_wheel_loads"].values())
        typer.echo(f"  vehicle {i:<12} {v['model']}, {v['direction']} at {v['speed'] * 3.6:.1f} km/h, enters at "
                   f"t = {v['entry_time']:.3f} s, y = {v['lateral_offset']:+.3f} m; wheel loads [{force_unit}] {loads}"
                   f"{'; lost contact' if v['contact_loss'] else ''}")
    if "governing_girder" in s:
        if "vehicles" not in s:
            typer.echo(f"  vehicle lateral      y = {s['lateral_offset']:.3f} m")
        typer.echo("  girder               " + "  ".join(f"{g:>7d}" for g in range(1, len(s["girder_y"]) + 1)))
        typer.echo(f"  {f'static max [{length_unit}]':<20} "
                   + "  ".join(f"{v * to_length:+7.3f}" for v in s["girder_max_static_displacement"]))
        typer.echo("  IM                   " + " ".join(f"{v:7.4f}{'!' if f else ' '}"
                                                      for v, f in zip(s["girder_impact_factors"], small_girders)).rstrip())
        if any(small_girders):
            typer.echo(f"  {'':<20} ! unreliable: static deflection under {SMALL_STATIC_FRACTION:.0%} of the largest "
                       "of the girders and points (a lightly loaded girder); not a design value — see the warning")
        typer.echo(f"  governing girder     {s['governing_girder']} (IM = {s['governing_girder_impact_factor']:.4f}"
                   f"{'!' if doubt else ''})")
    print_codes(s["design_code_allowances"], "deflection IM beside", several=bool(s.get("vehicles")))
    print_load_effects(s)
    print_negative_note(negative_impact(s))


def unsettled_outputs(s: dict[str, Any]) -> set[str]:
    """The outputs the step checks found unconverged: the ``step_not_converged`` flags' and every peak
    acceleration of the half-step check above its tolerance (``step_check.accelerations_not_converged``)."""
    named = {f.get("output") for f in s.get("flags", []) if f["code"] == "step_not_converged"}
    return (named | set((s.get("step_check") or {}).get("accelerations_not_converged", []))) - {None}


def acceleration_in_doubt(s: dict[str, Any], i: int) -> bool:
    """Whether the peak acceleration of response point ``i`` (0: the headline one, also the summary's top-level
    ``max_abs_acceleration``) is in doubt: a given step flagged too coarse, or the step checks found it unconverged."""
    names = {f"points[{s['points'][i]['name']}].max_abs_acceleration"} | ({"max_abs_acceleration"} if i == 0 else set())
    return coarse_step(s) or bool(names & unsettled_outputs(s))


def impact_doubts(s: dict[str, Any]) -> tuple[bool, bool]:
    """Whether the headline deflection IM and strain IM of a run's summary are in doubt (the report's "!"): wheels
    airborne on the bridge, a given step flagged too coarse, an implausible static deflection; the strain IM also
    when the modes' strain is not converged."""
    from vbikit.analysis.checks import has_flag

    doubt = has_flag(s, "airborne_wheels") or coarse_step(s) or has_flag(s, "implausible_deflection")
    return doubt, doubt or has_flag(s, "strain_not_converged")


def coarse_step(s: dict[str, Any]) -> bool:
    """Whether the run's given step is flagged too coarse for it (``coarse_step``, ``unresolved_modes``)."""
    from vbikit.analysis.checks import has_flag

    return has_flag(s, "coarse_step") or has_flag(s, "unresolved_modes")


def _moment_at(s: dict[str, Any], x: float) -> dict[str, Any] | None:
    """The run's moment section at ``x`` [m] (within 1 mm), if it reports one."""
    sections = [e for e in s.get("moment", {}).get("sections", []) if abs(float(e["x"]) - x) <= 1e-3]
    return sections[0] if sections else None


def negative_impact(s: dict[str, Any]) -> bool:
    """Whether the text report of summary ``s`` prints a negative impact factor."""
    ims = [s.get("impact_factor"), s.get("strain_impact_factor"), *s.get("girder_impact_factors", [])]
    ims += [p.get(k) for p in s.get("points", []) for k in ("impact_factor", "strain_impact_factor")]
    ims += [e.get("impact_factor") for kind in ("moment", "shear", "reaction") if kind in s for e in s[kind]["sections"]]
    return any(v is not None and v < 0 for v in ims)


def print_negative_note(negative: bool) -> None:
    """The one-line note on negative impact factors (``vbikit.analysis.checks.NEGATIVE_IM_NOTE``),
    when the report has one (``say``: standard error under ``--json``)."""
    if negative:
        from vbikit.analysis.checks import NEGATIVE_IM_NOTE

        say(f"  note: {NEGATIVE_IM_NOTE}")


def step_line(s: dict) -> None:
    """The step check's lines (``vbikit.scenario.step_check.half_step_check``, or ``converge_step``'s halving for load
    effects or a train: ``step_check_words``): how much the impact factors and the peak deck accelerations change;
    "not run" at a given crossing.dt."""
    from vbikit.scenario.step_check import DT_GIVEN_WORDS, percent_words, step_check_words

    check = s.get("step_check")
    if not check:
        if s.get("inputs", {}).get("dt_given"):  # (a scenario's run at its own crossing.dt)
            typer.echo(f"  step check           {DT_GIVEN_WORDS}")
        return
    typer.echo(f"  step check           {step_check_words(check)}")
    if check.get("acceleration_change") is not None:  # (a summary written before the accelerations were checked: none)
        where = f" ({check['acceleration_output']})" if check.get("acceleration_output") else ""
        typer.echo(f"                       the peak deck accelerations by at most {percent_words(check['acceleration_change'])} "
                   f"of their values{where}")


def start_line(s: dict) -> None:
    """The start check's line (``vbikit.solve.run_in.start_settling``): what share of the vehicles' start
    transient is left when they reach the bridge, and the run-in that settles it; nothing on a smooth road
    (the vehicles start in their static equilibrium on it) or for moving forces."""
    from vbikit.solve.run_in import SETTLED_TRANSIENT_LEFT

    left, needed = s.get("start_transient_left"), s.get("start_settling_run_in")
    if left is None or not math.isfinite(left) or left <= 0.0:
        return
    run_in = float(s["inputs"]["run_in"] if "inputs" in s else s.get("run_in", 0.0))  # (a random run's summary: run_in)
    start = f"run-in {run_in:g} m" if run_in > 0 else "at rest (crossing.run_in = 0, the paper's start)"
    if left <= SETTLED_TRANSIENT_LEFT:
        typer.echo(f"  start                {start}: {left:.1%} of the start transient left at the bridge (settled)")
        return
    remedy = (f"crossing.run_in = {math.ceil(needed):g} m leaves {SETTLED_TRANSIENT_LEFT:.0%}" if math.isfinite(needed)
              else "an undamped vehicle mode the road excites never settles")
    whose = "the vehicles'" if s.get("vehicles") else "the vehicle's"
    typer.echo(f"  start                {start}: {left:.0%} of {whose} start transient is left at the bridge, "
               f"part of this IM; {remedy}")


def im_text(value: float) -> str:
    """An impact factor to 4 decimals, a value that rounds to zero printed as 0.0000 (not −0.0000)."""
    return f"{0.0 if abs(value) < 5e-5 else value:.4f}"


def print_codes(c: dict[str, Any], title: str, several: bool = False) -> None:
    """One line of design-code dynamic allowances and one of the inputs they were computed from (a
    railway vehicle: EN 1991-2 Φ2 / Φ3 and a pointer to ``vbikit rail`` instead of the highway codes)."""
    if c.get("railway"):
        typer.echo(f"  {title:<20} EN 1991-2 Phi2 {c['en1991_2_phi2']:.3f}  Phi3 {c['en1991_2_phi3']:.3f}")
        typer.echo(f"  {'':<20} (railway vehicle: no highway allowances; Phi2 / Phi3 of 6.4.5.2 for L_Phi = "
                   f"{c['loaded_length']:.2f} m (the loaded length: EN 1991-2 Table 6.2 lengthens L_Phi for continuous "
                   "decks, which would lower them) are factors 1 + phi of LM71, not of this train: its resonance check "
                   "is `vbikit rail`, EN 1991-2 6.4.6)")
        return
    values = "  ".join(f"{label} {c[k]:.3f}" for k, label in CODE_LABELS.items() if k in c)
    typer.echo(f"  {title:<20} {values}")
    n = c["n_axles"]
    typer.echo(f"  {'':<20} (loaded length {c['loaded_length']:.2f} m and f1 = {c['first_frequency']:.2f} Hz; CSA S6 "
               f"by {n} axle{'' if n == 1 else 's'}, the most axles on a span of the loaded length at once"
               + ("; several vehicles' axles as placed, at one offset counted once)" if several else ")"))


def print_load_effects(s: dict[str, Any]) -> None:
    """The moment / shear / reaction table of a summary (nothing when it has none)."""
    rows = [(kind, e) for kind in ("moment", "shear", "reaction") if kind in s for e in s[kind]["sections"]]
    if not rows:
        return
    method = next(s[k]["method"] for k in ("moment", "shear", "reaction") if k in s)
    keys = ("en1991_2_phi2", "en1991_2_phi3") if rows[0][1].get("code_allowances", {}).get("railway") else \
        ("aashto_standard", "jtg_d60_2015", "ohbdc_1983")
    beside = "EN 1991-2 Phi2 / Phi3" if keys[0] == "en1991_2_phi2" else "AASHTO Std / JTG D60 / OHBDC"
    from vbikit.outputs import report_unit

    (moment_unit, _), (force_unit, _) = report_unit("N m"), report_unit("N")
    typer.echo(f"  load effects ({method}; {moment_unit} / {force_unit}; IM beside {beside})")
    # the marks come from the flags (their subject is the effect's label), never from the warnings' words
    unresolved = {f.get("subject") for f in s.get("flags", []) if f["code"] == "effect_step"} - {None}
    # a given step too coarse, wheels airborne or an implausible deflection: every IM of the run in doubt (as the headline's)
    every_doubted = impact_doubts(s)[0]
    hogging_jtg = False
    for kind, e in rows:
        unit = report_unit("N m" if kind == "moment" else "N")[1]
        where = f"support {e['support']}" if kind == "reaction" else f"x = {e['x']:.2f} m"
        if e.get("girder"):
            where += f", girder {e['girder']}"
        c = e.get("code_allowances", {})
        mark = "!" if e.get("label") in unresolved or every_doubted else " "
        jtg = kind == "moment" and e.get("hogging_region") and "jtg_d60_2015" in keys
        hogging_jtg |= bool(jtg)
        codes = " / ".join(f"{c.get(k, float('nan')):.3f}{'?' if jtg and k == 'jtg_d60_2015' else ''}" for k in keys)
        typer.echo(f"    {kind:<8} {where:<24} static {e['static_peak'] * unit:+10.2f}  dynamic {e['dynamic_peak'] * unit:+10.2f}"
                   f"  IM {im_text(e['impact_factor']):>7}{mark}  codes " + codes)
        if e.get("opposite_impact_factor") is not None:  # both signs (vbikit.analysis.effects): the other extreme
            typer.echo(f"    {'':<8} {'and ' + e['opposite_sense']:<24} "
                       f"static {e['opposite_static_peak'] * unit:+10.2f}  dynamic {e['opposite_dynamic_peak'] * unit:+10.2f}"
                       f"  IM {im_text(e['opposite_impact_factor']):>7}   (the {e['governing']} dynamic peak governs)")
    if any(e.get("label") in unresolved for _, e in rows):
        typer.echo(f"    {'':<8} ! the step does not resolve this load effect: its IM may be off — see the warning")
    if hogging_jtg:
        from vbikit.analysis.codes import jtg_d60_2015

        f2 = s["frequencies_hz"][1] if len(s.get("frequencies_hz", [])) > 1 else None
        other = f": μ(f2 = {f2:.2f} Hz) = {jtg_d60_2015(f2):.3f}" if f2 is not None and math.isfinite(f2) and f2 > 0 else ""
        typer.echo(f"    {'':<8} ? JTG D60 by f1 beside a hogging moment: the clause's commentary is said to take the "
                   f"second frequency f2 for hogging moments of continuous beams (unconfirmed; docs/bridges.md){other}")


def print_points(points: list[dict[str, Any]], small: list[bool], acceleration: list[bool] | None = None) -> None:
    """One line per response point ([[response.points]]): where, static and dynamic peaks, IMs; "!"
    marks an IM on a small static reference (``small``: per point, whether the run flags it
    ``small_static``, ``vbikit.analysis.checks``) and a peak acceleration the step check flags
    (``acceleration``: per point)."""
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION
    from vbikit.outputs import report_unit

    unit, k = report_unit("m")  # deflections in mm (the positions x, y are geometry: m)
    typer.echo(f"  {'points':<20} {'x [m]':>8} {'y [m]':>8} {f'static [{unit}]':>12} {f'dynamic [{unit}]':>13} {'IM':>8} "
               f"{'strain IM':>9} {'|a|max [m/s²]':>14}")
    for p, flag, acc in zip(points, small, acceleration or [False] * len(points)):
        typer.echo((f"  {p['name']:<20} {p['x']:8.3f} {p['y']:8.3f} {p['max_static_displacement'] * k:+12.4f} "
                    f"{p['max_dynamic_displacement'] * k:+13.4f} {p['impact_factor']:8.4f} "
                    f"{p['strain_impact_factor']:9.4f} {p['max_abs_acceleration']:14.4f}{'!' if acc else ' '}"
                    f"{' !' if flag else ''}").rstrip())
    if any(small):
        typer.echo(f"  {'':<20} ! unreliable IM: static deflection under {SMALL_STATIC_FRACTION:.0%} of the largest "
                   "on the bridge; not a design value — see the warning")


def outputs(run: Run, as_json: bool, out: Optional[Path], plot: Optional[Path], summary_path: Optional[Path]) -> None:
    """Write the files asked for (CSV, figure, JSON summary), then print the JSON or the text report."""
    if out is not None:
        guard(lambda: run.write_csv(out))
    if plot is not None:
        guard(lambda: run.plot(plot))
    if summary_path is not None:
        guard(lambda: write_text(summary_path, json_text(run.summary, indent=2) + "\n"))
    if as_json:
        typer.echo(json_text(run.summary))
    else:
        print_summary(run)
        for label, path in (("time histories", out), ("figure", plot), ("summary", summary_path)):
            if path is not None:
                typer.echo(f"  {label:<20} {path}")
