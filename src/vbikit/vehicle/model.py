"""Linear multibody vehicle models: M q̈ + C q̇ + K q = F_G + Σ_w r_wᵀ F_w (paper Eq. 2).

Conventions
-----------
* Generalised coordinates ``q`` are absolute displacements/rotations from the unstretched
  springs, z up, so gravity ``F_G`` is part of the load and the static state has q < 0.
* Longitudinal positions on the vehicle, ``s`` [m], are measured *rearward* from the front
  axle (the vehicle drives towards −s, i.e. in the bridge's +x direction).
* Pitch θ is positive nose-up, roll φ positive raising the left side (y > 0), so a point at
  (s, y) of a rigid body with centre of gravity at s_cg moves by z + (s_cg − s)·θ + y·φ.
* Tire springs are *not* in K: they are the contact with the road/deck and belong to the
  coupling (``vbikit.contact``).  Each [`Wheel`][vbikit.vehicle.Wheel] carries its tire's stiffness and
  damping and the row r_w with z_wheel = r_w · q.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

#: gravitational acceleration [m/s²]
GRAVITY = 9.81


@dataclass(frozen=True)
class Wheel:
    """One wheel (or one wheel line of a planar model) and its tire.

    Parameters
    ----------
    name : str
        Label used in outputs (``contact_force_<name>``).
    offset : float
        Distance s [m] of the wheel centre behind the front axle (≥ 0).
    lateral : float
        Transverse position y [m] relative to the vehicle centreline (positive left).
    stiffness, damping : float
        Tire spring [N/m] and dashpot [N·s/m] of the single-point model.
    row : ndarray
        z_wheel = row · q [m]; empty for a vehicle without DOFs (moving force).
    fixed_load : float
        Constant downward force [N] transmitted in addition to the tire spring; used by the
        moving-force model, zero otherwise.
    """

    name: str
    offset: float
    lateral: float
    stiffness: float
    damping: float
    row: NDArray[np.float64]
    fixed_load: float = 0.0


@dataclass(frozen=True)
class Vehicle:
    """A linear vehicle model with its wheels.

    Parameters
    ----------
    name : str
        The model's name.
    dof_names : tuple of str
        Name of each degree of freedom.
    mass, damping, stiffness : ndarray
        The (n_dof × n_dof) matrices without tires.
    gravity : ndarray
        The gravity load vector F_G [N, N·m].
    wheels : tuple of Wheel
        The wheels and their tires.
    description : str
        A one-line description.
    parameters : dict of str to float
        The parameters the model was built from.
    usual_speed_kmh : (float, float), optional
        Keyword only: the usual speed range of this kind of vehicle [km/h]; a speed outside it is
        warned of (``vbikit.analysis.checks``); None: that of road vehicles.
    railway : bool, optional
        Keyword only: a railway vehicle (the trains of ``vbikit.vehicle.trains``, ``TRAIN_PRESETS``,
        and the rail cars of ``vbikit.vehicle.rail_car`` set it): its run report shows the EN 1991-2
        dynamic factors instead of the highway codes' allowances (``vbikit.analysis.codes``).
    bodies : dict, optional
        Keyword only: the rigid bodies of a vehicle built by ``VehicleBuilder``, name ->
        (s_cg [m], heave, pitch, roll rows) (sensor positions, ``vbikit.driveby``).
    """

    name: str
    dof_names: tuple[str, ...]
    mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    gravity: NDArray[np.float64]
    wheels: tuple[Wheel, ...]
    description: str = ""
    parameters: dict[str, float] = field(default_factory=dict)
    #: rigid bodies of a built vehicle: name -> (s_cg [m], heave, pitch, roll rows); a point (s, y) of
    #: the body moves by (heave + (s_cg − s)·pitch + y·roll) · q (empty when not built by VehicleBuilder)
    bodies: dict = field(default_factory=dict, kw_only=True, repr=False, compare=False)
    usual_speed_kmh: "tuple[float, float] | None" = field(default=None, kw_only=True, repr=False, compare=False)
    railway: bool = field(default=False, kw_only=True, repr=False, compare=False)

    @property
    def n_dof(self) -> int:
        return len(self.dof_names)

    @property
    def length(self) -> float:
        """Distance from the front to the rearmost wheel [m]."""
        return max(w.offset for w in self.wheels)

    @property
    def total_weight(self) -> float:
        """Weight carried by the wheels [N]: −Σ F_G heave components plus fixed loads."""
        return float(sum(self.static_wheel_loads()))

    def tire_stiffness_matrix(self) -> NDArray[np.float64]:
        """Σ_w k_w r_w r_wᵀ: the tires as springs to a rigid, flat ground."""
        rows, k_w = self._wheel_rows()
        if not len(rows):
            return np.zeros((self.n_dof, self.n_dof))
        return (k_w[:, None, None] * (rows[:, :, None] * rows[:, None, :])).sum(axis=0)  # added wheel by wheel

    def tire_damping_matrix(self) -> NDArray[np.float64]:
        """Σ_w c_w r_w r_wᵀ: the tires as dashpots to a rigid, flat ground."""
        rows, _ = self._wheel_rows()
        if not len(rows):
            return np.zeros((self.n_dof, self.n_dof))
        c_w = np.array([w.damping for w in self.wheels], float)
        return (c_w[:, None, None] * (rows[:, :, None] * rows[:, None, :])).sum(axis=0)  # added wheel by wheel

    def _wheel_rows(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The wheels' rows r_w stacked (n_wheels, n_dof) and their tire stiffnesses k_w (kept: vehicles are immutable)."""
        kept = self.__dict__.get("_rows_and_stiffness")
        if kept is None:
            kept = (np.array([w.row for w in self.wheels], float).reshape(len(self.wheels), self.n_dof),
                    np.array([w.stiffness for w in self.wheels], float))
            object.__setattr__(self, "_rows_and_stiffness", kept)
        return kept

    def _grounded_stiffness(self) -> NDArray[np.float64]:
        """K̂ = K + Σ k_w r_w r_wᵀ, the stiffness on rigid ground (kept: vehicles are immutable; not to be written)."""
        kept = self.__dict__.get("_k_hat")
        if kept is None:
            kept = self.stiffness + self.tire_stiffness_matrix()
            object.__setattr__(self, "_k_hat", kept)
        return kept

    def stiffness_bound(self) -> float:
        """‖M⁻¹K̂‖∞ (K̂ = K + Σ k_w r_w r_wᵀ): a bound on ω_max² on rigid ground, no eigenvalue below any
        induced norm (``vbikit.solve.timestep``; kept: vehicles are immutable)."""
        kept = self.__dict__.get("_stiffness_bound")
        if kept is None:
            kept = float(np.abs(np.linalg.solve(self.mass, self._grounded_stiffness())).sum(axis=1).max()) \
                if self.n_dof else 0.0
            object.__setattr__(self, "_stiffness_bound", kept)
        return kept

    def static_state(self, ground: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Static displacement q_s [m, rad] with each wheel on rigid ground at elevation ``ground`` [m].

        Solves (K + Σ k_w r_w r_wᵀ) q = F_G + Σ k_w r_w g_w.
        """
        if self.n_dof == 0:
            return np.zeros(0)
        g = np.zeros(len(self.wheels)) if ground is None else np.asarray(ground, float)
        rows, k_w = self._wheel_rows()
        rhs = self.gravity + ((k_w[:, None] * rows) * g[:, None]).sum(axis=0)  # Σ_w k_w r_w g_w, wheel by wheel
        return np.linalg.solve(self._grounded_stiffness(), rhs)

    def static_wheel_loads(self) -> NDArray[np.float64]:
        """Static wheel loads [N] (positive = pressing down) on flat rigid ground, from equilibrium
        (solved once per vehicle: vehicles are immutable; a fresh copy each call)."""
        loads = self.__dict__.get("_static_wheel_loads")
        if loads is None:
            q = self.static_state()
            loads = np.array([w.fixed_load - w.stiffness * (w.row @ q if self.n_dof else 0.0) for w in self.wheels])
            object.__setattr__(self, "_static_wheel_loads", loads)
        return loads.copy()

    def natural_frequencies(self) -> NDArray[np.float64]:
        """Undamped natural frequencies [Hz] on rigid ground (tires as springs; solved once per
        vehicle: vehicles are immutable; a fresh copy each call)."""
        if self.n_dof == 0:
            return np.zeros(0)
        freqs = self.__dict__.get("_natural_frequencies")
        if freqs is None:
            from scipy.linalg import eigh

            lam = eigh(self._grounded_stiffness(), self.mass, eigvals_only=True)
            freqs = np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)
            object.__setattr__(self, "_natural_frequencies", freqs)
        return freqs.copy()

    def slowest_decay_rate(self, groups: NDArray[np.int64] | None = None) -> float:
        """σ_min [1/s]: how fast the slowest free vibration that the road can excite dies out, the vehicle on
        rigid, flat ground — the smallest −Re λ over the eigenvalues λ of its first-order form ż = A z,
        z = (q, q̇), A = [[0, I], [−M⁻¹K̂, −M⁻¹Ĉ]] with the tires as springs and dashpots to the ground
        (K̂ = K + Σ k_w r_w r_wᵀ, Ĉ = C + Σ c_w r_w r_wᵀ); exact for any damping, classical or not (e.g. Inman,
        *Engineering Vibration*, 4th ed., §4.10).  A mode of damping ratio ζ and frequency ω decays as exp(−ζω t):
        σ = ζω.

        Only the modes the road reaches count: ``groups`` (one per wheel) numbers the wheels the road moves
        together — the wheels of one axle on one road line see the same profile at the same time (``None``: each
        wheel on its own).  A mode that no group's input reaches, through its tires' springs or dashpots
        (|ψⱼᴴ b| ≤ 1e-9 ‖ψⱼ‖ ‖b‖ for every input b = (0, M⁻¹ Σ_w∈g k_w r_w) and (0, M⁻¹ Σ_w∈g c_w r_w), ψⱼ its
        left eigenvector), is at rest on a rough road as on a flat one (a body's roll when both wheel lines read
        the same profile): it has no start transient.  0 for an undamped mode the road reaches (|Re λ| ≤ 1e-9 |λ|,
        round-off); infinite when the road reaches no mode (a vehicle without DOFs, a moving force; tires without
        stiffness or damping): nothing to settle.  Kept per ``groups``: vehicles are immutable."""
        lam = self.slowest_mode(groups)
        if lam is None:
            return math.inf
        return -lam.real if -lam.real > 1e-9 * abs(lam) else 0.0  # (an undamped mode: Re λ at round-off, either sign)

    def slowest_mode(self, groups: NDArray[np.int64] | None = None) -> complex | None:
        """λ, the eigenvalue of the slowest decaying mode the road excites (``slowest_decay_rate`` is −Re λ;
        |λ| / 2π its undamped natural frequency [Hz] for an underdamped mode); None when there is none (no DOFs,
        or no mode the road reaches).  ``groups`` as for ``slowest_decay_rate``; kept per ``groups``."""
        n_w = len(self.wheels)
        groups = np.arange(n_w) if groups is None else np.asarray(groups, np.int64)
        if groups.shape != (n_w,):
            raise ValueError(f"groups: one group number per wheel ({n_w}), got shape {groups.shape}")
        store = self.__dict__.setdefault("_slowest_modes", {})  # (the instance's own dict: frozen)
        key = groups.tobytes()
        if key not in store:
            store[key] = self._slowest_mode(groups) if self.n_dof else None
        return store[key]

    def _slowest_mode(self, groups: NDArray[np.int64]) -> complex | None:
        """``slowest_mode`` computed (a vehicle with DOFs)."""
        from scipy.linalg import eig

        rows, k_w = self._wheel_rows()
        c_w = np.array([w.damping for w in self.wheels], float)
        c_hat = self.damping + self.tire_damping_matrix()
        n = self.n_dof
        member = (groups[:, None] == np.unique(groups)[None, :]).astype(float)  # (wheels, groups)
        forces = rows.T @ np.hstack([k_w[:, None] * member, c_w[:, None] * member])  # Σ_w∈g k_w r_w, Σ_w∈g c_w r_w
        forces = forces[:, np.any(forces != 0.0, axis=0)]
        if not forces.shape[1]:
            return None
        m_inv = np.linalg.solve(self.mass, np.hstack([self._grounded_stiffness(), c_hat, forces]))
        a = np.zeros((2 * n, 2 * n))
        a[:n, n:] = np.eye(n)
        a[n:, :n] = -m_inv[:, :n]
        a[n:, n:] = -m_inv[:, n:2 * n]
        b = np.vstack([np.zeros((n, forces.shape[1])), m_inv[:, 2 * n:]])  # the inputs (0, M⁻¹ f)
        lam, left = eig(a, left=True, right=False)  # columns ψⱼ: ψⱼᴴ A = λⱼ ψⱼᴴ
        reach = np.abs(left.conj().T @ b) / (np.linalg.norm(left, axis=0)[:, None] * np.linalg.norm(b, axis=0)[None, :])
        excited = np.flatnonzero(reach.max(axis=1) > 1e-9)
        return complex(lam[excited[np.argmax(lam.real[excited])]]) if excited.size else None


@dataclass(frozen=True)
class CombinedVehicle(Vehicle):
    """Several vehicles as one system: block-diagonal M, C, K, stacked F_G and wheels (each
    wheel's row padded with zeros outside its own vehicle's DOFs).  DOF and wheel names are
    prefixed ``v1_``, ``v2_``, … ; ``dof_offsets[i]`` / ``wheel_offsets[i]`` is the first DOF /
    wheel of vehicle i (a last entry holds the totals).  The vehicles do not interact: on
    rigid ground each keeps its own static state, loads and frequencies."""

    parts: tuple[Vehicle, ...] = ()
    dof_offsets: tuple[int, ...] = ()
    wheel_offsets: tuple[int, ...] = ()

    @property
    def _stacked(self) -> bool:
        """True when made by ``combine_vehicles`` from ``parts`` (not a copy with other matrices, e.g.
        ``dataclasses.replace``): its static state and wheel loads are then the parts' own."""
        return bool(self.__dict__.get("_from_parts", False))

    def static_state(self, ground: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Each vehicle's own static state (``Vehicle.static_state``, its wheels' part of
        ``ground``), stacked: the block-diagonal system decouples."""
        if not self._stacked:
            return super().static_state(ground)
        g = [None] * len(self.parts) if ground is None else \
            [np.asarray(ground, float)[a:b] for a, b in zip(self.wheel_offsets[:-1], self.wheel_offsets[1:])]
        try:
            return np.concatenate([p.static_state(gi) for p, gi in zip(self.parts, g)]) if self.n_dof else np.zeros(0)
        except np.linalg.LinAlgError:  # a part singular on its own (a mechanism): the whole system as given
            return super().static_state(ground)

    def stiffness_bound(self) -> float:
        """``Vehicle.stiffness_bound``: the largest of the vehicles' own (kept with each: M and K̂ are
        block-diagonal, so every row of M⁻¹K̂ is a row of one vehicle's own)."""
        if not self._stacked or not self.parts:
            return super().stiffness_bound()
        return max(p.stiffness_bound() for p in self.parts)

    def static_wheel_loads(self) -> NDArray[np.float64]:
        """Each vehicle's own static wheel loads (kept per vehicle), stacked (a fresh array)."""
        if not self._stacked:
            return super().static_wheel_loads()
        try:
            return np.concatenate([p.static_wheel_loads() for p in self.parts])
        except np.linalg.LinAlgError:  # a part singular on its own (a mechanism): the whole system as given
            return super().static_wheel_loads()

def combine_vehicles(vehicles: "tuple[Vehicle, ...] | list[Vehicle]") -> CombinedVehicle:
    """Stack ``vehicles`` into one ``CombinedVehicle`` (see there)."""
    vehicles = tuple(vehicles)
    if not vehicles:
        raise ValueError("combine_vehicles needs at least one vehicle")
    dof_off, wheel_off = [0], [0]
    for v in vehicles:
        dof_off.append(dof_off[-1] + v.n_dof)
        wheel_off.append(wheel_off[-1] + len(v.wheels))
    n = dof_off[-1]

    def blocks(attr: str) -> NDArray[np.float64]:
        out = np.zeros((n, n))
        for i, v in enumerate(vehicles):
            out[dof_off[i]:dof_off[i + 1], dof_off[i]:dof_off[i + 1]] = getattr(v, attr)
        return out

    wheels = []
    names: list[str] = []
    for i, v in enumerate(vehicles):
        names += [f"v{i + 1}_{d}" for d in v.dof_names]
        rows = np.zeros((len(v.wheels), n))
        rows[:, dof_off[i]:dof_off[i + 1]] = v._wheel_rows()[0]
        for w, row in zip(v.wheels, rows):
            wheels.append(Wheel(f"v{i + 1}_{w.name}", w.offset, w.lateral, w.stiffness, w.damping, row, w.fixed_load))
    gravity = np.concatenate([v.gravity for v in vehicles]) if n else np.zeros(0)
    combined = CombinedVehicle(
        "+".join(v.name for v in vehicles), tuple(names), blocks("mass"), blocks("damping"), blocks("stiffness"),
        gravity, tuple(wheels), f"{len(vehicles)} vehicles: " + ", ".join(v.name for v in vehicles), {},
        vehicles, tuple(dof_off), tuple(wheel_off), railway=any(v.railway for v in vehicles))
    object.__setattr__(combined, "_from_parts", True)  # its blocks are the parts' own (``CombinedVehicle._stacked``)
    return combined
