"""Time histories of one crossing and the responses derived from them."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit.solve.crossing import Crossing


class DivergenceError(ValueError):
    """An integration whose states became non-finite; the message gives the step and time."""


def check_finite(result: "CrossingResult") -> "CrossingResult":
    """``result`` if every state history is finite, else :class:`DivergenceError` naming the
    first step (and its time) with a non-finite bridge, vehicle or tire value."""
    ok = np.ones(result.time.size, bool)
    for a in (result.xi, result.xi_dot, result.xi_ddot, result.q, result.q_dot, result.q_ddot, result.wheel_forces):
        if a.size:
            ok &= np.isfinite(a).reshape(a.shape[0], -1).all(axis=1)
    if not ok.all():
        i = int(np.argmin(ok))
        c = result.crossing
        raise DivergenceError(
            f"the integration diverged at step {i} of {result.n_steps} (t = {result.time[i]:.6g} s, front axle at "
            f"x = {result.front_position[i]:.3f} m): non-finite states with {c.integrator} at dt = {result.dt:.3g} s; "
            "use a smaller crossing.dt (or leave it out), fewer bridge modes, or integrator = \"newmark\"")
    return result


@dataclass(frozen=True)
class CrossingResult:
    """Histories at the n_t = n_steps + 1 time points ``time`` [s].

    ``xi``, ``xi_dot``, ``xi_ddot`` (n_t, n_modes): bridge modal coordinates and rates;
    ``q``, ``q_dot``, ``q_ddot`` (n_t, n_dof): vehicle coordinates (absolute, z up);
    ``wheel_forces`` (n_t, n_wheels): tire forces [N], compression positive (0 = no contact);
    ``contact_lengths`` (n_t, n_wheels): length [m] of the patch in contact (0 for point tires);
    ``front_position`` [m], ``speed`` [m/s] of the vehicle (several vehicles: (n_t, n_vehicles),
    x of each front axle and its speed).  ``dt`` [s] is the spacing of the stored time points;
    ``integration_dt`` [s] the integrator's step (larger ``dt`` when the histories were thinned,
    ``simulate(..., output_every=k)``).
    """

    crossing: Crossing
    time: NDArray[np.float64]
    dt: float
    front_position: NDArray[np.float64]
    speed: NDArray[np.float64]
    xi: NDArray[np.float64]
    xi_dot: NDArray[np.float64]
    xi_ddot: NDArray[np.float64]
    q: NDArray[np.float64]
    q_dot: NDArray[np.float64]
    q_ddot: NDArray[np.float64]
    wheel_forces: NDArray[np.float64]
    contact_lengths: NDArray[np.float64]
    integration_dt: float | None = None

    @property
    def travel(self) -> NDArray[np.float64]:
        """The vehicles' travel s_v [m] at ``time`` ((n_t,) for one vehicle: its front-axle x;
        else (n_t, n_vehicles))."""
        if not self.crossing.vehicles:
            return self.front_position
        return self.crossing.travel(self.time)

    def wheel_positions(self) -> NDArray[np.float64]:
        """x [m] of every wheel centre at every time (n_t, n_wheels), each vehicle on its own path."""
        crossing = self.crossing
        offsets = np.array([w.offset for w in crossing.vehicle.wheels])
        if not crossing.vehicles:
            return self.front_position[:, None] - offsets[None, :]
        n_per = np.diff(crossing.vehicle.wheel_offsets)
        veh = np.repeat(np.arange(len(crossing.vehicles)), n_per)
        sign = np.array([m.sign for m in crossing.vehicles])[veh]
        return self.front_position[:, veh] - sign[None, :] * offsets[None, :]

    @property
    def n_steps(self) -> int:
        return int(self.time.size - 1)

    def point(self, x: float | None = None, y: float | None = None) -> tuple[float, float]:
        """The deck point (x, y) [m] responses are read at: x default the bridge's
        ``default_response_x`` (midspan; a continuous beam: the middle of its first span), y default
        the bridge's ``default_response_y`` (its default girder on a slab-on-girder deck)."""
        b = self.crossing.bridge
        return (float(getattr(b, "default_response_x", b.span / 2)) if x is None else float(x),
                float(getattr(b, "default_response_y", 0.0)) if y is None else float(y))

    def _shapes(self, x: float | None, y: float | None) -> NDArray[np.float64]:
        return self.crossing.bridge.mode_shapes(*([v] for v in self.point(x, y)))[0]

    def displacement(self, x: float | None = None, y: float | None = None) -> NDArray[np.float64]:
        """Deck vertical displacement [m] at (x, y) (z up: negative under load); defaults: :meth:`point`."""
        return self.xi @ self._shapes(x, y)

    def velocity(self, x: float | None = None, y: float | None = None) -> NDArray[np.float64]:
        """Deck vertical velocity [m/s] at (x, y)."""
        return self.xi_dot @ self._shapes(x, y)

    def acceleration(self, x: float | None = None, y: float | None = None) -> NDArray[np.float64]:
        """Deck vertical acceleration [m/s²] at (x, y)."""
        return self.xi_ddot @ self._shapes(x, y)

    def strain(self, x: float | None = None, y: float | None = None) -> NDArray[np.float64]:
        """Bottom-fibre longitudinal strain [-] at (x, y), tension positive."""
        return self.xi @ self.crossing.bridge.strain_shapes(*([v] for v in self.point(x, y)))[0]
