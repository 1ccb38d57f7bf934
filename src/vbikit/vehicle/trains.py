"""Trains as chains of axle loads: the HSLM-A and HSLM-B load models, real trains from a table
file, and documented real trains (presets).

A [`Train`][vbikit.vehicle.Train] is its axle positions a_k [m] behind the first axle (a_0 = 0,
non-decreasing), its static axle loads P_k [N] (downward, > 0) and optionally its cars
([`CarGeometry`][vbikit.vehicle.CarGeometry]: where each car's bogies are and, when known, its masses
and suspensions), from which coupled car models can be built.

HSLM-A (EN 1991-2:2003 + AC, 6.4.6.1.1, Figure 6.12 and Table 6.3 — the numbers checked against the
standard's Annex E, E.1, which refers to "the Universal Trains in accordance with Figure 6.12 and
Table 6.3"; Annex E, Table E.1 gives the limits of validity of HSLM, not the trains): two power
cars, two end coaches and N intermediate coaches of length D, articulated (neighbouring coaches
share a bogie), bogie axle spacing d, axle load P.  The chain, front to rear (tests/rail/test_trains.py
asserts, within 1e-9 m, SincBridgeDynamics.jl's ``TRAIN_MODELS`` axle counts and last axles of all
ten, the first twelve axles of A2 and the last eight of A8):

* power car: two bogies of axle spacing 3 m, 11 m between them — axles at 0, 3, 14, 17 m;
* end coach: its own bogie (spacing d) with its first axle 3.525 m behind the power car's last,
  and D − (3.525 + d)/2 m from its centre to the centre of the first shared bogie;
* N + 1 shared bogies (spacing d) at D centre to centre;
* the rear end coach and power car, mirrored.

So an HSLM-A train has 2N + 14 axles and its first-to-last axle length is (N + 2) D + 37.525 m.

HSLM-B (EN 1991-2:2003 + AC, 6.4.6.1.1; the figure number not checked against a second source): N
point forces of 170 kN at a uniform spacing d, both read from a figure of the span (simply
supported spans below 7 m).  The figure's curves are not encoded here (no second source could be
checked): ``hslm_b`` takes N and d from the user.
"""
from __future__ import annotations

import logging
import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Optional

import numpy as np
from numpy.typing import NDArray

from vbikit.errors import VbikitError
from vbikit.vehicle.model import GRAVITY, Vehicle

log = logging.getLogger(__name__)

#: an axle load of a train table above this is warned of [kN]: 40 t, beyond the heaviest heavy-haul axles
#: (about 35 t) and far above LM71's 250 kN (EN 1991-2 6.3.2)
AXLE_LOAD_WARNING_KN = 400.0
#: the largest axle load [kN] of any train (a 1000 t axle: no railway load, a unit error)
MAX_AXLE_LOAD_KN = 10000.0
#: the longest train [m], first to last axle
MAX_TRAIN_LENGTH = 5000.0

#: usual speeds of trains [km/h]: up to 1.2 × 350 km/h, the sweep limit of EN 1991-2 6.4.6 on the
#: fastest lines (a speed outside is warned of, as for road vehicles)
TRAIN_SPEED_RANGE_KMH = (5.0, 420.0)



class TrainError(VbikitError):
    """A train that cannot be built: a bad table file (names the file and line) or parameter."""


@dataclass(frozen=True)
class CarGeometry:
    """One car of a train: its bogies and, when known, its masses and suspensions.

    Parameters
    ----------
    first_bogie : float
        Position [m] of the centre of its front bogie behind the train's first axle.
    bogie_spacing : float
        Distance [m] between its two bogie centres (2 L_c).
    axle_spacing : float
        Axle spacing [m] of each bogie (2 L_b).
    body_mass, body_pitch_inertia, bogie_mass, bogie_pitch_inertia, wheelset_mass : float, optional
        [kg], [kg m²] (None where not documented).
    primary_stiffness, primary_damping : float, optional
        Primary suspension per axle (both wheels, a planar model) [N/m], [N s/m].
    secondary_stiffness, secondary_damping : float, optional
        Secondary suspension per bogie (both sides) [N/m], [N s/m].
    name : str
        Label, e.g. ``"car 1"``.
    """

    first_bogie: float
    bogie_spacing: float
    axle_spacing: float
    body_mass: Optional[float] = None
    body_pitch_inertia: Optional[float] = None
    bogie_mass: Optional[float] = None
    bogie_pitch_inertia: Optional[float] = None
    wheelset_mass: Optional[float] = None
    primary_stiffness: Optional[float] = None
    primary_damping: Optional[float] = None
    secondary_stiffness: Optional[float] = None
    secondary_damping: Optional[float] = None
    name: str = ""

    @property
    def axle_positions(self) -> NDArray[np.float64]:
        """Its four axles [m] behind the train's first axle."""
        b, s = self.first_bogie, 0.5 * self.axle_spacing
        return np.array([b - s, b + s, b + self.bogie_spacing - s, b + self.bogie_spacing + s])

    @property
    def static_axle_load(self) -> Optional[float]:
        """g ((m_body/2 + m_bogie)/2 + m_wheelset) [N]: the static load of each axle (None when a
        mass is unknown)."""
        if None in (self.body_mass, self.bogie_mass, self.wheelset_mass):
            return None
        return GRAVITY * ((0.5 * self.body_mass + self.bogie_mass) / 2.0 + self.wheelset_mass)


@dataclass(frozen=True)
class Train:
    """A train as moving axle loads.

    Parameters
    ----------
    name : str
        Display name (``"HSLM-A1"``).
    axle_positions : array
        a_k [m] behind the first axle: a_0 = 0, non-decreasing.
    axle_loads : array
        P_k [N], downward, > 0.
    cars : tuple of CarGeometry, optional
        The cars, when the train's multibody data are known.
    source : str
        Where the data come from.
    coach_length : float, optional
        The principal excitation wavelength D [m] (regular coach length) when the train has one;
        resonance speeds are v_i = n0 D / i (EN 1991-2 6.4.6).
    bogie_axle_spacings : tuple of float, optional
        The train's characteristic axle spacings within a bogie [m] (distinct, ascending): a second
        family of resonances v = n0 d / i, which governs short spans (HSLM-A: d of Table 6.3 and the
        power cars' 3 m; default: the cars' ``axle_spacing`` when the cars are known, else none).
    """

    name: str
    axle_positions: NDArray[np.float64]
    axle_loads: NDArray[np.float64]
    cars: Optional[tuple[CarGeometry, ...]] = None
    source: str = ""
    coach_length: Optional[float] = None
    bogie_axle_spacings: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        a = np.asarray(self.axle_positions, float).ravel()
        p = np.asarray(self.axle_loads, float).ravel()
        if a.size == 0 or a.size != p.size:
            raise TrainError(f"train {self.name!r}: needs as many axle positions as loads (>= 1), got {a.size} and {p.size}")
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(p))):
            raise TrainError(f"train {self.name!r}: axle positions and loads must be finite")
        if abs(a[0]) > 1e-9 or np.any(np.diff(a) < 0):
            raise TrainError(f"train {self.name!r}: axle positions must start at 0 m and not decrease")
        if np.any(p <= 0) or np.any(p > MAX_AXLE_LOAD_KN * 1e3):
            raise TrainError(f"train {self.name!r}: axle loads must be within 0 … {MAX_AXLE_LOAD_KN * 1e3:g} N "
                             f"(0 … {MAX_AXLE_LOAD_KN:g} kN)")
        if a[-1] > MAX_TRAIN_LENGTH:
            raise TrainError(f"train {self.name!r}: longer than {MAX_TRAIN_LENGTH:g} m ({a[-1]:g} m)")
        object.__setattr__(self, "axle_positions", a)
        object.__setattr__(self, "axle_loads", p)
        d = self.bogie_axle_spacings or tuple(c.axle_spacing for c in self.cars or ())
        if not all(math.isfinite(x) and x > 0 for x in d):
            raise TrainError(f"train {self.name!r}: bogie axle spacings must be > 0 m, got {d!r}")
        object.__setattr__(self, "bogie_axle_spacings", tuple(sorted({round(float(x), 9) for x in d})))

    @property
    def n_axles(self) -> int:
        return int(self.axle_positions.size)

    @property
    def length(self) -> float:
        """First-to-last axle distance [m]."""
        return float(self.axle_positions[-1])

    @property
    def total_load(self) -> float:
        """Σ P_k [N]."""
        return float(self.axle_loads.sum())


# ---------------------------------------------------------------------------------------- HSLM
#: EN 1991-2:2003 + AC, Table 6.3: (N intermediate coaches, coach length D [m], bogie axle spacing d [m],
#: point force P [kN]) of HSLM-A1 … A10 (D, d, P also in SincBridgeDynamics.jl's TRAIN_MODELS)
HSLM_A_TABLE: dict[int, tuple[int, float, float, float]] = {
    1: (18, 18.0, 2.0, 170.0),
    2: (17, 19.0, 3.5, 200.0),
    3: (16, 20.0, 2.0, 180.0),
    4: (15, 21.0, 3.0, 190.0),
    5: (14, 22.0, 2.0, 170.0),
    6: (13, 23.0, 2.0, 180.0),
    7: (13, 24.0, 2.0, 190.0),
    8: (12, 25.0, 2.5, 190.0),
    9: (11, 26.0, 2.0, 210.0),
    10: (11, 27.0, 2.0, 210.0),
}
#: power car axles [m] (EN 1991-2:2003 Figure 6.12) and the gap [m] from its last axle to the end coach's first
POWER_CAR_AXLES = (0.0, 3.0, 14.0, 17.0)
POWER_TO_END_COACH = 3.525
HSLM_SOURCE = "EN 1991-2:2003 + AC, 6.4.6.1.1, Figure 6.12 and Table 6.3"


def hslm_a_axles(n: int, coach: float, d: float) -> NDArray[np.float64]:
    """Axle positions [m] of the HSLM-A chain (module docstring) with N = ``n`` intermediate
    coaches of length D = ``coach`` [m] and bogie axle spacing d [m]."""
    front = list(POWER_CAR_AXLES)
    end_bogie = front[-1] + POWER_TO_END_COACH + 0.5 * d  # centre of the end coach's own bogie
    first_shared = end_bogie + coach - 0.5 * (POWER_TO_END_COACH + d)
    centres = [end_bogie, *(first_shared + coach * np.arange(n + 1))]
    rear_end = centres[-1] + coach - 0.5 * (POWER_TO_END_COACH + d)
    centres.append(rear_end)
    axles = front + [c + s for c in centres for s in (-0.5 * d, 0.5 * d)]
    last = axles[-1] + POWER_TO_END_COACH
    axles += [last + x for x in POWER_CAR_AXLES]
    return np.array(axles)


def hslm_a(number: int) -> Train:
    """HSLM-A``number`` (1 … 10) of EN 1991-2:2003 (Table 6.3) as moving axle loads."""
    if number not in HSLM_A_TABLE:
        raise TrainError(f"HSLM-A{number}: the HSLM-A trains are numbered 1 … 10")
    n, coach, d, p = HSLM_A_TABLE[number]
    a = hslm_a_axles(n, coach, d)
    return Train(f"HSLM-A{number}", a, np.full(a.size, p * 1e3), None,
                 f"{HSLM_SOURCE} (N = {n}, D = {coach:g} m, d = {d:g} m, P = {p:g} kN)", coach,
                 (d, POWER_CAR_AXLES[1] - POWER_CAR_AXLES[0]))  # coach bogies d, power-car bogies 3 m


#: the accepted HSLM-B parameters: the number of forces N and their spacing d [m] (``hslm_b``; the
#: rail file's ``[[trains.hslm_b]]`` takes the same ranges)
HSLM_B_N, HSLM_B_SPACING = (1, 100), (0.5, 50.0)
#: the start of every HSLM-B train's name (``hslm_b``): how the railway checks tell HSLM-B from other trains
HSLM_B_NAME = "HSLM-B"


def hslm_b(n: int, spacing: float, load: float = 170e3) -> Train:
    """HSLM-B: ``n`` equal point forces ``load`` [N] (170 kN in EN 1991-2:2003 6.4.6.1.1) at a uniform
    ``spacing`` d [m]; N and d are read by the user from the standard's HSLM-B figure for the span."""
    if int(n) != n or not HSLM_B_N[0] <= n <= HSLM_B_N[1]:
        raise TrainError(f"HSLM-B: the number of forces N must be an integer within {HSLM_B_N[0]} … {HSLM_B_N[1]}, "
                         f"got {n!r}")
    if not (math.isfinite(spacing) and HSLM_B_SPACING[0] <= spacing <= HSLM_B_SPACING[1]):
        raise TrainError(f"HSLM-B: the spacing d must be within {HSLM_B_SPACING[0]:g} … {HSLM_B_SPACING[1]:g} m, "
                         f"got {spacing!r}")
    a = spacing * np.arange(int(n), dtype=float)
    return Train(f"{HSLM_B_NAME} (N = {int(n)}, d = {spacing:g} m)", a, np.full(a.size, float(load)), None,
                 "EN 1991-2:2003 + AC, 6.4.6.1.1, HSLM-B (N and d given by the user)", spacing)


def rail_distributed(train: Train, sleeper_spacing: float = 0.6) -> Train:
    """The longitudinal distribution of each axle load by the rail over three sleepers (EN 1991-2
    6.3.6.1, Figure 6.4): P/4 at −a, P/2 at 0, P/4 at +a (a the sleeper spacing [m]), the chain
    shifted by a so that it starts at 0 (a shift of the entry time only).  Moving forces only: the
    result has no cars."""
    a = float(sleeper_spacing)
    if not (math.isfinite(a) and 0.1 <= a <= 2.0):
        raise TrainError(f"sleeper spacing must be within 0.1 … 2 m, got {sleeper_spacing!r}", key="trains.sleeper_spacing")
    x = (train.axle_positions[:, None] + np.array([0.0, a, 2 * a])[None, :]).ravel()
    p = (train.axle_loads[:, None] * np.array([0.25, 0.5, 0.25])[None, :]).ravel()
    order = np.argsort(x, kind="stable")
    return Train(f"{train.name} (rail-distributed)", x[order], p[order], None,
                 f"{train.source}; loads distributed over three sleepers {a:g} m apart (EN 1991-2 6.3.6.1)",
                 train.coach_length, train.bogie_axle_spacings)


# ------------------------------------------------------------------------------- real trains
def _ice3_cars() -> tuple[CarGeometry, ...]:
    """The eight cars of the ICE 3 / AVE S-103 (Velaro E) as described by Goicolea (2014): bogie
    centres 17.375 m apart, bogie axle spacing 2.5 m, car length 24.775 m (3.7 m from each end
    bogie to the coupling, the end cars' noses 4.76 m); body 47.8 t (cars 4 and 5: 41.2 t), bogie
    3.5 t, wheelset 1.8 t; per axle k1 = 2 × 1200 kN/m, c1 = 2 × 10 kN s/m; per bogie
    k2 = 2 × 350 kN/m, c2 = 2 × 20 kN s/m (both sides of the 3D model added for a planar car)."""
    cars = []
    for k in range(8):
        light = k in (3, 4)
        cars.append(CarGeometry(
            first_bogie=1.25 + 24.775 * k, bogie_spacing=17.375, axle_spacing=2.5,
            body_mass=41200.0 if light else 47800.0, body_pitch_inertia=1687552.0 if light else 1957888.0,
            bogie_mass=3500.0, bogie_pitch_inertia=1372.0 if light else 1715.0, wheelset_mass=1800.0,
            primary_stiffness=2 * 1200e3, primary_damping=2 * 10e3,
            secondary_stiffness=2 * 350e3, secondary_damping=2 * 20e3, name=f"car {k + 1}"))
    return tuple(cars)


def train_from_cars(name: str, cars: tuple[CarGeometry, ...], source: str, coach_length: float | None = None) -> Train:
    """A train whose axles and static loads come from its cars' geometry and masses."""
    axles = np.concatenate([c.axle_positions for c in cars])
    loads = np.concatenate([np.full(4, c.static_axle_load or np.nan) for c in cars])
    order = np.argsort(axles, kind="stable")
    axles = axles[order] - axles[order][0]
    return Train(name, axles, loads[order], cars, source, coach_length)


def ice3() -> Train:
    """ICE 3 / AVE S-103 (Velaro E), eight cars (``_ice3_cars``): 32 axles, 193.3 m first to last
    axle, static axle loads 152.1 kN (cars 4 and 5: 135.9 kN) from the masses."""
    return train_from_cars("ICE 3", _ice3_cars(),
                           "Goicolea (2014), Simplified mechanical description of AVE S-103 - ICE3 Velaro E "
                           "high speed train, Universidad Politecnica de Madrid (as transcribed in TTB-2D, Cantero)",
                           coach_length=24.775)


def train_vehicle(train: Train) -> Vehicle:
    """The train as a vbikit vehicle of moving forces: one wheel per axle at s = a_k behind the first,
    carrying P_k as a constant load (no DOFs; the moving-force model of EN 1991-2 6.4.6, as
    [`moving_force`][vbikit.vehicle.moving_force] for one axle).  ``[vehicle] model = "hslm-a1"`` in a
    scenario builds this."""
    from vbikit.vehicle.builder import VehicleBuilder

    vb = VehicleBuilder(train.name)
    for k, (a, p) in enumerate(zip(train.axle_positions, train.axle_loads)):
        vb.wheel(f"a{k + 1}", {}, float(a), 0.0, 0.0, 0.0, fixed_load=float(p))
    vehicle = vb.build(f"{train.name}: {train.n_axles} moving axle loads" + (f" ({train.source})" if train.source else ""),
                       {"n_axles": float(train.n_axles), "total_load": train.total_load})
    return replace(vehicle, usual_speed_kmh=TRAIN_SPEED_RANGE_KMH, railway=True)


# ---------------------------------------------------------------------------------- registry
@dataclass(frozen=True)
class TrainPreset:
    """A named train: ``name`` (lower case, for inputs), its builder and a one-line description."""

    name: str
    build: Callable[[], Train]
    description: str
    references: tuple[str, ...] = field(default=())


TRAIN_PRESETS: dict[str, TrainPreset] = {
    **{f"hslm-a{k}": TrainPreset(f"hslm-a{k}", (lambda k=k: hslm_a(k)),
                                 f"HSLM-A{k}: EN 1991-2:2003 Table 6.3 universal train, N = {HSLM_A_TABLE[k][0]}, "
                                 f"D = {HSLM_A_TABLE[k][1]:g} m, d = {HSLM_A_TABLE[k][2]:g} m, P = {HSLM_A_TABLE[k][3]:g} kN",
                                 ("EN1991-2", "SincBridgeDynamics")) for k in HSLM_A_TABLE},
    "ice3": TrainPreset("ice3", ice3, "ICE 3 / AVE S-103 (Velaro E), 8 cars with their masses and suspensions",
                        ("Goicolea2014", "Cantero2022")),
}


def get_train(name: str) -> Train:
    """The preset ``name`` (case-insensitive; ``hslm-a1`` … ``hslm-a10``, ``ice3``)."""
    key = name.strip().lower()
    if key not in TRAIN_PRESETS:
        raise TrainError(f"unknown train {name!r}; presets: {', '.join(TRAIN_PRESETS)} (or a table file .csv)",
                         key="trains")
    return TRAIN_PRESETS[key].build()


# ------------------------------------------------------------------------------- table files
#: the columns of a train table, in order: (name, unit) — the header line, when given, names them
TABLE_COLUMNS = (("position", "m"), ("load", "kN"))
_COLUMNS_TEXT = ", ".join(f"{n} [{u}]" for n, u in TABLE_COLUMNS)
#: a header cell: the column's name, optionally with its unit as ``name [unit]``, ``name (unit)`` or ``name_unit``
_HEADER_CELL = re.compile(r"(?i)([a-z]+)(?:\s*\[\s*([a-z]+)\s*\]|\s*\(\s*([a-z]+)\s*\)|[ _]+([a-z]+))?")


def _number(cell: str) -> float | None:
    try:
        return float(cell)
    except ValueError:
        return None


def _check_header(cells: list[str], where: str, lineno: int) -> None:
    """TrainError unless ``cells`` name the columns ``TABLE_COLUMNS`` in order (units, when
    written, m and kN); the message names the column, never the file's text."""
    for k, (name, unit) in enumerate(TABLE_COLUMNS):
        m = _HEADER_CELL.fullmatch(cells[k])
        given = next((u for u in m.groups()[1:] if u), None) if m else None
        if m is None or m.group(1).lower() != name:
            raise TrainError(f"{where}, line {lineno}: not a train table: its header's column {k + 1} is not "
                             f"'{name}'; a train table has the columns '{_COLUMNS_TEXT}' (header e.g. "
                             f"'position_m,load_kN', or none: one axle a line)")
        if given is not None and given.lower() != unit.lower():
            raise TrainError(f"{where}, line {lineno}: the header gives column {k + 1} ({name}) another unit than "
                             f"{unit}; a train table is read in '{_COLUMNS_TEXT}'")


def parse_train_table(text: str, name: str, where: str = "train table") -> Train:
    """A train from CSV text: one axle a line, ``position [m], load [kN]`` (``TABLE_COLUMNS``; first
    axle at 0 or any origin — positions are shifted to start at 0); blank lines and ``#`` comments
    are skipped.  The first line may be a header naming the two columns (``position_m,load_kN``,
    ``position [m], load [kN]``, ``position,load``; units, when written, m and kN); any other text
    is refused.  Every axle is two finite numbers (empty cells after them are ignored), its load
    within 0 … ``MAX_AXLE_LOAD_KN`` kN, its position beyond the previous one, the train at most
    ``MAX_TRAIN_LENGTH`` m long; at least one axle.  Errors name ``where`` and the line, never the
    text."""
    from vbikit._files import csv_rows

    positions: list[float] = []
    loads: list[float] = []
    for row, (lineno, cells) in enumerate(csv_rows(text, TrainError, where)):
        while len(cells) > len(TABLE_COLUMNS) and not cells[-1]:
            cells = cells[:-1]  # empty trailing cells (a spreadsheet's export)
        if len(cells) != len(TABLE_COLUMNS):
            raise TrainError(f"{where}, line {lineno}: expected two columns '{_COLUMNS_TEXT}', got "
                             f"{len(cells)} cell(s)")
        x, p = _number(cells[0]), _number(cells[1])
        if row == 0 and x is None:
            _check_header(cells, where, lineno)
            continue
        if x is None or p is None:
            raise TrainError(f"{where}, line {lineno}: position [m] and load [kN] must be numbers")
        if not (math.isfinite(x) and math.isfinite(p)):
            raise TrainError(f"{where}, line {lineno}: position and load must be finite")
        if not 0 < p <= MAX_AXLE_LOAD_KN:
            raise TrainError(f"{where}, line {lineno}: load must be within 0 … {MAX_AXLE_LOAD_KN:g} kN (above 0)")
        if positions and x <= positions[-1]:
            raise TrainError(f"{where}, line {lineno}: axle positions must increase (this axle is not beyond the "
                             "previous one; two axles cannot stand at one position)")
        if positions and x - positions[0] > MAX_TRAIN_LENGTH:
            raise TrainError(f"{where}, line {lineno}: this axle is more than {MAX_TRAIN_LENGTH:g} m behind the first; "
                             f"a train is at most {MAX_TRAIN_LENGTH:g} m long")
        positions.append(x)
        loads.append(p * 1e3)
    if not positions:
        raise TrainError(f"{where}: no axles (expected lines '{_COLUMNS_TEXT}')")
    heavy = [k + 1 for k, p in enumerate(loads) if p > AXLE_LOAD_WARNING_KN * 1e3]
    if heavy:
        log.warning("%s: %d axle(s) above %g kN (axle %d first), beyond any railway axle load; check the unit (kN)",
                    where, len(heavy), AXLE_LOAD_WARNING_KN, heavy[0])
    a = np.array(positions) - positions[0]
    return Train(name, a, np.array(loads), None, where)


def read_train_table(path: str | Path, name: str | None = None) -> Train:
    """A train from a CSV file (``parse_train_table``); its name defaults to the file's stem.  Errors
    name the file as given (``path``); the train's ``source`` is the file's name."""
    import dataclasses

    from vbikit._files import read_text

    path = Path(path)
    text = read_text(path, TrainError, "train table")
    return dataclasses.replace(parse_train_table(text, name or path.stem, where=str(path)), source=path.name)
