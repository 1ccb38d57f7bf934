"""Assemble a multibody vehicle from rigid bodies, spring–dampers and wheels.

Each body's heave z (at its centre of gravity), pitch θ and roll φ are linear functions of
the generalised coordinates (a body may own them, or — like a semitrailer hinged at the
fifth wheel — inherit its heave from another body).  Mass and gravity follow from the
kinetic and potential energy: M = Σ_b (m h hᵀ + J_θ p pᵀ + J_φ r rᵀ), F_G = −g Σ_b m h; a
spring k between points with displacement rows a and b adds k (a−b)(a−b)ᵀ to K.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vbikit.vehicle.model import GRAVITY, Vehicle, Wheel

Row = dict[int, float]


def _combine(*terms: tuple[float, Row]) -> Row:
    out: Row = {}
    for coef, row in terms:
        for i, c in row.items():
            out[i] = out.get(i, 0.0) + coef * c
    return out


@dataclass
class Body:
    """A rigid body: mass [kg], pitch/roll inertias [kg·m²] about its CG at s_cg [m]."""

    name: str
    mass: float
    s_cg: float
    pitch_inertia: float
    roll_inertia: float
    heave: Row
    pitch: Row = field(default_factory=dict)
    roll: Row = field(default_factory=dict)

    def point(self, s: float, y: float = 0.0) -> Row:
        """Vertical displacement row of the body point at (s, y) (``_combine`` of its heave, pitch and roll rows)."""
        out: Row = {}
        for coef, row in ((1.0, self.heave), (self.s_cg - s, self.pitch), (y, self.roll)):
            for i, c in row.items():
                out[i] = out.get(i, 0.0) + coef * c
        return out


class VehicleBuilder:
    """Incremental assembly of a [`Vehicle`][vbikit.vehicle.Vehicle].

    Parameters
    ----------
    name : str
        The vehicle's name.
    """

    def __init__(self, name: str) -> None:
        self.name = name
        self.dofs: list[str] = []
        self.bodies: list[Body] = []
        self.springs: list[tuple[Row, Row, float, float]] = []
        self.wheels: list[tuple[str, float, float, float, float, Row, float]] = []

    def _dof(self, name: str) -> Row:
        self.dofs.append(name)
        return {len(self.dofs) - 1: 1.0}

    def body(
        self,
        name: str,
        mass: float,
        s_cg: float,
        *,
        pitch_inertia: float = 0.0,
        roll_inertia: float = 0.0,
        heave: Row | None = None,
        pitch: bool = False,
        roll: bool = False,
    ) -> Body:
        """Add a body; it owns a heave DOF unless ``heave`` (a row) ties it to another body."""
        b = Body(
            name,
            mass,
            s_cg,
            pitch_inertia,
            roll_inertia,
            heave=self._dof(f"{name}_heave") if heave is None else heave,
        )
        if pitch:
            b.pitch = self._dof(f"{name}_pitch")
        if roll:
            b.roll = self._dof(f"{name}_roll")
        self.bodies.append(b)
        return b

    def hinged_body(
        self, name: str, mass: float, s_cg: float, parent: Body, s_hinge: float, *, pitch_inertia: float, roll_inertia: float = 0.0, roll: bool = False
    ) -> Body:
        """A body pinned (vertically) to ``parent`` at s_hinge, pitching about the pin (a semitrailer)."""
        b = self.body(name, mass, s_cg, pitch_inertia=pitch_inertia, roll_inertia=roll_inertia, heave={}, pitch=True, roll=roll)
        # z_cg = z_hinge − (s_cg − s_hinge)·θ
        b.heave = _combine((1.0, parent.point(s_hinge)), (-(s_cg - s_hinge), b.pitch))
        return b

    def pivoted_beam(
        self, name: str, parent: Body, s_pivot: float, y_pivot: float = 0.0, *, mass: float, pitch_inertia: float
    ) -> Body:
        """A rigid beam pinned at its centre (s_pivot, y_pivot) to ``parent``, free to pitch (a walking beam).

        Its CG is at the pivot and it moves with the parent's point there (no heave DOF of its own,
        no roll); it owns one pitch DOF.  Two loads on the beam at equal arms ±a from the pivot are
        equal in static equilibrium (moment balance about the pin: F₁ a = F₂ a), so a tandem axle
        group hung from its ends is load-equalising whatever the spring stiffnesses.  Mass [kg] and
        pitch inertia [kg·m²] must be > 0 for a regular mass matrix.
        """
        if not (mass > 0 and pitch_inertia > 0):
            raise ValueError(f"pivoted beam '{name}': mass and pitch_inertia must be > 0, got {mass!r}, {pitch_inertia!r}")
        b = self.body(name, mass, s_pivot, pitch_inertia=pitch_inertia, heave={}, pitch=True)
        b.heave = dict(parent.point(s_pivot, y_pivot))  # z_cg = z of the parent's pin point
        return b

    def spring(self, a: Row, b: Row | None, stiffness: float, damping: float = 0.0) -> None:
        """A vertical spring–damper between two points (``b=None`` is the ground)."""
        self.springs.append((a, b or {}, stiffness, damping))

    def wheel(self, name: str, at: Row, s: float, y: float, stiffness: float, damping: float, fixed_load: float = 0.0) -> None:
        """A wheel whose centre moves as row ``at``, at (s, y) on the vehicle, with its tire k, c."""
        self.wheels.append((name, s, y, stiffness, damping, at, fixed_load))

    def build(self, description: str = "", parameters: dict[str, float] | None = None) -> Vehicle:
        """The [`Vehicle`][vbikit.vehicle.Vehicle]: M = Σ_b (m h hᵀ + J_θ p pᵀ + J_φ r rᵀ), K (C) = Σ_s k (c) d dᵀ
        with d = a − b, F_G = −g Σ_b m h (module docstring): the rows stacked, each sum over bodies or
        springs one reduction in their order (the values of adding the terms one by one)."""
        n = len(self.dofs)

        def dense(rows: list[Row]) -> np.ndarray:
            v = [0.0] * (len(rows) * n)  # (a list: its items added to as floats, then one array)
            for k, row in enumerate(rows):
                for i, c in row.items():
                    v[k * n + i] += c
            return np.array(v, float).reshape(len(rows), n)

        bodies, springs, wheel_specs = self.bodies, self.springs, self.wheels
        # every row once, in one array: heave, pitch, roll of the bodies, the springs' ends, the wheels
        every = dense([b.heave for b in bodies] + [b.pitch for b in bodies] + [b.roll for b in bodies]
                      + [a for a, _, _, _ in springs] + [b_ for _, b_, _, _ in springs] + [row for *_, row, _ in wheel_specs])
        return assemble(self.name, tuple(self.dofs), every,
                        [(b.name, b.mass, b.s_cg, b.pitch_inertia, b.roll_inertia) for b in bodies],
                        [(ks, cs) for _, _, ks, cs in springs], [(nm, s, y, kt, ct, fl) for nm, s, y, kt, ct, _, fl in wheel_specs],
                        description, parameters)


def assemble(name: str, dofs: tuple[str, ...], every: np.ndarray, bodies: list[tuple[str, float, float, float, float]],
             springs: list[tuple[float, float]], wheel_specs: list[tuple[str, float, float, float, float, float]],
             description: str = "", parameters: dict[str, float] | None = None) -> Vehicle:
    """The [`Vehicle`][vbikit.vehicle.Vehicle] of ``VehicleBuilder.build`` from its dense rows ``every``
    (heave, pitch, roll rows of the bodies, the springs' first and second ends, the wheels' rows, stacked
    in that order), the bodies' (name, mass, s_cg, pitch and roll inertias), the springs' (k, c) and the
    wheels' (name, s, y, k, c, fixed load): M = Σ_b (m h hᵀ + J_θ p pᵀ + J_φ r rᵀ), K (C) = Σ_s k (c) d dᵀ
    with d = a − b, F_G = −g Σ_b m h, each sum one reduction in the bodies' or springs' order (the values
    of adding the terms one by one).  ``every`` is the vehicle's own (its rows are views of it)."""
    n = len(dofs)

    def outer_sum(coef: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """Σ_k coef_k · row_k row_kᵀ (n × n)."""
        return (coef[:, None, None] * (rows[:, :, None] * rows[:, None, :])).sum(axis=0) if len(rows) \
            else np.zeros((n, n))

    nb, ns = len(bodies), len(springs)
    h, p, r = every[:nb], every[nb:2 * nb], every[2 * nb:3 * nb]
    mass = np.array([b[1] for b in bodies], float)
    m = (mass[:, None, None] * (h[:, :, None] * h[:, None, :])
         + np.array([b[3] for b in bodies], float)[:, None, None] * (p[:, :, None] * p[:, None, :])
         + np.array([b[4] for b in bodies], float)[:, None, None] * (r[:, :, None] * r[:, None, :])
         ).sum(axis=0) if bodies else np.zeros((n, n))
    fg = -((GRAVITY * mass)[:, None] * h).sum(axis=0) if bodies else np.zeros(n)
    d = every[3 * nb:3 * nb + ns] - every[3 * nb + ns:3 * nb + 2 * ns]
    k = outer_sum(np.array([ks for ks, _ in springs], float), d)
    c = outer_sum(np.array([cs for _, cs in springs], float), d)
    rows = every[3 * nb + 2 * ns:]  # (each wheel's and body's rows: views of ``every``, which nothing else holds)
    wheels = tuple(Wheel(nm, s, y, kt, ct, rows[w], fl) for w, (nm, s, y, kt, ct, fl) in enumerate(wheel_specs))
    body_rows = {b[0]: (b[2], h[i], p[i], r[i]) for i, b in enumerate(bodies)}
    return Vehicle(name, tuple(dofs), m, c, k, fg, wheels, description, dict(parameters or {}), bodies=body_rows)
