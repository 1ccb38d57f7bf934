"""The time step a load effect needs: one rule for `vbikit run` and for the Python path.

A load effect R (moment, shear, reaction) weighs the higher bridge modes far more than the
deflection does: its value per unit force at x carried by mode i is r_i φ_i(x) / ω_i² (mass-
normalised modes, ``vbikit.bridge.effects``).  A wheel load P moving at v drives mode i with
P φ_i(v t); the mode follows it quasi-statically except where the drive changes abruptly, at the
deck ends: a jump |φ_i| (a deck end on elastic bearings) leaves a free vibration of amplitude
P |φ_i| / ω_i², a kink (the slope φ_i' of a pinned end) one of P v |φ_i'| / ω_i³.  Per unit load the
mode's share of the effect then rings with at most

    a_i = |r_i| / ω_i² · Σ_ends (|φ_i| + v |φ_i'| / ω_i)      (both ends of a wheel line, the largest line)

Read every dt, a sinusoid of frequency f_i loses at most a_i (1 − cos(π f_i dt)) of its peak between
two samples, and all of it (a_i) once f_i dt ≥ 1/2 (the exact integrator's states of such a mode
are no better).  The estimate of the error of the effect's impact factor is the root sum of
squares of these losses over the largest static influence |I|max:

    e(dt) = sqrt(Σ_i [a_i (1 − cos(π min(f_i dt, 1/2)))]²) / max_x |I(x)|,   I(x) = Σ_i r_i φ_i(x) / ω_i²

(independent of the vehicle's weight).  ``load_effect_step`` is the largest dt with
e(dt) ≤ ``STEP_TOLERANCE`` for every requested effect.  Measured on two 20 m spans on elastic
bearings (40 modes, no damping, quarter car at 70 km/h, pier moment; tests/verification/
test_library_step_check.py): e = 0.13, 0.038, 0.012, 0.0014 at dt = 1.25e-3, 3.1e-4, 1.5e-4, 5e-5 s
against observed impact-factor errors 0.068, 0.010, 0.0035, 0.0011: an upper estimate, within a
factor 1–10 (each mode's observed ring 0.4 … 1.0 a_i).  For a train of many axles it is an
estimate, not a bound: HSLM-A1 on a 20 m simple span at 226.8 km/h, reaction at the exit support,
0.0098 against an observed 0.0135 at dt = 1.43e-3 s; `vbikit run` confirms by step halving.
Wheel forces that vary fast (a rough road) ring the modes too and are not counted.

``vbikit run`` starts a load-effect run at this step when it is below the automatic one (then
confirms it by step halving, ``vbikit.scenario.step_check``); ``load_effect_response`` (the
Python path) compares the step a result was run at with it and says so when it is longer
(``logging.warning`` and ``LoadEffectResponse.step_warning``).
"""
from __future__ import annotations

from typing import Any, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import kept_for


#: largest estimated (and, in `vbikit run`'s halving check, observed) change [-] of an impact factor
#: that a step may leave
STEP_TOLERANCE = 5e-3
#: deck points per wheel line at which the influence of each mode is evaluated
_POINTS = 401
#: a result's step may exceed the recommended one by this factor before it is flagged (round-off)
_SLACK = 1.01


def _deck_points(crossing: Any) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """x, y [m] along every wheel line of ``crossing`` where a wheel can stand on the deck."""
    _, _, y = crossing.point_kinematics()
    return _line_points(crossing.bridge, np.unique(y))


def _line_points(bridge: Any, lines: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """x, y [m] along the wheel lines y = ``lines`` where a wheel can stand on the deck of ``bridge``."""
    x0, x1 = bridge.deck_extent
    xx, yy = np.meshgrid(np.linspace(x0, x1, _POINTS), lines)
    xi = np.asarray(bridge.span_coordinate(xx, yy))
    on = (xi >= 0.0) & (xi <= bridge.span)
    return xx[on], yy[on]


#: deck quantities (``_deck_modes``) and steps (``load_effect_step``) per bridge (by identity, dropped
#: with the bridge: bridges are immutable) and set of wheel lines: the events of a traffic stream or a
#: lifetime run on one bridge drive on a few lines, and scenario runs share their bridges
#: (``vbikit.scenario.build``)
_DECK_ENTRIES_PER_BRIDGE = 256


def _kept(crossing: Any, key: tuple, make: Any) -> Any:
    """The value of ``key`` kept for the crossing's bridge and set of wheel lines (``make()`` the first time)."""
    _, _, y = crossing.point_kinematics()
    return kept_for(crossing.bridge, "deck steps", _DECK_ENTRIES_PER_BRIDGE).get((np.unique(y).tobytes(),) + key, make)


def _deck_modes(crossing: Any) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Mode shapes at the deck points of every wheel line (n_points, n_modes) and, per line (n_lines,
    n_modes), Σ |φ_i| and Σ |φ_i'| over the line's two ends (kept per bridge and set of lines)."""
    _, _, y = crossing.point_kinematics()
    return _kept(crossing, ("modes",), lambda: _deck_modes_on(crossing.bridge, np.unique(y)))


def _deck_modes_on(bridge: Any, lines: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                                                     NDArray[np.float64]]:
    """``_deck_modes`` of the wheel lines y = ``lines`` (sorted, unique) on ``bridge``, computed."""
    x, y = _line_points(bridge, lines)
    n_m = bridge.omega.size
    if x.size == 0:
        return np.zeros((0, n_m)), np.zeros((1, n_m)), np.zeros((1, n_m))
    lines = np.unique(y)
    ends_x = np.array([[x[y == line].min(), x[y == line].max()] for line in lines]).ravel()
    ends_y = np.repeat(lines, 2)
    jump = np.abs(bridge.mode_shapes(ends_x, ends_y)).reshape(lines.size, 2, n_m).sum(axis=1)
    kink = np.abs(bridge.mode_slopes(ends_x, ends_y)).reshape(lines.size, 2, n_m).sum(axis=1)
    return bridge.mode_shapes(x, y), jump, kink  # shared by every crossing on these lines: read only


def mode_weights(crossing: Any, effect: Any) -> tuple[NDArray[np.float64], float]:
    """Per mode, a_i [m or 1 per N] of the module docstring: the bound of its free vibration's share
    of the effect per unit load, from the jump |φ_i| and the kink v |φ_i'| / ω_i the load makes in
    the modal force where a wheel enters and leaves the deck (summed over both ends of a wheel line,
    the largest over the lines), and max |I| of the modal influence line."""
    bridge = crossing.bridge
    shapes, jump, kink = _deck_modes(crossing)
    if shapes.shape[0] == 0:
        return np.zeros(bridge.omega.size), 0.0
    scale = np.asarray(effect.modal, float) / bridge.omega**2
    i_max = float(np.abs(shapes @ scale).max())
    per_line = jump + kink * (float(crossing.max_speed) / bridge.omega)[None, :]
    return np.abs(scale) * per_line.max(axis=0), i_max


def step_error(crossing: Any, effect: Any, dt: float) -> float:
    """The estimate e(dt) [-] of the impact-factor error of ``effect`` read every ``dt`` [s]
    (module docstring); 0 for an effect without static influence."""
    a, i_max = mode_weights(crossing, effect)
    return _error(a, i_max, crossing.bridge.frequencies_hz, dt)


def _error(a: NDArray[np.float64], i_max: float, f: NDArray[np.float64], dt: float) -> float:
    if i_max <= 0.0:
        return 0.0
    loss = a * (1.0 - np.cos(np.pi * np.minimum(f * dt, 0.5)))
    return float(np.sqrt(np.sum(loss**2)) / i_max)


def load_effect_step(crossing: Any, effects: Sequence[Any], tolerance: float = STEP_TOLERANCE) -> float:
    """The largest step [s] at which the estimate e(dt) of every effect's impact-factor error is at
    most ``tolerance`` (module docstring); inf without effects or modes."""
    f = np.asarray(crossing.bridge.frequencies_hz, float)
    if not len(effects) or f.size == 0:
        return float("inf")
    # kept per bridge, wheel lines, top speed, tolerance and effects: what the step depends on
    key = ("step", float(crossing.max_speed), float(tolerance),
           b"".join(np.asarray(e.modal, float).tobytes() for e in effects))
    return _kept(crossing, key, lambda: _load_effect_step(crossing, effects, tolerance, f))


def _load_effect_step(crossing: Any, effects: Sequence[Any], tolerance: float, f: NDArray[np.float64]) -> float:
    weights = [mode_weights(crossing, e) for e in effects]

    def worst(dt: float) -> float:
        return max(_error(a, i_max, f, dt) for a, i_max in weights)

    hi = 0.5 / float(f.min())  # every mode lost: e is at its largest from here on
    if worst(hi) <= tolerance:
        return float("inf")
    lo = hi
    while worst(lo) > tolerance and lo > 1e-12:
        lo /= 2.0
    for _ in range(40):  # e grows with dt: bisection in log dt
        mid = float(np.sqrt(lo * hi))
        lo, hi = (mid, hi) if worst(mid) <= tolerance else (lo, mid)
    return lo


def step_warning(crossing: Any, effect: Any, dt: float, tolerance: float = STEP_TOLERANCE) -> tuple[str | None, float]:
    """A warning (or None) if ``effect`` read from a run at step ``dt`` [s] is not resolved, and the
    recommended step [s] (``load_effect_step``)."""
    best = load_effect_step(crossing, [effect], tolerance)
    if not dt > _SLACK * best:
        return None, best
    error = step_error(crossing, effect, dt)
    return (f"{effect.label}: the step {dt:.3g} s does not resolve the bridge modes this load effect needs (its "
            f"impact factor may be off by up to about {error:.2g}); run with crossing dt <= {best:.2g} s "
            f"(estimated error <= {tolerance:g})"), best
