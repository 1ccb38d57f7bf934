"""The output catalogue: every named result of a crossing, defined once.

Two kinds of entries:

* [`Quantity`][vbikit.outputs.Quantity] — a time history at a deck point (``displacement``, ``strain``, …): name,
  unit and long name.  CSV headers (``name [unit]``), ``to_xarray`` / ``to_dataframe``
  variables and the docs' results table read them from here.
* [`Output`][vbikit.outputs.Output] — a number reduced from a crossing: name, unit, long name, its ``scope``
  (``"point"``: one value per response point, from that point's histories; ``"crossing"``: one
  value per crossing) and its ``reduce`` function.  The JSON summary (``vbikit run --json``,
  ``vbikit.Report.summary``), study datasets and traffic datasets are filled from here, so a
  name or a unit cannot disagree between them.

A reducer receives a [`Reduction`][vbikit.outputs.Reduction]: the point's histories (``point``, an object with
``displacement_impact`` / ``strain_impact`` ([`ImpactFactor`][vbikit.analysis.ImpactFactor]),
``velocity``, ``acceleration`` … as [`PointResponse`][vbikit.analysis.PointResponse]), the
crossing result (``result``) and its load-effect responses by kind (``effects``; the first of
each kind).  It returns a float, or ``None`` when the output does not apply (no load effect of
that kind): the summary leaves it out and datasets store NaN.

Adding an output is one [`register_output`][vbikit.outputs.register_output] call (docs/extending.md).  Units are written as
in CSV headers and JSON (``m/s^2``, ``-`` for dimensionless); [`cf_unit`][vbikit.outputs.cf_unit] gives the CF /
UDUNITS spelling datasets use (``m s-2``, ``1``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Literal, Mapping, Optional, Sequence

import numpy as np

Scope = Literal["point", "crossing"]

#: CSV / JSON spelling of a unit → its CF (UDUNITS) spelling in NetCDF datasets
CF_UNITS: dict[str, str] = {"m/s": "m s-1", "m/s^2": "m s-2", "-": "1", "rad/s^2": "rad s-2", "km/h": "km h-1",
                            "cycle/m": "m-1", "m^3/cycle": "m3", "N m^2": "N m2"}


def cf_unit(unit: str) -> str:
    """The CF/UDUNITS spelling of ``unit`` (``"m/s^2"`` → ``"m s-2"``, ``"-"`` → ``"1"``)."""
    return CF_UNITS.get(unit, unit)


def member_units(units: Sequence[str], dim: str, coordinate: str) -> dict[str, str]:
    """The unit attributes of a dataset variable whose values along ``dim`` have the CF units ``units`` (one a member,
    held by the coordinate ``coordinate``): ``{"units": u}`` when they share one; otherwise ``{"units_by_<dim>":
    coordinate}`` and no ``units`` — CF allows one parseable unit per variable, and a packed "N m; m; N" is one no
    parser reads (cf_units and pint refuse the whole dataset) — the one convention of the lifetime load effects and
    the drive-by sensors."""
    kinds = list(dict.fromkeys(str(u) for u in units))
    return {"units": kinds[0]} if len(kinds) == 1 else {f"units_by_{dim}": coordinate}


def csv_unit(unit: str) -> str:
    """The CSV / JSON spelling of a CF/UDUNITS ``unit`` (``cf_unit``'s inverse: ``"m s-2"`` → ``"m/s^2"``, ``"1"``
    → ``"-"``; a unit both write alike as it is)."""
    return _CSV_UNITS.get(unit, unit)


_CSV_UNITS = {cf: csv for csv, cf in CF_UNITS.items()}


#: SI unit of a result → (unit, factor) of the plain-text reports (``vbikit run``, ``vbikit lifetime``,
#: ``vbikit rail``, ``vbikit presets``): moments in kN m, forces in kN, deflections (results in m) in
#: mm; JSON, CSV and NetCDF stay SI.  Geometry (spans, positions, offsets) is input, not a result,
#: and stays in m
REPORT_UNITS: dict[str, tuple[str, float]] = {"N m": ("kN m", 1e-3), "N": ("kN", 1e-3), "m": ("mm", 1e3)}


def report_unit(unit: str) -> tuple[str, float]:
    """The unit a text report shows a value of SI ``unit`` in and the factor to it
    (``"N m"`` → ``("kN m", 1e-3)``, ``"m"`` (a deflection) → ``("mm", 1e3)``; a unit not in
    ``REPORT_UNITS`` as it is, factor 1)."""
    return REPORT_UNITS.get(unit, (unit, 1.0))


@dataclass(frozen=True)
class Quantity:
    """A time history at a deck point.

    Parameters
    ----------
    name : str
        Column and variable name, e.g. ``"displacement"``.
    unit : str
        Unit in the CSV spelling, e.g. ``"m/s^2"``.
    long_name : str
        Description for datasets and the docs.
    """

    name: str
    unit: str
    long_name: str


@dataclass(frozen=True)
class Reduction:
    """What a reducer reads.

    Parameters
    ----------
    result : CrossingResult
        The crossing result.
    point : PointResponse, optional
        One response point's histories (None for crossing-scope outputs).
    effects : mapping of str to LoadEffectResponse
        The load-effect responses, the first of each kind (``"moment"``, ``"shear"``,
        ``"reaction"``).
    """

    result: Any
    point: Any = None
    effects: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Output:
    """A number reduced from a crossing (see the module docstring).

    Parameters
    ----------
    name : str
        Key in the JSON summary and variable name in datasets.
    unit : str
        Unit in the CSV/JSON spelling (``"-"`` for dimensionless).
    long_name : str
        Description for datasets and the docs.
    scope : str
        ``"point"``: one value per response point; ``"crossing"``: one value per crossing.
    reduce : callable
        ``reduce(reduction) -> float | None``: the value from a [`Reduction`][vbikit.outputs.Reduction],
        None where the output does not apply.
    effect : str, optional
        The load-effect kind (``"moment"``, ``"shear"``, ``"reaction"``) the reducer reads from
        ``Reduction.effects``; a run that asks for none of these outputs does not compute that
        kind's histories (``effect_kinds``).
    resolve : str
        The coarsest ``Crossing.resolve`` whose automatic step keeps this output within the step's accuracy
        bound (``vbikit.solve.crossing.RESOLVES``): "deflections" (the deck's deflections, tire forces, step
        counts) or "effects" (the default: accelerations, velocities, strains, moments, shears, reactions).
        A run that asks only for "deflections" outputs may take the coarser step (``outputs_resolve``).
    """

    name: str
    unit: str
    long_name: str
    scope: Scope
    reduce: Callable[[Reduction], Optional[float]]
    effect: Optional[str] = None
    resolve: str = "effects"

    @property
    def cf_unit(self) -> str:
        return cf_unit(self.unit)


#: deck histories at a response point, in CSV column order
QUANTITIES: dict[str, Quantity] = {q.name: q for q in (
    Quantity("displacement", "m", "deck vertical displacement (z up)"),
    Quantity("static_displacement", "m", "static reference displacement"),
    Quantity("strain", "-", "bottom-fibre longitudinal strain (tension positive)"),
    Quantity("static_strain", "-", "static reference strain"),
    Quantity("velocity", "m/s", "deck vertical velocity"),
    Quantity("acceleration", "m/s^2", "deck vertical acceleration"),
)}

#: every registered output, by name, in registration order
OUTPUTS: dict[str, Output] = {}


def register_output(output: Output) -> Output:
    """Add ``output`` to the catalogue and return it.

    Parameters
    ----------
    output : Output
        The output to register under ``output.name``.

    Raises
    ------
    ValueError
        A name registered already, or a scope other than ``"point"`` and ``"crossing"``.
    """
    if output.name in OUTPUTS:
        raise ValueError(f"output {output.name!r} is already registered")
    if output.scope not in ("point", "crossing"):
        raise ValueError(f"output {output.name!r}: scope must be 'point' or 'crossing', got {output.scope!r}")
    OUTPUTS[output.name] = output
    return output


def outputs(scope: Scope | None = None, names: Optional[Sequence[str]] = None) -> list[Output]:
    """The registered outputs (of one ``scope``; only those named in ``names`` when given — None:
    all), in registration order."""
    wanted = None if names is None else set(names)
    return [o for o in OUTPUTS.values() if (scope is None or o.scope == scope) and (wanted is None or o.name in wanted)]


def select_outputs(names: Sequence[str], key: str | None = None) -> tuple[str, ...]:
    """``names`` checked against the catalogue, in registration order (a run that asks for these
    reduces only them).

    Raises
    ------
    ValueError
        An empty list, a repeated name or a name the catalogue does not have; the message lists the
        allowed names, after ``key:`` when given (a schema validator adds the key itself).
    """
    names = list(names)
    where = f"{key}: " if key else ""
    allowed = ", ".join(OUTPUTS)
    if not names:
        raise ValueError(f"{where}give at least one output name; allowed: {allowed}")
    unknown = [n for n in names if n not in OUTPUTS]
    if unknown:
        shown = unknown[0] if len(unknown[0]) <= 40 else unknown[0][:40] + "…"
        raise ValueError(f"{where}unknown output {shown!r}; allowed: {allowed}")
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise ValueError(f"{where}output {repeated[0]!r} is listed more than once")
    return tuple(o.name for o in outputs(names=names))


def effect_kinds(names: Optional[Sequence[str]] = None) -> set[str]:
    """The load-effect kinds the outputs ``names`` (None: all) read (``Output.effect``)."""
    return {o.effect for o in outputs(names=names) if o.effect is not None}


def outputs_resolve(names: Optional[Sequence[str]] = None) -> str:
    """What a run reducing the outputs ``names`` (None: all) must resolve (``Crossing.resolve``):
    "deflections" when every one of them is resolved at that step (``Output.resolve``), else "effects"."""
    return "deflections" if all(o.resolve == "deflections" for o in outputs(names=names)) else "effects"


def base_resolve(base: Mapping[str, Any], names: Optional[Sequence[str]] = None) -> str:
    """What a population's crossings resolve (``Crossing.resolve``) when they reduce the outputs ``names``
    (None: all): the base scenario's (``base``, a scenario table) ``crossing.resolve`` when it gives one, else
    ``outputs_resolve(names)``.

    Raises
    ------
    ValueError
        A base for deflections only whose outputs need the step for every result.
    """
    crossing = base.get("crossing")
    given = crossing.get("resolve") if isinstance(crossing, Mapping) else None
    needs = outputs_resolve(names)
    if given is None:
        return needs
    if given != "effects" and needs == "effects":
        raise ValueError(f'crossing.resolve = "{given}" in the base scenario: the outputs (every output, or outputs '
                         "beyond the deflections, tire forces and step counts) need the step for every result; leave "
                         "crossing.resolve out, or ask only for those outputs")
    return given


def reduce_outputs(reduction: Reduction, scope: Scope,
                   names: Optional[Sequence[str]] = None) -> dict[str, Optional[float]]:
    """Every output of ``scope`` (only those in ``names`` when given) for ``reduction``: name →
    value (None where it does not apply)."""
    out: dict[str, Optional[float]] = {}
    for o in outputs(scope, names):
        value = o.reduce(reduction)
        out[o.name] = None if value is None else float(value)
    return out


def as_number(value: Optional[float]) -> float:
    """A reduced value for a dataset: None (does not apply) → NaN."""
    return math.nan if value is None else float(value)


def _peak_abs(values: Any) -> float:
    return float(np.max(np.abs(values)))


# ---------------------------------------------------------------- per response point
for _name, _unit, _long, _fn in (
    ("impact_factor", "-", "displacement impact factor IM = (R_dyn,max − R_st,max)/R_st,max at the response point",
     lambda r: r.point.displacement_impact.impact_factor),
    ("max_dynamic_displacement", "m", "dynamic peak displacement in the static peak's direction (z up: negative)",
     lambda r: r.point.displacement_impact.dynamic_peak),
    ("max_static_displacement", "m", "static reference peak displacement under the moving static wheel loads",
     lambda r: r.point.displacement_impact.static_peak),
    ("time_of_max_dynamic_displacement", "s", "time of the dynamic peak displacement",
     lambda r: r.point.displacement_impact.time_dynamic_peak),
):
    register_output(Output(_name, _unit, _long, "point", _fn, resolve="deflections"))

for _name, _unit, _long, _fn in (
    ("strain_impact_factor", "-", "bottom-fibre strain impact factor at the response point",
     lambda r: r.point.strain_impact.impact_factor),
    ("max_dynamic_strain", "-", "dynamic peak bottom-fibre strain (tension positive)",
     lambda r: r.point.strain_impact.dynamic_peak),
    ("max_static_strain", "-", "static reference peak bottom-fibre strain",
     lambda r: r.point.strain_impact.static_peak),
    ("max_abs_acceleration", "m/s^2", "largest absolute deck acceleration at the response point",
     lambda r: _peak_abs(r.point.acceleration)),
    ("max_abs_velocity", "m/s", "largest absolute deck velocity at the response point",
     lambda r: _peak_abs(r.point.velocity)),
):
    register_output(Output(_name, _unit, _long, "point", _fn))


# ---------------------------------------------------------------- per crossing
def _min_tire_force(r: Reduction) -> Optional[float]:
    forces = r.result.wheel_forces
    return float(forces.min()) if forces.size else None


register_output(Output("min_tire_force", "N", "smallest tire force over the crossing (0: a tire lost contact)",
                       "crossing", _min_tire_force, resolve="deflections"))


def _effect(kind: str, attribute: str) -> Callable[[Reduction], Optional[float]]:
    def reduce(r: Reduction) -> Optional[float]:
        response = r.effects.get(kind)
        return None if response is None else getattr(response.impact, attribute)
    return reduce


for _kind, _what, _unit in (("moment", "sagging positive", "N m"), ("shear", "dM/dx, just right of the section", "N"),
                            ("reaction", "upward", "N")):
    for _attr, _suffix, _desc, _u in (
            ("impact_factor", "impact_factor", "impact factor in the static peak's direction", "-"),
            ("static_peak", "static_peak", "static peak", _unit),
            ("dynamic_peak", "dynamic_peak", "dynamic peak in the static peak's direction", _unit)):
        register_output(Output(f"{_kind}_{_suffix}", _u, f"{_kind} ({_what}) {_desc}: the first requested {_kind} "
                               f"(default the bridge's first); absent (NaN) if the bridge has none",
                               "crossing", _effect(_kind, _attr), effect=_kind))

register_output(Output("dt", "s", "time step of the stored histories", "crossing", lambda r: r.result.dt,
                       resolve="deflections"))
register_output(Output("n_steps", "-", "number of time steps", "crossing", lambda r: r.result.n_steps,
                       resolve="deflections"))
register_output(Output("unconverged_steps", "-", "integration steps whose contact forces did not converge within the "
                       "implicit integrator's iteration limit, after the run at half and a quarter of its step "
                       "(0 for a sound run; flag contact_not_converged)",
                       "crossing", lambda r: float(r.result.unconverged_steps), resolve="deflections"))

#: the outputs every population of crossings (a study's grid, a traffic stream's events) reduces and
#: stores whatever it asks for: what each crossing's numbers are worth (its dataset flags read them)
QUALITY_OUTPUTS = ("unconverged_steps",)
