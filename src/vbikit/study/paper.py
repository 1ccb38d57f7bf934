"""The paper's numerical studies (§3, Figs. 5–8, 10, 11) as named study specifications.

Settings ([paper] unless marked):

* Figs. 5–7: HS20-44 on Bridges 1 / 2 / 3, multipoint tire (0.254 m patch) with
  n ∈ {1, 3, 4, 5, 6, 7, 8, 9} (n = 1 is the single-point tire), 45 / 75 / 105 km/h, good /
  average / poor roads ([substitute] ISO 8608 B / C / D), 20 profiles each.
* Fig. 8: the same with the two-axle truck on Bridge 2.
* Figs. 10 / 11: single-point, multipoint (n = 6) and deformable disk tires, 15 … 120 km/h
  every 15, B / C / D, 20 profiles, Bridge 2, without (Fig. 10) / with (Fig. 11) the 20 mm
  depression at the bridge entry ([substitute] vbikit's default depression geometry).

Bridges (default): the 3D slab-on-girder grillage presets ``paper-bridge-N`` (10 modes, the
truck at the preset's loading position), response = midspan deflection of Girder 4 as in the
paper.  With ``beam=True``: the beam stand-ins ``paper-bridge-N-beam`` (whole cross-section, not
Girder 4; 6 bending modes — midspan deflection converged to < 0.1 % with modes 1, 3, 5; more
modes only shorten the RK4 step, which is set by the highest mode).  Both: 2 % damping, RK4
with the automatic step, tires that cannot pull.  The same 20 road seeds (derived from study
seed 2024) are used for every n, tire model and speed, so differences are not sampling noise.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.study.spec import Study

#: AASHTO reference lines (model data §6): LRFD IM and Standard Specifications 50/(L+125) ≤ 0.3
AASHTO_LRFD_IM = 0.33
AASHTO_STANDARD_IM = {"paper-bridge-1-beam": 0.30, "paper-bridge-2-beam": 0.278, "paper-bridge-3-beam": 0.196,
                      "paper-bridge-1": 0.30, "paper-bridge-2": 0.278, "paper-bridge-3": 0.196}

PAPER_SEED = 2024
N_POINTS = [1, 3, 4, 5, 6, 7, 8, 9]
SPEEDS_5_8 = [45, 75, 105]
SPEEDS_10_11 = [15, 30, 45, 60, 75, 90, 105, 120]
CLASSES = ["B", "C", "D"]
CLASS_NAMES = {"B": "good (ISO B)", "C": "average (ISO C)", "D": "poor (ISO D)"}
N_MODES = 6


def bridge_model(fig: str, beam: bool = False) -> str:
    """The bridge preset of paper figure ``fig``: 3D ``paper-bridge-N`` or the beam stand-in."""
    return FIGURES[fig]["bridge"] + ("-beam" if beam else "")


def _base(bridge: str, vehicle: str, name: str, beam: bool) -> dict[str, Any]:
    base: dict[str, Any] = {
        "name": name,
        "bridge": {"model": bridge, "damping_ratio": 0.02},
        "vehicle": {"model": vehicle},
        "tire": {"model": "multipoint", "n_points": 6, "contact_length": 0.254},
        "road": {"class": "C", "seed": 0},
        "crossing": {"speed_kmh": 75, "approach": 10},
    }
    if beam:
        base["bridge"]["n_modes"] = N_MODES
    else:
        base["response"] = {"girder": 4}
    return base


FIGURES: dict[str, dict[str, Any]] = {
    "fig5": {"bridge": "paper-bridge-1", "vehicle": "hs20-44", "kind": "points",
             "title": "Fig. 5: IM vs number of points, HS20-44, Bridge 1 (9.16 m)"},
    "fig6": {"bridge": "paper-bridge-2", "vehicle": "hs20-44", "kind": "points",
             "title": "Fig. 6: IM vs number of points, HS20-44, Bridge 2 (16.76 m)"},
    "fig7": {"bridge": "paper-bridge-3", "vehicle": "hs20-44", "kind": "points",
             "title": "Fig. 7: IM vs number of points, HS20-44, Bridge 3 (39.62 m)"},
    "fig8": {"bridge": "paper-bridge-2", "vehicle": "two-axle", "kind": "points",
             "title": "Fig. 8: IM vs number of points, two-axle truck, Bridge 2 (16.76 m)"},
    "fig10": {"bridge": "paper-bridge-2", "vehicle": "hs20-44", "kind": "tires", "depression": False,
              "title": "Fig. 10: IM vs speed per tire model, Bridge 2, no depression"},
    "fig11": {"bridge": "paper-bridge-2", "vehicle": "hs20-44", "kind": "tires", "depression": True,
              "title": "Fig. 11: IM vs speed per tire model, Bridge 2, 20 mm depression at the entry"},
}


#: the outputs the paper studies reduce and store (``outputs`` of the study file, ``vbikit.outputs``):
#: every figure plots the displacement impact factor at the response point (``plot_paper_figure``);
#: its two peaks come with it at no cost, and the smallest tire force (a tire that lost contact),
#: the stored step and the step count say how each crossing ran.  The strain impact factor, the
#: deck peaks and the moment, shear and reaction (three load-effect histories a crossing) are not
#: reduced: a run of the same study with more ``outputs`` gives them.
PAPER_OUTPUTS = ("impact_factor", "max_dynamic_displacement", "max_static_displacement", "min_tire_force",
                 "dt", "n_steps")

#: the paper studies run with the library's default integrator (exact modal stepping; against the
#: paper's RK4 over the whole programme, benchmarks/bench_studies.py: README, "Benchmarks");
#: ``integrator="rk4"`` runs them as the paper did
PAPER_INTEGRATOR: str | None = None  # None: the crossings' own default (vbikit.solve.integrators)


def paper_study_dict(fig: str, samples: int = 20, beam: bool = False, integrator: str | None = PAPER_INTEGRATOR,
                     method: str = "monte-carlo") -> dict[str, Any]:
    """The study (as the dict of its TOML) of paper figure ``fig`` ("fig5" … "fig11") on the 3D
    bridges at Girder 4, or on the beam stand-ins with ``beam=True``; ``integrator``: the
    crossings' integrator (default ``PAPER_INTEGRATOR``, the library's default; "rk4" as the paper);
    ``method``: ``"monte-carlo"`` (the paper's: ``samples`` road profiles a cell) or ``"pem"`` (the
    impact factor's distribution a cell by pseudo-excitation, ``vbikit.study.pem``: no seed axis,
    linear tires only — Figs. 10/11 sweep the point and multi-point tires, not the disk — and no
    road defects, so not Fig. 11)."""
    if fig not in FIGURES:
        raise ValueError(f"unknown paper study {fig!r}; allowed: {', '.join(FIGURES)}")
    f = FIGURES[fig]
    if method == "pem" and f.get("depression"):
        raise ValueError(f"{fig} has a road depression (road.defects): method = \"pem\" takes the road as a Gaussian "
                         "process only; run it with method = \"monte-carlo\"")
    base = _base(bridge_model(fig, beam), f["vehicle"], f["title"], beam)
    if integrator is not None:
        base["crossing"]["integrator"] = integrator
    if f["kind"] == "points":
        axes: dict[str, Any] = {"tire.n_points": N_POINTS, "crossing.speed_kmh": SPEEDS_5_8}
    else:
        axes = {"tire.model": ["point", "multipoint", "disk"], "crossing.speed_kmh": SPEEDS_10_11}
        base["tire"] = {"model": "multipoint"}  # each model with its defaults (multipoint: n = 6 over 0.254 m)
        if f["depression"]:
            base["road"]["defects"] = [{"kind": "depression", "position": 0.0}]
    axes["road.class"] = CLASSES
    if method == "pem":
        if f["kind"] == "tires":
            axes["tire.model"] = ["point", "multipoint"]  # the disk tire is geometric nonlinear
        return {"name": f"paper-{fig}" + ("-beam" if beam else "") + "-pem", "seed": PAPER_SEED, "batch_size": 32,
                "method": "pem", "base": base, "axes": axes}
    axes["road.seed"] = {"samples": samples}
    return {"name": f"paper-{fig}" + ("-beam" if beam else ""), "seed": PAPER_SEED, "batch_size": 32,
            "outputs": list(PAPER_OUTPUTS), "base": base, "axes": axes,
            **({} if method == "monte-carlo" else {"method": method})}  # another value: the study's error


def paper_study(fig: str, samples: int = 20, beam: bool = False, integrator: str | None = PAPER_INTEGRATOR,
                method: str = "monte-carlo") -> Study:
    """The validated [`Study`][vbikit.study.Study] of paper figure ``fig`` (see ``paper_study_dict``)."""
    from vbikit.study.spec import parse_study

    return parse_study(paper_study_dict(fig, samples, beam, integrator, method))
