"""Contact-point response: the road-and-deck surface under a wheel, back-calculated from the
measured motion of a single-axle test vehicle, and its true value in a simulation.

Single-axle test vehicle (a mass m_v on a spring k_v and dashpot c_v standing on the surface,
vbikit's ``sprung-mass`` preset): with u_v the vehicle's vertical displacement from its static
position and u_c the surface elevation under the wheel (deck displacement + road profile, both
z up), the vehicle's equation of motion is

    m_v ü_v + c_v (u̇_v − u̇_c) + k_v (u_v − u_c) = 0.

* Undamped suspension (c_v = 0): u_c = u_v + m_v ü_v / k_v — the force balance of the mass
  (Yang, Zheng, Zhang & Xu 2018; Yang, Li & Chang 2014 for the contact-point idea).
* Damped suspension: the same equation is a first-order ODE for u_c,

      u̇_c + (k_v / c_v) u_c = g(t) / c_v,     g = m_v ü_v + c_v u̇_v + k_v u_v,

  solved exactly for g linear between samples (a first-order hold; exponential integrator):
  with a = k_v / c_v, h the sample interval, E = e^(−a h),

      u_c[n+1] = E u_c[n] + (1 / c_v) [ g[n+1] (1 − E) / a + (g[n] − g[n+1]) ((1 − E) / (a² h) − E / a) ],

  from u_c[0] (0 for a vehicle at rest on a smooth approach).  The filter is stable (E < 1) and
  forgets its start with the time constant c_v / k_v.  As c_v → 0 it tends to the undamped formula.

The simulation's own contact law (``vbikit.solve.kernels``) is s_p = φ_p·ξ + r(x_p): the deck's
modal displacement under the point plus the road elevation there; [`true_contact_response`][vbikit.driveby.true_contact_response]
returns exactly that for a point tire (0 where the wheel is off the deck, plus the road).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.errors import VbikitError
from vbikit.vehicle.model import Vehicle


@dataclass(frozen=True)
class SingleAxle:
    """Mass m [kg], suspension stiffness k [N/m] and damping c [N·s/m] of a single-axle test vehicle."""

    mass: float
    stiffness: float
    damping: float = 0.0

    @property
    def frequency_hz(self) -> float:
        """Its natural frequency on rigid ground √(k/m)/2π [Hz]."""
        return float(np.sqrt(self.stiffness / self.mass) / (2 * np.pi))

    @classmethod
    def of(cls, vehicle: Vehicle) -> "SingleAxle":
        """The parameters of a one-DOF, one-wheel vehicle (the ``sprung-mass`` preset)."""
        if vehicle.n_dof != 1 or len(vehicle.wheels) != 1:
            raise VbikitError(f"identification.method = \"contact\": the contact-point response is back-calculated for a "
                              f"single-axle test vehicle (one mass on one spring, vehicle model \"sprung-mass\"); "
                              f"{vehicle.name!r} has {vehicle.n_dof} DOFs and {len(vehicle.wheels)} wheels "
                              "(use method = \"sensor\")")
        w = vehicle.wheels[0]
        return cls(float(vehicle.mass[0, 0]), float(w.stiffness), float(w.damping))


def contact_point_response(u: ArrayLike, u_dot: ArrayLike, u_ddot: ArrayLike, vehicle: SingleAxle, dt: float,
                           u_c0: float = 0.0) -> NDArray[np.float64]:
    """Back-calculated contact-point displacement u_c [m] (module docstring) from the vehicle's
    displacement u [m] (from its static position), velocity [m/s] and acceleration [m/s²] sampled
    every ``dt`` [s]; ``u_c0`` the surface elevation at the first sample.  Undamped vehicles use
    the algebraic formula (``u_dot`` unused)."""
    u, u_ddot = np.asarray(u, float), np.asarray(u_ddot, float)
    m, k, c = vehicle.mass, vehicle.stiffness, vehicle.damping
    if c == 0.0:
        return u + m * u_ddot / k
    g = m * u_ddot + c * np.asarray(u_dot, float) + k * u
    a = k / c
    ah = a * dt
    E = np.exp(-ah)
    w1 = (1.0 - E) / a / c  # weight of g[n+1] (its full share when g is constant)
    w0 = ((1.0 - E) / (a * ah) - E / a) / c  # weight of g[n] − g[n+1]
    from scipy.signal import lfilter

    # u_c[n+1] − E u_c[n] = w1 g[n+1] + w0 (g[n] − g[n+1]) = (w1 − w0) g[n+1] + w0 g[n]
    b_coef = np.array([w1 - w0, w0])
    out, _ = lfilter(b_coef, [1.0, -E], g[1:], zi=[E * u_c0 + w0 * g[0]])
    return np.concatenate([[u_c0], out])


def contact_acceleration(u_c: ArrayLike, dt: float) -> NDArray[np.float64]:
    """ü_c [m/s²] by second-order central differences (one-sided at the ends; ``numpy.gradient``
    twice); used for identification, where the ω² weighting brings out the bridge frequency over
    the quasi-static (driving-frequency) part."""
    return np.gradient(np.gradient(np.asarray(u_c, float), dt, edge_order=2), dt, edge_order=2)


def true_contact_response(result, wheel: int = 0, road: bool = True) -> NDArray[np.float64]:
    """The surface under wheel ``wheel`` in a simulation [m], z up: the deck displacement under it
    (mode shapes on its track; 0 off the deck) plus the road elevation (``road=True``), as the
    engine's contact law for a point tire, at the result's time points."""
    crossing = result.crossing
    bridge = crossing.bridge
    x = result.wheel_positions()[:, wheel]
    origin, sign, y = crossing.point_kinematics()
    points = np.flatnonzero(crossing.contact.wheel == wheel)
    if points.size != 1:
        raise VbikitError("true_contact_response: the wheel has several contact points (use a point tire)")
    yp = float(y[points[0]])
    lo, hi = bridge.deck_extent
    on = (x >= lo) & (x <= hi)
    deck = np.zeros_like(x)
    if on.any():
        phi = bridge.mode_shapes(x[on], np.full(int(on.sum()), yp))
        deck[on] = np.einsum("tm,tm->t", result.xi[on], phi)
    if road and crossing.road is not None:
        deck = deck + crossing.road.elevation(x)
    return deck


def on_bridge(result, wheel: int = 0) -> NDArray[np.bool_]:
    """True at the result's time points where wheel ``wheel`` is on the deck."""
    lo, hi = result.crossing.bridge.deck_extent
    x = result.wheel_positions()[:, wheel]
    return (x >= lo) & (x <= hi)


def derivatives(x: ArrayLike, dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """First and second derivatives of a uniformly sampled ``x`` by fourth-order central
    differences (five-point stencils: x' ≈ (−x₂ + 8x₁ − 8x₋₁ + x₋₂) / 12h,
    x'' ≈ (−x₂ + 16x₁ − 30x₀ + 16x₋₁ − x₋₂) / 12h²; relative error ≈ (ωh)⁴ / 30 and (ωh)⁴ / 90 at
    circular frequency ω), second-order ``numpy.gradient`` at the two samples of each end."""
    x = np.asarray(x, float)
    d1 = np.gradient(x, dt, edge_order=2)
    d2 = np.gradient(d1, dt, edge_order=2)
    if x.size >= 5:
        d1[2:-2] = (-x[4:] + 8 * x[3:-1] - 8 * x[1:-3] + x[:-4]) / (12 * dt)
        d2[2:-2] = (-x[4:] + 16 * x[3:-1] - 30 * x[2:-2] + 16 * x[1:-3] - x[:-4]) / (12 * dt * dt)
    return d1, d2


def contact_acceleration_from_measured(a: ArrayLike, vehicle: SingleAxle, dt: float, a_c0: float = 0.0) -> NDArray[np.float64]:
    """Contact-point acceleration ü_c [m/s²] from the measured vehicle acceleration ü_v alone.

    The equation of motion is linear with constant coefficients, so differentiating it twice
    gives the same relation between accelerations: m_v ü_v'' + c_v (ü_v' − ü_c') + k_v (ü_v − ü_c)
    = 0 — [`contact_point_response`][vbikit.driveby.contact_point_response] applied to (ü_v, ü_v', ü_v''),
    the derivatives by fourth-order central differences (``derivatives``).  Undamped:
    ü_c = ü_v + (m_v / k_v) ü_v''.  The differences amplify noise at frequency f by ≈ (f / f_v)²:
    band-limit before identifying."""
    a = np.asarray(a, float)
    da, dda = derivatives(a, dt)
    return contact_point_response(a, da, dda, vehicle, dt, a_c0)
