"""Time histories of one crossing and the responses derived from them."""
from __future__ import annotations

import math
import threading
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import Kept
from vbikit.bridge.base import GirderDeck
from vbikit.errors import VbikitError
from vbikit.outputs import CF_UNITS, QUANTITIES, cf_unit, member_units
from vbikit.solve.crossing import Crossing

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    import xarray as xr

    from vbikit.solve.kernels import Vehicles


_add = np.add.reduce
#: read-out points whose mode shapes a crossing keeps (``CrossingResult.displacement`` and its kin)
KEPT_SHAPES = 32


class DivergenceError(VbikitError):
    """An integration whose states became non-finite; the message gives the step and time."""


def check_finite(result: "CrossingResult", fresh: bool = False) -> "CrossingResult":
    """``result`` if every state history is finite, else ``DivergenceError`` naming the
    first step (and its time) with a non-finite bridge, vehicle or tire value.  ``fresh``: the
    result comes straight from its run, unchanged (``vbikit.solve.simulate``): a deferred q̈'s
    ``fingerprint``, the sums of q, q̇ and the wheel forces at the run's end, stands for theirs."""
    # (q̈ is not read: it follows from q, q̇ and the wheel forces, and may not be computed yet)
    arrays = (result.xi, result.xi_dot, result.xi_ddot, result.q, result.q_dot, result.wheel_forces)
    deferred = result.__dict__.get("_q_ddot") if fresh else None
    known = deferred.fingerprint if isinstance(deferred, DeferredAccelerations) and deferred.q is result.q \
        and deferred.q_dot is result.q_dot and deferred.wheel_force is result.wheel_forces else None
    total = 0.0
    with np.errstate(over="ignore", invalid="ignore"):  # a sum that overflows only takes the step-by-step path
        for a in arrays[:3] if known is not None else arrays:
            total += _add(a, None)
        if known is not None:
            total += _add(known, None)
    if math.isfinite(total):  # NaN and inf propagate into the sums: all finite
        return result
    ok = np.ones(result.time.size, bool)
    for a in arrays:
        if a.size:
            ok &= np.isfinite(a).reshape(a.shape[0], -1).all(axis=1)
    if not ok.all():
        from vbikit.solve.integrators import implicit_names

        i = int(np.argmin(ok))
        c = result.crossing
        front = np.atleast_1d(np.asarray(result.front_position[i], float))
        where = f"front axle at x = {float(front[0]):.3f} m" if front.size == 1 else \
            "front axles at " + ", ".join(f"x = {float(x):.3f} m (vehicle {k})" for k, x in enumerate(front, start=1))
        raise DivergenceError(
            f"the integration diverged at step {i} of {result.n_steps} (t = {result.time[i]:.6g} s, {where}): "
            f"non-finite states with {c.integrator} at dt = {result.dt:.3g} s; "
            "use a smaller crossing.dt (or leave it out), fewer bridge modes, or "
            + " or ".join(f'integrator = "{name}"' for name in implicit_names() if name != c.integrator))
    return result


#: doubles in the work space of ``vehicle_accelerations`` (under the 128 KiB above which the C library
#: maps fresh pages for an allocation: a fresh array costs its page faults, more than the products)
ACCELERATION_CHUNK = 16000


def vehicle_accelerations(vehicles: "Vehicles", q: NDArray[np.float64], q_dot: NDArray[np.float64],
                          wheel_force: NDArray[np.float64], out: NDArray[np.float64]) -> NDArray[np.float64]:
    """The vehicles' accelerations q̈ = M⁻¹(F_G + Hᵀ F_w − C q̇ − K q) into ``out`` at every stored row of
    the histories ``q``, ``q_dot`` (…, n_t, n_d) and the wheel forces ``wheel_force`` F_w (…, n_t, n_w)
    (any leading lane axes; each C-contiguous): the vehicles' equation of motion with the tire forces
    as loads (C, K the vehicles' own matrices, without the tires: the implicit step's
    M⁻¹(F_G + Hᵀ G − Ĉ q̇ − K̂ q) with G = F_w + k_w h_w·q + c_w h_w·q̇ and K̂ = K + Σ k_w h_wᵀh_w, Ĉ
    likewise, is the same).  Matrix products over blocks of rows after the run, in place of one
    product a step in the lean kernels' loops."""
    arrays = (q, q_dot, wheel_force, out)
    if not all(a.flags.c_contiguous for a in arrays):
        raise ValueError("vehicle_accelerations: the histories must be C-contiguous")
    if out.size == 0:  # no vehicle DOFs (moving forces) or no rows
        return out
    n_rows = out.size // out.shape[-1]
    q2, v2, f2, o2 = (a.reshape(n_rows, a.shape[-1]) for a in arrays)  # views (contiguous; F_w may have no wheels)
    m_inv = vehicles.mass_inv
    by_q, by_v = (m_inv @ -vehicles.stiffness).T, (m_inv @ -vehicles.damping).T
    by_f, constant = (m_inv @ vehicles.wheel_rows.T).T, m_inv @ vehicles.gravity
    n_d = o2.shape[1]
    chunk = max(1, ACCELERATION_CHUNK // max(n_d, 1))
    part = np.empty((min(chunk, n_rows), n_d))
    for lo in range(0, n_rows, chunk):
        hi = min(lo + chunk, n_rows)
        o, p = o2[lo:hi], part[:hi - lo]
        np.matmul(q2[lo:hi], by_q, out=o)
        np.matmul(v2[lo:hi], by_v, out=p)
        o += p
        np.matmul(f2[lo:hi], by_f, out=p)
        o += p
        o += constant
    return out


class ChangedHistoryError(VbikitError):
    """q̈ asked of a result whose q, q̇ or wheel forces were changed in place after the run."""


def _fingerprint(*arrays: NDArray[np.float64]) -> NDArray[np.float64]:
    """The sum of each array (a cheap check that none was changed in place: a change of units, an
    offset or added noise changes its sum)."""
    return np.array([_add(a, None) if a.size else 0.0 for a in arrays])


@dataclass(frozen=True)
class DeferredAccelerations:
    """The vehicles' accelerations of one stored history, computed when first read
    (``vehicle_accelerations`` of these arrays into ``out``): an integrator that leaves q̈ out of
    its step loop (the lean kernels, ``vbikit.solve.integrators.run_implicit``) hands these to its
    results, and runs that never read q̈ (traffic, lifetime and study reductions) never pay for it.

    q̈ follows from the result's own q, q̇ and wheel forces (the same arrays), so it is computed only
    if they still hold what the run stored (``fingerprint``, their sums at the run's end): a result
    whose histories were changed in place before q̈ was read raises ``ChangedHistoryError`` instead
    of giving accelerations of the changed values."""

    vehicles: Any
    q: NDArray[np.float64]
    q_dot: NDArray[np.float64]
    wheel_force: NDArray[np.float64]
    out: NDArray[np.float64]
    fingerprint: NDArray[np.float64] | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        if self.fingerprint is None:
            object.__setattr__(self, "fingerprint", _fingerprint(self.q, self.q_dot, self.wheel_force))

    def __call__(self) -> NDArray[np.float64]:
        if not np.array_equal(_fingerprint(self.q, self.q_dot, self.wheel_force), self.fingerprint, equal_nan=True):
            raise ChangedHistoryError(
                "q_ddot follows from the result's q, q_dot and wheel_forces, and one of them was changed in place "
                "after the run: read q_ddot before changing them, or change copies (numpy's .copy())")
        return vehicle_accelerations(self.vehicles, self.q, self.q_dot, self.wheel_force, self.out)


#: one computation of a deferred q̈ at a time (two threads reading one result would write into the same
#: array: numpy's products release the GIL)
_DEFERRED_LOCK = threading.Lock()


class _Deferred:
    """A field of a frozen dataclass that may be given a ``DeferredAccelerations``: computed on the
    first read and kept (a data descriptor, so the dataclass's ``__init__`` stores through
    ``__set__``; no default), under a lock: threads reading one result compute it once.  The value lives under the field's name with a leading underscore; a
    state with the plain name (a result pickled before the field was deferred) is read too."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.key = "_" + name

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        if obj is None:
            raise AttributeError(self.key[1:])  # (the dataclass then gives the field no default)
        state = obj.__dict__
        value = state[self.key] if self.key in state else state[self.key[1:]]
        if isinstance(value, DeferredAccelerations):
            with _DEFERRED_LOCK:
                value = state[self.key]  # (another thread may have computed it meanwhile)
                if isinstance(value, DeferredAccelerations):
                    value = value()
                    state[self.key] = value
        return value

    def __set__(self, obj: Any, value: Any) -> None:
        obj.__dict__[self.key] = value


def check_on_deck(bridge: Any, x: float, y: float) -> None:
    """ValueError unless (x, y) [m] is a point of the deck: both finite and x within the span along its line (a skew
    deck's span coordinate) — the one check of every reader of a point's response (``CrossingResult.point``,
    ``vbikit.analysis.point_response``): off the span the mode shapes are zero, and a response there read as zeros."""
    if not (math.isfinite(x) and math.isfinite(y) and 0.0 <= float(bridge.span_coordinate(x, y)) <= bridge.span):
        raise ValueError(f"response.x must be within the span 0 … {bridge.span} m and response.y finite, got ({x}, {y})")


@dataclass(frozen=True)
class CrossingResult:
    """Histories at the n_t = n_steps + 1 time points ``time`` [s].

    Parameters
    ----------
    crossing : Crossing
        The crossing that was integrated.
    time : ndarray
        The stored time points [s], (n_t,).
    dt : float
        Spacing [s] of the stored time points.
    front_position, speed : ndarray
        (n_t, n_vehicles): x [m] of each vehicle's front axle and its speed [m/s].
    xi, xi_dot, xi_ddot : ndarray
        (n_t, n_modes): bridge modal coordinates and rates.
    q, q_dot, q_ddot : ndarray
        (n_t, n_dof): vehicle coordinates (absolute, z up) and rates (``q_ddot`` may be given as
        ``DeferredAccelerations``: computed from q, q̇ and the wheel forces when first read).
    wheel_forces : ndarray
        (n_t, n_wheels): tire forces [N], compression positive (0 = no contact).
    contact_lengths : ndarray
        (n_t, n_wheels): length [m] of the patch in contact (0 for point tires).
    integration_dt : float, optional
        The integrator's step [s] (smaller than ``dt`` when the histories were thinned,
        ``simulate(..., output_every=k)``).
    kernel_data : KernelData, optional
        The tabulated arrays the run used (mode-shape tables along the wheel tracks), kept so that
        the static reference is read from the same tables without tabulating them again.  Shared
        with the crossing (``Crossing.kept``) and its later runs: not to be written to (kept
        writeable only because numba compiles a separate kernel for read-only arrays).
    unconverged_steps : int
        Integration steps of an implicit integrator whose end-of-step contact forces did not settle
        to their tolerance within the iteration limit (``vbikit.solve.integrators.IMPLICIT_TOLERANCE``,
        ``IMPLICIT_MAX_ITERATIONS``); the run goes on with the last iterate, so the states after such a
        step carry a force error above the tolerance.  0 for a sound run (and for RK4, which does
        not iterate); a crossing run as one lane of a rigid-disk batch counts the steps where any
        lane of its kernel call did not settle.  Flagged (``contact_not_converged``).
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
    q_ddot: NDArray[np.float64] = _Deferred()  # type: ignore[assignment]  (an array, or computed when read)
    wheel_forces: NDArray[np.float64]
    contact_lengths: NDArray[np.float64]
    integration_dt: float | None = None
    kernel_data: Any = field(default=None, repr=False, compare=False)
    unconverged_steps: int = 0

    @property
    def travel(self) -> NDArray[np.float64]:
        """The vehicles' travel s_v [m] past their entry supports at ``time``, (n_t, n_vehicles)
        (computed once, or given by the run, ``keep_travel``: a result is immutable; a fresh copy each
        access)."""
        known = self.__dict__.get("_travel")
        if known is None:
            known = self.crossing.travel(self.time)
            object.__setattr__(self, "_travel", known)
        return known.copy()

    def shared_travel(self) -> NDArray[np.float64]:
        """``travel`` without its copy: the result's own array, for the reductions that only read it (a
        traffic event reads it three times) — not to be written."""
        known = self.__dict__.get("_travel")
        if known is None:
            self.travel  # noqa: B018 - computes and keeps it
            known = self.__dict__["_travel"]
        return known

    def keep_travel(self, travel: NDArray[np.float64]) -> None:
        """Keep ``travel``, the crossing's ``Crossing.travel`` at ``time`` that the run has already (its time
        grid's rows: the same numbers, ``travel`` is elementwise in t), as the result's ``travel``
        (not to be written to)."""
        object.__setattr__(self, "_travel", travel)

    def wheel_positions(self) -> NDArray[np.float64]:
        """x [m] of every wheel centre at every time (n_t, n_wheels), each vehicle on its own path."""
        crossing = self.crossing
        offsets = np.array([w.offset for w in crossing.vehicle.wheels])
        veh = np.repeat(np.arange(crossing.n_vehicles), [len(m.vehicle.wheels) for m in crossing.vehicles])
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
        y = float(b.default_response_y) if y is None else float(y)
        if x is None:  # a skew deck's default section depends on the line (oblique supports)
            x = b.default_x_at(y)
        check_on_deck(b, float(x), y)  # (a point off the span read zeros: its mode shapes are 0 there)
        return float(x), y

    def girder_sections(self, x: float | None = None, y: float | None = None) -> list[float]:
        """x [m] on every girder line (Girder 1 first) of the section through the point (x, y) (y
        default the response line; x default: each girder's own default section, the middle of its
        first span): the same x on a square deck, the same distance ξ = x − y tan θ from the
        support line on a skew deck."""
        b = self.crossing.bridge
        ys = [float(g) for g in b.girder_y] if isinstance(b, GirderDeck) else []
        if x is None:
            return [float(b.default_x_at(g)) for g in ys]
        y0 = float(b.default_response_y) if y is None else float(y)
        xi = float(b.span_coordinate(x, y0))
        return [float(x) + (xi - float(b.span_coordinate(x, g))) for g in ys]

    def _shapes(self, x: float | None, y: float | None) -> NDArray[np.float64]:
        """φ_m(x, y) of every mode at the deck point (kept with the crossing, the last ``KEPT_SHAPES``
        points in one entry of its store: its bridge is immutable)."""
        c, point = self.crossing, self.point(x, y)
        shapes = c.kept("shapes", None, lambda: Kept(KEPT_SHAPES))
        return shapes.get(point, lambda: c.bridge.mode_shapes(*([v] for v in point))[0])

    def displacement(self, x: float | None = None, y: float | None = None) -> NDArray[np.float64]:
        """Deck vertical displacement [m] at (x, y) (z up: negative under load); defaults: [`point`][vbikit.solve.CrossingResult.point]."""
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

    # ------------------------------------------------------------------ labelled results
    def to_xarray(self, points: Sequence[tuple[float, float]] | None = None, girder_x: float | None = None,
                  static: bool = True, names: Sequence[str] | None = None, effects: Sequence[Any] = ()) -> "xr.Dataset":
        """The crossing as a labelled ``xarray.Dataset`` with units.

        Parameters
        ----------
        points : sequence of (x, y), optional
            Deck points [m] (x from the entry support, y from the deck centreline); default
            [`point`][vbikit.solve.CrossingResult.point] (midspan on the bridge's response line).  Responses there have the dimensions (time, point).
        girder_x : float, optional
            Section x [m] (on the response line) of the per-girder responses (dimension ``girder``,
            Girder 1 first) on a bridge with girders: [`girder_sections`][vbikit.solve.CrossingResult.girder_sections].  Ignored for bridges
            without girders.
        static : bool
            Also the static reference responses (``static_displacement``, ``static_strain``).
        names : sequence of str, optional
            The points' names (coordinate ``point``), as in the CSV headers; default ``p1``, ``p2``, ….
        effects : sequence of LoadEffectResponse, optional
            Load-effect responses (``vbikit.analysis.load_effect_response``):
            each one's ``dynamic`` history as variable ``<name>`` and its ``static`` one as ``<name>_static``
            (the CSV's moment / shear / reaction columns), in the effect's unit.

        Returns
        -------
        xarray.Dataset
            Coordinate ``time`` [s]; variables with ``units`` and ``long_name`` attributes:
            deck ``displacement`` [m], ``velocity`` [m/s], ``acceleration`` [m/s^2], ``strain``
            [-] (tension positive) per point and, with girders, ``girder_*`` per girder;
            ``contact_force`` [N] and ``contact_length`` [m] per wheel; ``vehicle_displacement``
            and ``vehicle_acceleration`` per vehicle DOF (m for heave, rad for pitch and roll: their one
            ``units``, or, where they mix, ``units_by_dof`` naming the coordinate of each DOF's unit,
            ``dof_units`` or ``dof_acceleration_units``; ``vehicle_dof_units``); ``modal_displacement`` per mode;
            ``front_axle_x`` [m] and ``speed`` [m/s]; ``<effect>`` and ``<effect>_static`` of every
            load effect in ``effects``.  Names and units are those of the CSV (``vbikit.outputs``).
            Sign conventions in the dataset's attributes.
        """
        import xarray as xr

        from vbikit.solve.system import static_modal_history

        bridge = self.crossing.bridge
        vehicle = self.crossing.vehicle
        pts = [self.point()] if points is None else [self.point(float(x), float(y)) for x, y in points]  # (checked)
        labels = [f"p{i}" for i in range(1, len(pts) + 1)] if names is None else [str(n) for n in names]
        if len(labels) != len(pts):
            raise ValueError(f"names: {len(labels)} names for {len(pts)} points")
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        xi_st = static_modal_history(self.crossing, self.travel, self.kernel_data) if static else None
        data: dict[str, tuple[tuple[str, ...], Any, dict[str, str]]] = {}

        def deck(prefix: str, dim: str, px: list[float], py: list[float], label: str) -> None:
            phi = np.stack([bridge.mode_shapes([x], [y])[0] for x, y in zip(px, py)], axis=1)
            eps = np.stack([bridge.strain_shapes([x], [y])[0] for x, y in zip(px, py)], axis=1)
            rows = [("displacement", self.xi @ phi), ("velocity", self.xi_dot @ phi),
                    ("acceleration", self.xi_ddot @ phi), ("strain", self.xi @ eps)]
            if xi_st is not None:
                rows += [("static_displacement", xi_st @ phi), ("static_strain", xi_st @ eps)]
            for name, values in rows:
                q = QUANTITIES[name]
                data[prefix + name] = (("time", dim), values, {"units": cf_unit(q.unit), "long_name": f"{q.long_name}{label}"})

        deck("", "point", xs, ys, "")
        girder_y = bridge.girder_y if isinstance(bridge, GirderDeck) else None
        coords: dict[str, Any] = {
            **deck_point_coords(self.time, labels, xs, ys),
            "wheel": ("wheel", [w.name for w in vehicle.wheels]),
            **vehicle_dof_coords(vehicle.dof_names),
            "mode": ("mode", np.arange(1, bridge.frequencies_hz.size + 1)),
            "frequency": ("mode", np.asarray(bridge.frequencies_hz), {"units": "Hz", "long_name": "natural frequency"}),
        }
        if girder_y is not None:
            gy = [float(y) for y in girder_y]
            deck("girder_", "girder", self.girder_sections(girder_x), gy,
                 " on the girder line at its default section" if girder_x is None else
                 f" on the girder line at the section of x = {float(girder_x):g} m")
            coords["girder"] = ("girder", np.arange(1, len(girder_y) + 1))
            coords["girder_y"] = ("girder", np.asarray(girder_y, float), {"units": "m", "long_name": "girder line from the deck centreline"})
        if self.crossing.single:  # one vehicle (built with vehicle=): plain time series
            motion, front, speed = ("time",), self.front_position[:, 0], self.speed[:, 0]
        else:  # one column per vehicle
            motion, front, speed = ("time", "vehicle"), self.front_position, self.speed
            coords["vehicle"] = ("vehicle", np.arange(1, self.front_position.shape[1] + 1))
        data["front_axle_x"] = (motion, front, {"units": "m", "long_name": "front axle position from the entry support"})
        data["speed"] = (motion, speed, {"units": "m s-1", "long_name": "vehicle speed"})
        data["contact_force"] = (("time", "wheel"), self.wheel_forces, {"units": "N", "long_name": "tire force, compression positive"})
        data["contact_length"] = (("time", "wheel"), self.contact_lengths, {"units": "m", "long_name": "length of the tire patch in contact"})
        data["vehicle_displacement"] = (("time", "dof"), self.q, {**vehicle_dof_units(vehicle.dof_names),
                                                                  "long_name": "vehicle DOF, absolute, z up"})
        data["vehicle_acceleration"] = (("time", "dof"), self.q_ddot, {**vehicle_dof_units(vehicle.dof_names, True),
                                                                        "long_name": "vehicle DOF acceleration"})
        data["modal_displacement"] = (("time", "mode"), self.xi, {"units": "kg^0.5 m", "long_name": "bridge modal coordinate (mass-normalised modes)"})
        for e in effects:  # duck-typed LoadEffectResponse (the solver does not import analysis)
            what = f"{e.effect.kind} at x = {e.effect.x:g} m" if hasattr(e.effect, "x") else e.name
            data[e.name] = (("time",), np.asarray(e.dynamic), {"units": cf_unit(e.effect.units), "long_name": f"{what}, dynamic"})
            data[f"{e.name}_static"] = (("time",), np.asarray(e.static), {"units": cf_unit(e.effect.units),
                                                                          "long_name": f"{what}, static reference"})
        attrs = {
            "title": "vbikit crossing",
            "conventions": "SI units; x along the bridge from the entry support, y from the deck centreline "
                           "(positive left), z up: deflection under load is negative; strain positive in tension",
            "dt": self.dt,
            "integrator": self.crossing.integrator,
            "tire_model": self.crossing.tire.name,
            "vehicle": getattr(vehicle, "description", ""),
            "bridge": bridge.name or type(bridge).__name__,
        }
        return xr.Dataset({k: xr.Variable(*v) for k, v in data.items()}, coords=coords, attrs=attrs)

    def to_dataframe(self, points: Sequence[tuple[float, float]] | None = None, girder_x: float | None = None,
                     static: bool = True, names: Sequence[str] | None = None, effects: Sequence[Any] = ()) -> "pd.DataFrame":
        """The histories as a wide ``pandas.DataFrame``, index ``time [s]``, one column per
        quantity, point, girder, wheel and DOF, each header naming its unit with the CSV's names
        (``displacement [m]``; more than one point: ``displacement_<name> [m]``; ``girder3_strain [-]``,
        ``contact_force_axle1_left [N]``, ``tractor_pitch [rad]``, ``v2_front_axle_x [m]``, ``M_mid [N m]``
        and ``M_mid_static [N m]``): every CSV column, plus velocity, speed and modal coordinates.
        Arguments as [`to_xarray`][vbikit.solve.CrossingResult.to_xarray]."""
        import pandas as pd

        ds = self.to_xarray(points, girder_x, static, names, effects)
        plain = {cf: unit for unit, cf in CF_UNITS.items()}
        cols: dict[str, NDArray[np.float64]] = {}
        for name, var in ds.data_vars.items():
            units = plain.get(var.attrs.get("units", ""), var.attrs.get("units", ""))  # (none: per member, below)
            if var.dims == ("time",):
                cols[f"{name} [{units}]"] = var.values
                continue
            dim = var.dims[1]
            for i, label in enumerate(ds[dim].values):
                if dim == "point":
                    col = name if ds.sizes["point"] == 1 else f"{name}_{label}"
                    unit = units
                elif dim == "girder":
                    col, unit = name.replace("girder_", f"girder{label}_"), units
                elif dim == "dof":
                    member = ds["dof_acceleration_units" if name == "vehicle_acceleration" else "dof_units"].values[i]
                    unit = plain.get(str(member), str(member))
                    col = f"{label}" if name == "vehicle_displacement" else f"{label}_acceleration"
                elif dim == "mode":
                    col, unit = f"mode{label}", units
                elif dim == "vehicle":
                    col, unit = f"v{label}_{name}", units
                else:
                    col, unit = f"{name}_{label}", units
                cols[f"{col} [{unit}]"] = var.values[:, i]
        frame = pd.DataFrame(cols, index=pd.Index(self.time, name="time [s]"))
        return frame




def dof_unit(name: str) -> str:
    """Unit of a vehicle DOF by its name: rotations (``*_pitch``, ``*_roll``) in rad, else m."""
    return "rad" if name.endswith(("_pitch", "_roll")) else "m"


def dof_acceleration_unit(name: str) -> str:
    """CF unit of a vehicle DOF's acceleration by its name (``dof_unit`` per s²): ``rad s-2`` or ``m s-2``."""
    return f"{dof_unit(name)} s-2"


def deck_point_coords(time: NDArray[np.float64], names: Sequence[str], xs: Sequence[float],
                      ys: Sequence[float]) -> dict[str, Any]:
    """A dataset's ``time`` [s] and response-point coordinates: ``point`` (the names), ``x`` and ``y`` [m] (from the
    entry support, from the deck centreline) — the ordinary run's and the random run's."""
    return {"time": ("time", time, {"units": "s", "long_name": "time"}), "point": ("point", list(names)),
            "x": ("point", np.array(xs, float), {"units": "m", "long_name": "response point from the entry support"}),
            "y": ("point", np.array(ys, float), {"units": "m", "long_name": "response point from the deck centreline"})}


def vehicle_dof_coords(dof_names: Sequence[str]) -> dict[str, Any]:
    """A dataset's vehicle-DOF coordinates: ``dof`` (the names), ``dof_units`` and ``dof_acceleration_units`` (each
    DOF's unit and its acceleration's, CF spelled) — what ``vehicle_dof_units`` points a variable at."""
    names = list(dof_names)
    return {"dof": ("dof", names), "dof_units": ("dof", [dof_unit(n) for n in names]),
            "dof_acceleration_units": ("dof", [dof_acceleration_unit(n) for n in names])}


def vehicle_dof_units(dof_names: Sequence[str], acceleration: bool = False) -> dict[str, str]:
    """The unit attributes of a variable over the vehicle DOFs (``vbikit.outputs.member_units``): the DOFs' one
    unit, or ``units_by_dof`` naming the coordinate of each DOF's (``dof_units``, or ``dof_acceleration_units`` for
    an ``acceleration``) where translations and rotations mix — one parseable unit per variable, as CF allows (it
    wrote "m or rad (dof_units)", which no unit parser reads)."""
    unit = dof_acceleration_unit if acceleration else dof_unit
    units = [unit(n) for n in dof_names] or [unit("")]  # (moving forces, no DOFs: an empty variable in m)
    return member_units(units, "dof", "dof_acceleration_units" if acceleration else "dof_units")
