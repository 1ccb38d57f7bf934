"""Resource budgets: memory and time steps of a run estimated before it starts, and refused above
limits the user can raise (``vbikit run --max-memory 8GiB --max-steps 2e7``).

The estimates count what the solver and the reports hold at once, 8 bytes a number:

* road profiles: the random profile's DFT grid (N = next power of two ≥ max(length, 1/n_min)/Δx)
  as complex coefficients, phases and the real profile (≈ 40 bytes a sample);
* the bridge model: a slab-on-girder grillage (3 DOFs a node, n_girders × (n_elements + 1) nodes)
  solved by a sparse shift-invert eigensolver, limited to ``MAX_BRIDGE_DOF`` (60 000 DOFs,
  Bridge 2 with 4000 elements, take 3 s);
* histories: per lane and time point the bridge modal coordinates and rates (3 n_modes), the vehicle
  coordinates and rates (3 n_dof), wheel forces and patch lengths (2 n_wheels), and for the
  reports the static modal history and the response columns (n_modes + 48).

``check_run`` raises ``BudgetError`` (a ``ValueError``) naming the inputs that drive the
estimate.  The step limit stands for run time: at the default 5 × 10⁶ steps a single crossing of
the paper's 3D bridge with 20 modes takes minutes.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

from vbikit.bridge.base import GirderDeck
from vbikit.errors import VbikitError
from vbikit.solve.crossing import Crossing

GIB = 1024**3
#: default memory limit [bytes] of one run
DEFAULT_MAX_MEMORY = 4 * GIB
#: default limit on the time steps of one crossing
DEFAULT_MAX_STEPS = 5_000_000
#: limit on the degrees of freedom of a grillage solved for its modes (sparse eigensolver)
MAX_BRIDGE_DOF = 60_000
#: contact points per step the step limit allows on average: the work of a step grows with the
#: points (a deformable disk has hundreds per wheel), so ``n_steps × n_points`` is limited to
#: ``POINTS_PER_STEP × max_steps``
POINTS_PER_STEP = 200
#: bytes per road-profile sample while a random profile is generated
_ROAD_BYTES = 40
#: sizes of a run's inputs allowed at the default step limit, checked before anything is built (the
#: work of building and checking a model grows with them, like the work of its steps); a raised
#: ``--max-steps`` raises them in proportion (``size_budget``), a lowered one keeps them
MAX_AXLES = 50
#: vehicles in one crossing (one [[vehicles]] event)
MAX_VEHICLES = 50
#: spans of a continuous beam
MAX_SPANS = 20
#: Hermite elements of a continuous beam (all spans)
MAX_BEAM_ELEMENTS = 4000
#: load effects × beam elements (each load effect of a continuous beam integrates over every element)
MAX_EFFECT_ELEMENTS = 100_000


class BudgetError(VbikitError):
    """A run whose estimated memory or step count is above the limit; the message names the inputs."""


@dataclass(frozen=True)
class Limits:
    """Budget of one run: ``max_memory`` [bytes], ``max_steps`` [-]."""

    max_memory: float = DEFAULT_MAX_MEMORY
    max_steps: int = DEFAULT_MAX_STEPS


def parse_size(text: str) -> float:
    """Bytes from ``"4GiB"``, ``"500MB"``, ``"2e9"`` (B, kB, MB, GB, TB, KiB, MiB, GiB, TiB)."""
    m = re.fullmatch(r"\s*([0-9]*\.?[0-9]+(?:[eE][+-]?[0-9]+)?)\s*([kKMGT]?i?B)?\s*", text)
    if not m:
        raise ValueError(f"--max-memory: {text!r} is not a size such as 4GiB, 500MB or 2e9")
    unit = m[2] or "B"
    scale = {"B": 1, "kB": 1e3, "KB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12,
             "KiB": 1024, "kiB": 1024, "MiB": 1024**2, "GiB": GIB, "TiB": 1024**4}.get(unit)
    if scale is None:
        raise ValueError(f"--max-memory: unknown unit {unit!r}; use B, kB, MB, GB, TB, KiB, MiB, GiB or TiB")
    value = float(m[1]) * scale
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"--max-memory must be > 0, got {text!r}")
    return value


def human(n_bytes: float) -> str:
    """``n_bytes`` as a short text (``"26.7 GiB"``)."""
    for unit, scale in (("TiB", 1024**4), ("GiB", GIB), ("MiB", 1024**2), ("KiB", 1024)):
        if n_bytes >= scale:
            return f"{n_bytes / scale:.1f} {unit}"
    return f"{n_bytes:.0f} B"


def road_samples(length: float, spacing: float, n_min: float) -> int:
    """Samples of a random profile (the DFT grid of [`vbikit.road.psd.random_profile`][vbikit.road.random_profile])."""
    return 1 << max(0, math.ceil(math.log2(max(length, 1.0 / n_min) / spacing)))


def check_road(length: float, spacing: float, n_min: float, limits: Limits | None = None, what: str = "road") -> None:
    """Refuse a random profile whose generation would need more than ``limits.max_memory``."""
    limits = limits or Limits()
    n = road_samples(length, spacing, n_min)
    need = n * _ROAD_BYTES
    if need > limits.max_memory:
        raise BudgetError(
            f"{what}: a random profile of max(length = {length:g} m, 1/n_min = {1 / n_min:g} m) at spacing = "
            f"{spacing:g} m has {n:.3g} samples and needs ≈ {human(need)}, above the memory limit "
            f"{human(limits.max_memory)}; use a larger road.spacing, a shorter road.length, or raise --max-memory")


def size_budget(base: int, limits: Limits | None = None) -> int:
    """A size budget ``base`` (one of ``MAX_AXLES`` … ``MAX_EFFECT_ELEMENTS``) under ``limits``:
    ``base`` at the default step limit or below, in proportion above it."""
    limits = limits or Limits()
    return int(base * max(1.0, limits.max_steps / DEFAULT_MAX_STEPS))


def check_size(what: str, count: int, base: int, limits: Limits | None = None, advice: str = "") -> None:
    """Refuse ``count`` of ``what`` above ``size_budget(base, limits)``; the message names the
    budget, the ``--max-steps`` that would allow it, and ``advice`` (the inputs to change)."""
    allowed = size_budget(base, limits)
    if count > allowed:
        need = math.ceil(count / base * DEFAULT_MAX_STEPS)
        raise BudgetError(
            f"{what}: {count} is above the budget of {allowed} (checked before the model is built; the size budgets "
            f"grow with --max-steps above its default {DEFAULT_MAX_STEPS:.3g}): raise --max-steps to {need:.3g} or "
            f"more{f', or {advice}' if advice else ''}")


def check_bridge(bridge: object, limits: Limits | None = None) -> None:
    """Refuse a bridge model too large to solve for its modes (slab-on-girder grillages)."""
    limits = limits or Limits()
    n_elements = getattr(bridge, "element_count", None)  # grillage models: their mesh
    if n_elements is None or not isinstance(bridge, GirderDeck):
        return
    n_girders = bridge.n_girders
    dof = 3 * int(n_girders) * (int(n_elements) + 1)
    if dof > MAX_BRIDGE_DOF:
        raise BudgetError(
            f"bridge.deck: {n_girders} girders × {n_elements} elements give a grillage of {dof:.3g} degrees of "
            f"freedom; at most {MAX_BRIDGE_DOF} are solved: use fewer bridge.deck.n_elements (default: elements "
            "of 0.5 m) or fewer girders")


@dataclass(frozen=True)
class RunEstimate:
    """Steps, time points and memory [bytes] of a run of ``lanes`` crossings with step ``dt`` [s]."""

    dt: float
    n_steps: int
    memory: float
    lanes: int = 1
    n_points: int = 1


def estimate_run(crossing: Crossing, dt: float, lanes: int = 1) -> RunEstimate:
    """Steps and memory of ``lanes`` crossings like ``crossing`` at step ``dt`` [s] (module docstring)."""
    ratio = crossing.duration / dt if dt > 0 else math.inf
    n_steps = max(1, math.ceil(ratio - 1e-9)) if math.isfinite(ratio) and ratio < 1e18 else 10**18
    n_t = n_steps + 1
    n_m = int(crossing.bridge.omega.size)
    n_d = int(crossing.vehicle.n_dof)
    n_w = len(crossing.vehicle.wheels)
    per_point = lanes * (3 * n_m + 3 * n_d + 2 * n_w) + n_m + 48 + 3 * 2
    return RunEstimate(float(dt), int(n_steps), 8.0 * n_t * per_point, lanes, int(crossing.contact.n))


def check_run(crossing: Crossing, dt: float, limits: Limits | None = None, lanes: int = 1) -> RunEstimate:
    """The run's ``RunEstimate``, or ``BudgetError`` if it is above ``limits``."""
    limits = limits or Limits()
    est = estimate_run(crossing, dt, lanes)

    def drivers() -> str:  # (the inputs that set the run's size, for the messages: written only for one)
        return (f"a crossing of {crossing.duration:.4g} s (crossing.speed {crossing.speed:.4g} m/s = "
                f"{crossing.speed * 3.6:.4g} km/h, crossing.approach {crossing.approach:g} m, span {crossing.bridge.span:g} m, "
                f"crossing.free_vibration {crossing.free_vibration_time:.3g} s) at crossing.dt = {dt:.3g} s "
                f"({crossing.integrator}; bridge.n_modes = {crossing.bridge.omega.size}, highest mode "
                f"{crossing.bridge.frequencies_hz.max():.4g} Hz)")

    if est.n_steps > limits.max_steps:
        raise BudgetError(f"this run needs {est.n_steps:.3g} time steps, above the limit {limits.max_steps:.3g}: "
                          f"{drivers()}; raise --max-steps, or change those inputs")
    if est.n_steps * est.n_points > POINTS_PER_STEP * limits.max_steps:
        raise BudgetError(f"this run needs {est.n_steps:.3g} time steps × {est.n_points} contact points, above the limit "
                          f"{POINTS_PER_STEP} × {limits.max_steps:.3g} (--max-steps): the tire model has many points "
                          f"(tire.model = {crossing.tire.name!r}; a disk has one per tire.disk_spacing along its rim); "
                          f"{drivers()}; raise --max-steps, or use a coarser tire.disk_spacing")
    if est.memory > limits.max_memory:
        raise BudgetError(f"this run needs ≈ {human(est.memory)} of memory, above the limit {human(limits.max_memory)}: "
                          f"{est.n_steps} steps × {crossing.bridge.omega.size} modes × {lanes} lane(s); {drivers()}; raise --max-memory, "
                          "or use fewer bridge modes / a shorter crossing")
    return est
