"""Planar multibody railway car: car body, two bogies, four wheelsets (pitch and bounce).

Model (Zhai 2020, the vertical vehicle model of vehicle–track coupled dynamics).  One wheel line
in the vertical plane of the track axis: every stiffness, damping and load is the *whole car's*
(both rails together), as a beam bridge carries both rails.  Longitudinal positions s [m] are
rearward from the leading wheelset (vbikit's convention, ``vbikit.vehicle.model``):

    wheelsets   s_1 = 0,  s_2 = 2b,  s_3 = 2a,  s_4 = 2a + 2b
    bogies      centres (and centres of mass) at s = b and s = 2a + b
    car body    centre of mass at s = a + b + e   (e: offset behind the mid-point of the bogies)

a: half distance between the bogie centres, b: half axle spacing of a bogie.  Generalised
coordinates (z up, pitch θ positive nose-up, absolute from the unstretched springs):
z_c, θ_c (body), z_t1, θ_t1, z_t2, θ_t2 (bogies), z_w1 … z_w4 (wheelsets).  Springs:

* secondary k_s, c_s (per bogie, both sides) between the body point above bogie i and the
  bogie centre:  Δ_si = z_c + d_i θ_c − z_ti,  d_1 = a + e, d_2 = −(a − e);
* primary k_p, c_p (per wheelset, both sides) between the bogie point above wheelset j and the
  wheelset:  Δ_pj = z_ti ± b θ_ti − z_wj  (+ for the leading wheelset of the bogie);
* wheel–rail contact k_H (per wheelset, both wheels) between the wheelset and the rail:
  linearised Hertz ([`hertz_stiffness`][vbikit.vehicle.hertz_stiffness]) by default.

Equations of motion (the builder assembles exactly these, M q̈ + C q̇ + K q = F_G + contact):

    M_c z̈_c + Σ_i F_si = −M_c g,        J_c θ̈_c + Σ_i d_i F_si = 0
    M_t z̈_ti − F_si + Σ_{j∈i} F_pj = −M_t g,   J_t θ̈_ti + b (F_p,lead − F_p,trail) = 0
    M_w z̈_wj − F_pj + F_cj = −M_w g,    F_cj = k_H (z_wj − w_rail(x_j) − r(x_j))

with F_s = k_s Δ_s + c_s Δ̇_s, F_p = k_p Δ_p + c_p Δ̇_p.

Rigid contact (``contact="rigid"``): the wheelsets follow the rail.  vbikit's contact is a
spring (``vbikit.contact``), so a rigid wheel is modelled by removing the wheelset DOFs: the
primary spring–damper becomes the contact element between the bogie and the rail, and the
wheelset's weight M_w g is a gravity load on the bogie at the axle (F_G − M_w g r_j, r_j the
bogie point's row).  The bogie then feels the primary force F_pj exactly as with a wheelset, the
rail feels F_pj + M_w g (the contact element carries the wheelset's weight too, so loss of contact
is the wheel's), and only the wheelset's inertia load on the bridge, M_w (ẅ_rail + r̈), is
neglected (6 DOFs remain).

Static axle loads (statically determinate: each body rests on two supports):
P_1 = P_2 = M_w g + (M_t g + M_c g (a − e)/(2a))/2,  P_3 = P_4 = M_w g + (M_t g + M_c g (a + e)/(2a))/2.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Union

import numpy as np
from numpy.typing import NDArray

from vbikit.vehicle.builder import VehicleBuilder
from vbikit.vehicle.model import GRAVITY, Vehicle
from vbikit.vehicle.trains import TRAIN_SPEED_RANGE_KMH

#: Wheel–rail contact settings: "hertz" (linearised Hertz from the static wheel load and the
#: wheel radius), "rigid" (wheelsets follow the rail), or a stiffness [N/m] per wheelset.
Contact = Union[str, float]


def hertz_constant(wheel_radius: float, tread: str = "conical") -> float:
    """Wheel–rail Hertz contact constant G [m/N^(2/3)] of Zhai's empirical fits.

    G = 4.57 R^(−0.149) × 10⁻⁸ (conical tread), G = 3.86 R^(−0.115) × 10⁻⁸ (worn / LM tread),
    R the wheel rolling radius [m] (Zhai 2020, wheel/rail normal contact model).  The Hertz law
    is δZ = G P^(2/3) (P the normal load of one wheel [N], δZ the elastic approach [m]).  The
    classical Hertz compliance of steel on steel (Johnson 1985) gives G within 6 % for R = 0.43 m
    and a 0.3 m rail crown.
    """
    if not wheel_radius > 0:
        raise ValueError(f"wheel radius must be > 0 m, got {wheel_radius!r}")
    try:
        c, p = _HERTZ_FITS[tread]
    except KeyError:
        raise ValueError(f"unknown wheel tread {tread!r}; allowed: {', '.join(_HERTZ_FITS)}") from None
    return c * wheel_radius ** (-p) * 1e-8


#: tread -> (coefficient, exponent) of G = c R^(−p) × 1e-8 m/N^(2/3) (Zhai 2020)
_HERTZ_FITS: dict[str, tuple[float, float]] = {"conical": (4.57, 0.149), "worn": (3.86, 0.115)}


def hertz_stiffness(static_wheel_load: float, G: float | None = None, *, wheel_radius: float = 0.43,
                    tread: str = "conical") -> float:
    """Linearised Hertz wheel–rail stiffness k_H [N/m] of one wheel about its static load.

    From P = (δZ / G)^(3/2):  k_H = dP/dδZ = (3 / (2G)) P₀^(1/3)  (Zhai 2020).  ``G``
    [m/N^(2/3)] defaults to [`hertz_constant`][vbikit.vehicle.hertz_constant] of ``wheel_radius``
    [m] and ``tread``.  ``static_wheel_load`` P₀ [N] is one wheel's (half an
    axle's) load.
    """
    if not static_wheel_load > 0:
        raise ValueError(f"static wheel load must be > 0 N, got {static_wheel_load!r}")
    g = hertz_constant(wheel_radius, tread) if G is None else float(G)
    if not g > 0:
        raise ValueError(f"Hertz constant G must be > 0 m/N^(2/3), got {G!r}")
    return 1.5 * static_wheel_load ** (1.0 / 3.0) / g


@dataclass(frozen=True)
class RailCarParameters:
    """Parameters of the planar car model (module docstring), SI units, whole car (both rails).

    Parameters
    ----------
    body_mass : float
        Car body mass M_c [kg].
    body_pitch_inertia : float
        Car body pitch inertia J_c about its centre of mass [kg·m²].
    bogie_mass : float
        Mass of one bogie frame M_t [kg].
    bogie_pitch_inertia : float
        Pitch inertia J_t of one bogie about its centre [kg·m²].
    wheelset_mass : float
        Mass of one wheelset M_w [kg].
    primary_stiffness, primary_damping : float
        Primary suspension k_p [N/m], c_p [N·s/m] **per wheelset** (both axle boxes together).
    secondary_stiffness, secondary_damping : float
        Secondary suspension k_s [N/m], c_s [N·s/m] **per bogie** (both sides together).
    bogie_half_distance : float
        a [m]: half the distance between the two bogie centres.
    axle_half_spacing : float
        b [m]: half the axle spacing (wheelbase) of a bogie.
    contact : "hertz", "rigid" or float
        Wheel–rail contact: linearised Hertz (default), rigid (wheelsets follow the rail), or a
        stiffness [N/m] per wheelset.
    contact_damping : float
        Damping [N·s/m] per wheelset of the Hertz / given contact spring (default 0).
    wheel_radius : float
        Wheel rolling radius R [m] for the Hertz constant.
    tread : str
        "conical" or "worn" (the Hertz constant's fit).
    body_cg_offset : float
        e [m]: the body's centre of mass behind the mid-point of the bogie centres (|e| < a).
    name, source : str
        Label and the origin of the numbers.
    """

    body_mass: float
    body_pitch_inertia: float
    bogie_mass: float
    bogie_pitch_inertia: float
    wheelset_mass: float
    primary_stiffness: float
    primary_damping: float
    secondary_stiffness: float
    secondary_damping: float
    bogie_half_distance: float
    axle_half_spacing: float
    contact: Contact = "hertz"
    contact_damping: float = 0.0
    wheel_radius: float = 0.43
    tread: str = "conical"
    body_cg_offset: float = 0.0
    name: str = "rail-car"
    source: str = ""

    def __post_init__(self) -> None:
        for key in ("body_mass", "body_pitch_inertia", "bogie_mass", "bogie_pitch_inertia", "wheelset_mass",
                    "primary_stiffness", "secondary_stiffness", "bogie_half_distance", "axle_half_spacing",
                    "wheel_radius"):
            value = getattr(self, key)
            if not (np.isfinite(value) and value > 0):
                raise ValueError(f"rail car {key} must be > 0, got {value!r}")
        for key in ("primary_damping", "secondary_damping", "contact_damping"):
            value = getattr(self, key)
            if not (np.isfinite(value) and value >= 0):
                raise ValueError(f"rail car {key} must be >= 0, got {value!r}")
        if not abs(self.body_cg_offset) < self.bogie_half_distance:
            raise ValueError(f"rail car body_cg_offset must be inside (−a, a) = ±{self.bogie_half_distance} m, "
                             f"got {self.body_cg_offset!r}")
        if self.axle_half_spacing >= self.bogie_half_distance:
            raise ValueError("rail car axle_half_spacing b must be smaller than bogie_half_distance a")
        if isinstance(self.contact, str):
            if self.contact not in ("hertz", "rigid"):
                raise ValueError(f"rail car contact must be 'hertz', 'rigid' or a stiffness in N/m, got {self.contact!r}")
        elif not (np.isfinite(self.contact) and self.contact > 0):
            raise ValueError(f"rail car contact stiffness must be > 0 N/m, got {self.contact!r}")
        if self.tread not in _HERTZ_FITS:
            raise ValueError(f"unknown wheel tread {self.tread!r}; allowed: {', '.join(_HERTZ_FITS)}")

    @property
    def axle_offsets(self) -> tuple[float, float, float, float]:
        """s [m] of the four wheelsets behind the leading one: (0, 2b, 2a, 2a + 2b)."""
        a, b = self.bogie_half_distance, self.axle_half_spacing
        return (0.0, 2 * b, 2 * a, 2 * a + 2 * b)

    @property
    def total_mass(self) -> float:
        """M_c + 2 M_t + 4 M_w [kg]."""
        return self.body_mass + 2 * self.bogie_mass + 4 * self.wheelset_mass

    def static_axle_loads(self) -> NDArray[np.float64]:
        """Static axle loads P_1 … P_4 [N] by statics (module docstring), front to rear."""
        g, a, e = GRAVITY, self.bogie_half_distance, self.body_cg_offset
        body = self.body_mass * g
        front = self.wheelset_mass * g + 0.5 * (self.bogie_mass * g + body * (a - e) / (2 * a))
        rear = self.wheelset_mass * g + 0.5 * (self.bogie_mass * g + body * (a + e) / (2 * a))
        return np.array([front, front, rear, rear])

    def with_axle_loads(self, axle_loads: "tuple[float, ...] | list[float] | NDArray[np.float64]") -> "RailCarParameters":
        """These parameters with the body mass and its centre-of-mass offset e set so that the static
        axle loads are ``axle_loads`` [N] (four values, front to rear; equal within each bogie, as
        a bogie's centre of mass is at its centre).  Bogies, wheelsets, inertias and suspensions
        are kept."""
        p = np.asarray(axle_loads, float)
        if p.shape != (4,) or not np.all(np.isfinite(p)) or np.any(p <= 0):
            raise ValueError(f"rail car axle_loads must be four loads > 0 N (front to rear), got {axle_loads!r}")
        for i, j in ((0, 1), (2, 3)):
            if abs(p[i] - p[j]) > 1e-9 * max(p[i], p[j]):
                raise ValueError(f"rail car axle_loads {i + 1} and {j + 1} must be equal (one bogie), got {p[i]!r}, {p[j]!r}")
        g, a = GRAVITY, self.bogie_half_distance
        # load of the body on each bogie's secondary suspension
        s_front = p[0] + p[1] - (self.bogie_mass + 2 * self.wheelset_mass) * g
        s_rear = p[2] + p[3] - (self.bogie_mass + 2 * self.wheelset_mass) * g
        if s_front <= 0 or s_rear <= 0:
            raise ValueError(f"rail car axle_loads {list(p)} N are below the bogie and wheelset weight "
                             f"{(self.bogie_mass + 2 * self.wheelset_mass) * g / 2:.0f} N per axle")
        body_mass = (s_front + s_rear) / g
        offset = a * (s_rear - s_front) / (s_rear + s_front)
        return dataclasses.replace(self, body_mass=body_mass, body_cg_offset=offset)

    def contact_stiffness(self) -> NDArray[np.float64] | None:
        """Wheel–rail stiffness [N/m] per wheelset (both wheels in parallel, each carrying half the
        static axle load), front to rear; None for rigid contact."""
        if self.contact == "rigid":
            return None
        if self.contact == "hertz":
            return np.array([2.0 * hertz_stiffness(0.5 * p, wheel_radius=self.wheel_radius, tread=self.tread)
                             for p in self.static_axle_loads()])
        return np.full(4, float(self.contact))


def rail_car(params: RailCarParameters, axle_loads: "tuple[float, ...] | list[float] | None" = None) -> Vehicle:
    """The planar car (module docstring) as a [`Vehicle`][vbikit.vehicle.Vehicle].

    Parameters
    ----------
    params : RailCarParameters
        The car.
    axle_loads : sequence of 4 floats, optional
        Static axle loads [N], front to rear: the body mass and centre-of-mass offset are set to
        give them ([`RailCarParameters.with_axle_loads`][vbikit.vehicle.RailCarParameters.with_axle_loads]).

    Returns
    -------
    Vehicle
        10 DOFs (body, bogies: bounce and pitch; wheelsets: bounce), or 6 with rigid contact.
        Wheels ``w1`` … ``w4`` front to rear at s = 0, 2b, 2a, 2a + 2b, lateral y = 0 (one wheel
        line: a planar model on a beam; the bridge's lateral offset places it).
    """
    p = params if axle_loads is None else params.with_axle_loads(axle_loads)
    a, b, e = p.bogie_half_distance, p.axle_half_spacing, p.body_cg_offset
    s_w = p.axle_offsets
    s_bogie = (b, 2 * a + b)
    vb = VehicleBuilder(p.name)
    body = vb.body("body", p.body_mass, a + b + e, pitch_inertia=p.body_pitch_inertia, pitch=True)
    bogies = [vb.body(f"bogie{i + 1}", p.bogie_mass, s, pitch_inertia=p.bogie_pitch_inertia, pitch=True)
              for i, s in enumerate(s_bogie)]
    for bogie, s in zip(bogies, s_bogie):
        vb.spring(body.point(s), bogie.point(s), p.secondary_stiffness, p.secondary_damping)
    k_contact = p.contact_stiffness()
    for j, s in enumerate(s_w):
        bogie = bogies[j // 2]
        if k_contact is None:  # rigid: the primary suspension is the contact element
            vb.wheel(f"w{j + 1}", bogie.point(s), s, 0.0, p.primary_stiffness, p.primary_damping)
        else:
            wheelset = vb.body(f"wheelset{j + 1}", p.wheelset_mass, s)
            vb.spring(bogie.point(s), wheelset.heave, p.primary_stiffness, p.primary_damping)
            vb.wheel(f"w{j + 1}", wheelset.heave, s, 0.0, float(k_contact[j]), p.contact_damping)
    values = {f.name: getattr(p, f.name) for f in dataclasses.fields(p)
              if isinstance(getattr(p, f.name), (int, float)) and not isinstance(getattr(p, f.name), bool)}
    kind = "rigid contact" if k_contact is None else "linearised Hertz contact" if p.contact == "hertz" else "elastic contact"
    car = vb.build(f"{p.name}: planar rail car, body + 2 bogies + 4 wheelsets, {kind}"
                   + (f" ({p.source})" if p.source else ""), values)
    if k_contact is None:  # the wheelsets' weight rests on the bogies' axle points (module docstring)
        car = dataclasses.replace(car, gravity=car.gravity - p.wheelset_mass * GRAVITY * sum(w.row for w in car.wheels))
    return dataclasses.replace(car, usual_speed_kmh=TRAIN_SPEED_RANGE_KMH, railway=True)


#: Documented cars (whole-car values; per-side literature values × 2 for the planar model).
#: [public] numbers as printed in the source (read through their transcription in TTB-2D,
#: Cantero 2022, file ``TrainProp_*.m``); [substitute] our choice where the source gives none.
RAIL_CAR_PRESETS: dict[str, RailCarParameters] = {
    p.name: p
    for p in (
        # Zhai, Wang & Cai (2009), Vehicle System Dynamics 47(11), 1349–1376: "China Star" power car.
        # wheel radius 0.43 m [substitute].
        RailCarParameters(
            body_mass=59364.2, body_pitch_inertia=1.723e6, bogie_mass=5630.8, bogie_pitch_inertia=9487.0,
            wheelset_mass=1843.5, primary_stiffness=2 * 2.3996e6, primary_damping=2 * 30e3,
            secondary_stiffness=2 * 0.8858e6, secondary_damping=2 * 45e3, bogie_half_distance=5.73,
            axle_half_spacing=1.5, wheel_radius=0.43, name="china-star-power-car",
            source="Zhai, Wang & Cai 2009, VSD 47(11); wheel radius substitute"),
        # Goicolea (2014), Simplified mechanical description of AVE S-103 (ICE3 Velaro E), coaches 2, 3, 6, 7.
        # wheel radius 0.46 m [substitute: nominal new wheel diameter 920 mm].
        RailCarParameters(
            body_mass=47800.0, body_pitch_inertia=1957888.0, bogie_mass=3500.0, bogie_pitch_inertia=1715.0,
            wheelset_mass=1800.0, primary_stiffness=2 * 1200e3, primary_damping=2 * 10e3,
            secondary_stiffness=2 * 350e3, secondary_damping=2 * 20e3, bogie_half_distance=17.375 / 2,
            axle_half_spacing=1.25, wheel_radius=0.46, name="ice3-coach",
            source="Goicolea 2014, AVE S-103 / ICE3 coaches 2, 3, 6, 7; wheel radius substitute"),
        # Iwnicki (1998), Manchester benchmarks for rail vehicle simulation, VSD 30(3-4), 295–313.
        # wheel radius 0.46 m [substitute].
        RailCarParameters(
            body_mass=32000.0, body_pitch_inertia=1.97e6, bogie_mass=2615.0, bogie_pitch_inertia=1476.0,
            wheelset_mass=1813.0, primary_stiffness=2 * 1200e3, primary_damping=2 * 4e3,
            secondary_stiffness=2 * 430e3, secondary_damping=2 * 20e3, bogie_half_distance=9.5,
            axle_half_spacing=1.28, wheel_radius=0.46, name="manchester-benchmark",
            source="Iwnicki 1998, VSD 30(3-4); wheel radius substitute"),
    )
}
