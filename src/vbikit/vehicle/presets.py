"""Vehicle presets.  Each function returns a [`Vehicle`][vbikit.vehicle.Vehicle]; every
number is labelled [paper] (printed in the paper), [public] (standard or published benchmark)
or [substitute] (our documented engineering choice, see ``docs/model-data.md``).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import partial
from typing import Any, Callable

from vbikit.vehicle.axles import axle_truck, semitrailer_3s2
from vbikit.vehicle.builder import VehicleBuilder
from vbikit.vehicle.model import GRAVITY, Vehicle
from vbikit.vehicle.trains import TRAIN_PRESETS, get_train, train_vehicle


def moving_force(force: float = 100e3) -> Vehicle:
    """A constant vertical force P [N] moving over the bridge (no DOFs, no tire dynamics).

    The classical moving-load problem (Frýba 1972, ch. 1).  ``force`` default 100 kN is
    arbitrary [substitute]: dynamic amplification does not depend on it.
    """
    vb = VehicleBuilder("moving-force")
    vb.wheel("P", {}, 0.0, 0.0, 0.0, 0.0, fixed_load=force)
    return vb.build("moving constant force", {"force": force})


def sprung_mass(mass: float = 5750.0, stiffness: float = 1595e3, damping: float = 0.0) -> Vehicle:
    """A single mass on a spring–dashpot in contact with the surface (1 DOF).

    Defaults are Yang & Yau's benchmark vehicle [public] (Yang, Y.B. & Yau, J.D. 1997,
    *J. Eng. Mech.* 123(11), 1120–1128): M_v = 5750 kg, k_v = 1595 kN/m, undamped.
    The spring is the contact element, so tire models act on it.
    """
    vb = VehicleBuilder("sprung-mass")
    body = vb.body("body", mass, 0.0)
    vb.wheel("w1", body.heave, 0.0, 0.0, stiffness, damping)
    return vb.build("sprung mass (1 DOF)", {"mass": mass, "stiffness": stiffness, "damping": damping})


def quarter_car(
    sprung_mass: float = 10_000.0,
    unsprung_mass: float = 1_000.0,
    suspension_stiffness: float = 400e3,
    suspension_damping: float = 10e3,
    tire_stiffness: float = 1_750e3,
    tire_damping: float = 3e3,
) -> Vehicle:
    """Two-mass quarter car: body on a suspension over an axle on a tire (2 DOF; Biggs 1964 §8.5 type).

    Defaults are [substitute] heavy-vehicle values (body bounce ≈ 0.9 Hz, axle hop ≈ 7.4 Hz).
    """
    vb = VehicleBuilder("quarter-car")
    body = vb.body("body", sprung_mass, 0.0)
    axle = vb.body("axle", unsprung_mass, 0.0)
    vb.spring(body.heave, axle.heave, suspension_stiffness, suspension_damping)
    vb.wheel("w1", axle.heave, 0.0, 0.0, tire_stiffness, tire_damping)
    return vb.build(
        "quarter car (2 DOF)",
        {
            "sprung_mass": sprung_mass,
            "unsprung_mass": unsprung_mass,
            "suspension_stiffness": suspension_stiffness,
            "suspension_damping": suspension_damping,
            "tire_stiffness": tire_stiffness,
            "tire_damping": tire_damping,
        },
    )


def _axle_with_wheels(vb: VehicleBuilder, name: str, mass: float, s: float, b: float, carrier, k_susp, c_susp, k_tire, c_tire):
    """Axle with bounce and roll ([substitute] roll inertia m·b²), suspension and tires at ±b."""
    axle = vb.body(name, mass, s, roll_inertia=mass * b**2, roll=True)
    for side, y in (("left", b), ("right", -b)):
        vb.spring(carrier.point(s, y), axle.point(s, y), k_susp, c_susp)
        vb.wheel(f"{name}_{side}", axle.point(s, y), s, y, k_tire, c_tire)
    return axle


def hs20_44() -> Vehicle:
    """The paper's 11-DOF HS20-44 tractor–semitrailer (Table 1 of the paper).

    DOFs: tractor bounce, pitch, roll; trailer pitch and roll (its bounce tied to the tractor
    at the fifth wheel); bounce and roll of each of three axles.  Upper (suspension) and lower
    (tire) spring–dampers per side at ±b.  All masses, inertias, stiffnesses, dampings and
    L1–L6, b are [paper] Table 1; spring and damper values are taken per side.

    Geometry [computed] from Table 1 (model data §2), s rearward from axle 1: axle 1 at 0;
    tractor CG at L1 = 1.698; fifth wheel at L1 + L5 = 3.913; axle 2 at L1 + L2 = 4.267;
    trailer CG at 6.251; axle 3 at 8.534 m.  Static axle loads then are ≈ 30.7 / 134.2 /
    136.0 kN (nominal HS20-44: 35.6 / 142.3 / 142.3 kN).  Axle roll inertia m_axle·b²
    [substitute] (not printed).  As printed, the pitch inertias (2022, 33153 kg·m²) are
    smaller than the roll inertias (8544, 181216 kg·m²), unusual for a long trailer; we use
    Table 1 as printed.
    """
    L1, L2, L3, L5, b = 1.698, 2.569, 1.984, 2.215, 1.1
    s_axle = (0.0, L1 + L2, L1 + L2 + L3 + 2.283)  # L4 = 2.283
    s5 = L1 + L5
    vb = VehicleBuilder("hs20-44")
    tractor = vb.body("tractor", 2612.0, L1, pitch_inertia=2022.0, roll_inertia=8544.0, pitch=True, roll=True)
    trailer = vb.hinged_body("trailer", 26113.0, L1 + L2 + L3, tractor, s5, pitch_inertia=33153.0, roll_inertia=181216.0, roll=True)
    for i, (m, carrier, ks, kt, cs) in enumerate(
        (
            (490.0, tractor, 242604.0, 875082.0, 2190.0),
            (808.0, tractor, 1903172.0, 3503307.0, 7882.0),
            (653.0, trailer, 1969034.0, 3507429.0, 7182.0),
        )
    ):
        _axle_with_wheels(vb, f"axle{i + 1}", m, s_axle[i], b, carrier, ks, cs, kt, 2000.0)
    return vb.build("HS20-44 tractor-semitrailer, 11 DOF (paper Table 1)")


def two_axle_truck() -> Vehicle:
    """Two-axle truck (H20-44 loads) [substitute] (model data §2).

    HS20 tractor hardware with a rigid body of 16,837 kg, CG 3.471 m behind the front axle,
    pitch / roll inertia 8.52e4 / 1.49e4 kg·m²; axle masses 490 / 808 kg; suspension k
    242,604 / 1,903,172 N/m, c 2190 / 7882 N·s/m; tire k 875,082 / 3,503,307 N/m, c 2000 N·s/m;
    b = 1.1 m; wheelbase 4.267 m.  Axle loads ≈ 35.6 / 142.3 kN.  7 DOF: body bounce, pitch,
    roll; bounce and roll of both axles.
    """
    b = 1.1
    vb = VehicleBuilder("two-axle")
    body = vb.body("body", 16837.0, 3.471, pitch_inertia=8.52e4, roll_inertia=1.49e4, pitch=True, roll=True)
    _axle_with_wheels(vb, "axle1", 490.0, 0.0, b, body, 242604.0, 2190.0, 875082.0, 2000.0)
    _axle_with_wheels(vb, "axle2", 808.0, 4.267, b, body, 1903172.0, 7882.0, 3503307.0, 2000.0)
    return vb.build("two-axle truck, H20-44 loads (substitute parameters)")


#: [paper] static axle loads of the field-test dump truck [N] (paper §4.2)
DUMP_TRUCK_AXLE_LOADS = (80.0e3, 95.6e3, 95.6e3)


def dump_truck() -> Vehicle:
    """The field-test three-axle dump truck (paper §4.2) with a load-equalising rear tandem.

    * [paper] static axle loads 80.0 / 95.6 / 95.6 kN; middle axle 6.25 m behind the front axle
      and 1.2 m ahead of the rear axle (axles at s = 0, 6.25, 7.45 m).
    * [substitute] (model data §2) axle masses 700 / 1100 / 1100 kg; suspension k 0.3e6 / 1.0e6 /
      1.0e6 N/m and c 10e3 / 20e3 / 20e3 N·s/m per side; tire k 0.875e6 / 1.75e6 / 1.75e6 N/m and
      c 2e3 / 4e3 / 4e3 N·s/m per side; half-track b = 0.9 m; axle roll inertia m·b².
    * [substitute] rear tandem: one walking beam per side (mass 250 kg, pitch inertia
      250 · 1.2²/12 = 30 kg·m²), pinned at its centre (s = 6.85 m, y = ±b) to the body, the two
      rear axles hung from its ends by the suspension springs
      ([`pivoted_beam`][vbikit.vehicle.VehicleBuilder.pivoted_beam]).  A rigid body on three
      spring-supported axles is statically indeterminate (plain springs give ≈ 78 / 107 / 86 kN);
      with the beams the body rests on two supports (front suspension, tandem pivots) and the
      beams split their load equally, so the static axle loads are exactly the paper's.
    * [substitute] sprung mass 24,745 kg (model data §2) = body + both beams, with the body
      mass set so that the total weight is exactly 271.2 kN with g = 9.81 m/s² (body 24,245.26 kg,
      +0.26 kg); body CG from moment balance on its two supports (≈ 4.74 m behind axle 1);
      body pitch / roll inertia 1.5e5 / 2.5e4 kg·m² (≈ m(L² + h²)/12 for an 8.5 m × 2.5 m body).

    11 DOF: body bounce, pitch, roll; pitch of each walking beam; bounce and roll of each axle.
    """
    b = 0.9
    s1, s2, s3 = 0.0, 6.25, 7.45
    s_pivot = 0.5 * (s2 + s3)
    m_axle = (700.0, 1100.0, 1100.0)
    m_beam, j_beam = 250.0, 250.0 * 1.2**2 / 12.0
    g = GRAVITY
    total_mass = sum(DUMP_TRUCK_AXLE_LOADS) / g
    m_body = total_mass - sum(m_axle) - 2 * m_beam
    r_front = DUMP_TRUCK_AXLE_LOADS[0] - m_axle[0] * g  # body load on the front suspension [N]
    s_cg = s_pivot * (m_body * g - r_front) / (m_body * g)
    vb = VehicleBuilder("dump-truck")
    body = vb.body("body", m_body, s_cg, pitch_inertia=1.5e5, roll_inertia=2.5e4, pitch=True, roll=True)
    _axle_with_wheels(vb, "axle1", m_axle[0], s1, b, body, 0.3e6, 10e3, 0.875e6, 2e3)
    beams = {y: vb.pivoted_beam(f"beam_{side}", body, s_pivot, y, mass=m_beam, pitch_inertia=j_beam)
             for side, y in (("left", b), ("right", -b))}
    for i, s in ((2, s2), (3, s3)):
        axle = vb.body(f"axle{i}", m_axle[i - 1], s, roll_inertia=m_axle[i - 1] * b**2, roll=True)
        for side, y in (("left", b), ("right", -b)):
            vb.spring(beams[y].point(s), axle.point(s, y), 1.0e6, 20e3)
            vb.wheel(f"axle{i}_{side}", axle.point(s, y), s, y, 1.75e6, 4e3)
    return vb.build("three-axle dump truck of the field test, walking-beam rear tandem (paper §4.2; substitute parameters)",
                    {"body_mass": m_body, "body_cg": s_cg})


def _train(name: str) -> Vehicle:
    """A preset train (vbikit.vehicle.trains) as moving axle loads."""
    return train_vehicle(get_train(name))


#: the SI unit of every vehicle preset parameter and of every number a preset's vehicle states
#: (``Vehicle.parameters``), by name ("-": dimensionless or a count; None: not a number, e.g. group
#: names) — the one place: ``vbikit presets`` and docs/reference/scenario-keys.md read it
PARAMETER_UNITS: dict[str, str | None] = {
    "force": "N", "mass": "kg", "stiffness": "N/m", "damping": "N·s/m",
    "sprung_mass": "kg", "unsprung_mass": "kg", "suspension_stiffness": "N/m", "suspension_damping": "N·s/m",
    "tire_stiffness": "N/m", "tire_damping": "N·s/m",
    "body_mass": "kg", "body_cg": "m",  # the dump truck's body and its CG behind axle 1
    "axle_loads": "N", "axle_spacings": "m", "groups": None, "tractor_groups": "-", "unsprung_masses": "kg",
    "half_track": "m", "tire_deflection": "m", "suspension_deflection": "m", "suspension_damping_ratio": "-",
    "tire_damping_ratio": "-", "gross_weight": "N", "n_axles": "-", "total_load": "N",
}


def parameter_unit(name: str) -> str | None:
    """The SI unit of vehicle parameter ``name`` (``PARAMETER_UNITS``; "-": dimensionless, None: not a
    number or not listed)."""
    return PARAMETER_UNITS.get(name)


@dataclass(frozen=True)
class VehiclePreset:
    name: str
    build: Callable[..., Vehicle]
    #: parameters the scenario may set for this preset
    parameters: tuple[str, ...] = ()
    #: parameters that are not a single number: name -> "numbers" (list of numbers), "names"
    #: (list of strings) or "integer"
    kinds: dict[str, str] = field(default_factory=dict)
    #: parameters without a default (the scenario must give them)
    required: tuple[str, ...] = ()
    #: parameters of an example vehicle (``vbikit presets`` builds it), when some are required
    example: dict[str, Any] = field(default_factory=dict)

    def kind(self, parameter: str) -> str:
        """"number", "numbers", "names" or "integer"."""
        return self.kinds.get(parameter, "number")

    def example_vehicle(self) -> Vehicle:
        return self.build(**self.example)


VEHICLE_PRESETS: dict[str, VehiclePreset] = {
    p.name: p
    for p in (
        VehiclePreset("moving-force", moving_force, ("force",)),
        VehiclePreset("sprung-mass", sprung_mass, ("mass", "stiffness", "damping")),
        VehiclePreset(
            "quarter-car",
            quarter_car,
            ("sprung_mass", "unsprung_mass", "suspension_stiffness", "suspension_damping", "tire_stiffness", "tire_damping"),
        ),
        VehiclePreset("hs20-44", hs20_44),
        VehiclePreset("two-axle", two_axle_truck),
        VehiclePreset("dump-truck", dump_truck),
        VehiclePreset("3s2", semitrailer_3s2),
        VehiclePreset(
            "axles",
            axle_truck,
            ("axle_loads", "axle_spacings", "groups", "tractor_groups", "unsprung_masses", "half_track",
             "tire_deflection", "suspension_deflection", "suspension_damping_ratio", "tire_damping_ratio"),
            kinds={"axle_loads": "numbers", "axle_spacings": "numbers", "groups": "names", "tractor_groups": "integer",
                   "unsprung_masses": "numbers"},
            required=("axle_loads", "axle_spacings"),
            # a 3-S2 at US legal group loads: 12 / 34 / 34 kip (53.4 / 151.2 / 151.2 kN)
            example={"axle_loads": [53.4e3, 75.6e3, 75.6e3, 75.6e3, 75.6e3], "axle_spacings": [5.5, 1.3, 9.5, 1.3]},
        ),
        # trains as chains of moving axle loads (vbikit.vehicle.trains): hslm-a1 … hslm-a10, ice3
        *(VehiclePreset(name, partial(_train, name)) for name in TRAIN_PRESETS),
    )
}
