"""The moment envelope along a span: sections, the exact static envelope of a chain of axle loads and
the dynamic envelope of one crossing around a section."""
from __future__ import annotations

from typing import TYPE_CHECKING, Optional

import numpy as np
from numpy.typing import NDArray

from vbikit.bridge.base import ModalBridge
from vbikit.vehicle.trains import Train

if TYPE_CHECKING:
    from vbikit.rail.sweep import SweepSetup


#: the entry support's station lies this fraction of L right of it: a bridge model gives the moment at a
#: section as that of the forces and couples left of it, 0 at x = 0 exactly (a restrained end's couple is
#: at x = 0); just right of it the moment is the end's hogging moment (to a relative 1e-6)
END_OFFSET = 1e-6


def moment_sections(span: float, n: int, supports=(0.0,)) -> NDArray[np.float64]:
    """The moment stations [m]: x_j = j L / n, j = 0 … n (n even: midspan among them; x_0 at
    ``END_OFFSET`` · L), and every support x in ``supports`` (the span's ends, and interior supports
    of a continuous girder), sorted.  The supports are stations because a span with restrained
    ends, or a continuous girder over them, has its hogging moment there — the largest where the
    restraint is stiff — which an envelope of interior stations alone cannot see; on a simply
    supported span their moment is 0."""
    xs = np.concatenate([span * np.arange(0, n + 1) / n, np.asarray(supports, float)])
    xs = np.sort(xs[(xs >= 0.0) & (xs <= span * (1 + 1e-12))])
    keep = np.r_[True, np.diff(xs) > 1e-9 * span]
    xs = np.minimum(xs[keep], span)
    xs[0] = max(xs[0], END_OFFSET * span)
    return xs


def stations_words(n: int) -> str:
    """The station set of ``moment_sections`` in words (dataset attributes, report, docs)."""
    return (f"x = j L/{n}, j = 0 … {n} (both supports and midspan among them; x_0 = {END_OFFSET:g} L, just right of "
            "the entry support), and every interior support")


#: influence values [m per unit load] below this fraction of L are rounding of 0 (the moment line at a simply
#: supported end, a station of ``moment_sections``)
ROUNDING = 1e-12
#: a line is piecewise linear when it leaves the chords between its breakpoints by at most this share of its largest value
LINEAR_TOL = 1e-9
#: samples per piece of the linearity test, and first-axle travel samples per span on a curved line
_LINEAR_SAMPLES = 200
TRAVEL_STEPS = 400


def piecewise_linear(effect, x: float, span: float, y: float = 0.0) -> bool:
    """Whether the influence line η(ξ) of ``effect`` (section ``x`` [m]) is straight between its
    breakpoints 0, x, L (a simply supported span's moment and shear lines; not those of a span with
    rotational end restraints or of a girder in a deck, which are curved)."""
    eps = 1e-9 * span
    values, chords = [], []
    for a, b in ((0.0, x), (x, span)):
        if b - a <= 2 * eps:
            continue
        u = np.linspace(a + eps, b - eps, _LINEAR_SAMPLES)
        eta = np.asarray(effect.influence(u, np.full(u.size, y)), float)
        values.append(eta)
        chords.append(eta[0] + (eta[-1] - eta[0]) * (u - u[0]) / (u[-1] - u[0]))
    top = max((float(np.max(np.abs(v))) for v in values), default=0.0)
    return all(float(np.max(np.abs(v - c))) <= LINEAR_TOL * top for v, c in zip(values, chords)) if top > 0 else True


def static_envelope(bridge: ModalBridge, kind: str, sections: NDArray[np.float64], axles: NDArray[np.float64],
                    loads: NDArray[np.float64], y: float = 0.0, travel: Optional[NDArray[np.float64]] = None) -> NDArray[np.float64]:
    """max over the train's positions of |Σ_k P_k η(s − a_k)| at each section (η the effect of a unit
    downward force).  On a piecewise-linear influence line (a simply supported span's: breakpoints
    0, x, L; ``piecewise_linear``) the exact extreme by the breakpoint sweep
    (``vbikit.analysis.breakpoints.chain_extremes``: an axle on a breakpoint; each straight piece
    read 1e-9 L inside its ends and extended to them, the one-sided limits).  A curved line (restrained ends, a girder of a deck) is evaluated
    where an axle stands on a breakpoint and at the first-axle travel samples ``travel`` [m], every
    L / ``TRAVEL_STEPS`` of travel when none is given; ``travel`` given, a straight-sided line is
    evaluated so too (besides the sweep)."""
    from vbikit.analysis.breakpoints import chain_extremes

    span = float(bridge.span)
    eps = 1e-9 * span
    out = np.zeros(sections.size)
    for j, x in enumerate(sections):
        effect = bridge.load_effect(kind, float(x))

        def eta_at(pos):
            pos = np.asarray(pos, float)
            on = (pos >= 0.0) & (pos <= span)
            eta = np.zeros(pos.shape)
            if on.any():
                eta[on] = -np.asarray(effect.influence(pos[on], np.full(int(on.sum()), y)), float)
            eta[np.abs(eta) <= ROUNDING * span] = 0.0  # a simply supported end's moment line: rounding of 0
            return eta

        straight = piecewise_linear(effect, float(x), span, y)
        best = 0.0
        if straight:
            knots = np.unique(np.array([0.0, min(max(float(x), 0.0), span), span]))
            knots = knots[np.r_[True, np.diff(knots) > 4 * eps]]
            # each straight piece read eps inside its ends and extended to them: the one-sided limits
            a, b = eta_at(knots[:-1] + eps), eta_at(knots[1:] - eps)
            ext = (b - a) * eps / (np.diff(knots) - 2 * eps)
            left, right = np.r_[0.0, b + ext], np.r_[a - ext, 0.0]
            hi, lo = chain_extremes(knots, left, right, axles, loads)
            best = max(hi, -lo)
        extra = travel
        if extra is None and not straight:
            extra = np.arange(0.0, span + float(axles[-1]) + span / TRAVEL_STEPS, span / TRAVEL_STEPS)
        if extra is not None or not straight:
            cand = np.concatenate(([] if straight else [axles + b for b in (0.0, float(x), span)]) +
                                  ([extra] if extra is not None else []))
            pos = cand[:, None] - axles[None, :]
            best = max(best, float(np.max(np.abs(eta_at(pos) @ loads))))
        out[j] = best
    return out


def moment_envelope_near(setup: "SweepSetup", train: Train, speed: float, x_lo: float, x_hi: float,
                         n: int = 81) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Peak |M| [N m] of one crossing at ``speed`` [m/s] at n sections in [x_lo, x_hi] [m] (mode
    acceleration, the sweep's Δx): the envelope between the sweep's sections, to place its maximum."""
    from vbikit.solve.moving_loads import moving_load_history

    bridge = setup.bridge
    xs = np.linspace(x_lo, x_hi, n)
    effects = [bridge.load_effect("moment", float(x)) for x in xs]
    h = moving_load_history(bridge, train.axle_positions, train.axle_loads, speed, dx=setup.dx,
                            free_vibration=setup.free_vibration, effects=effects, y=setup.y)
    r = np.array([e.modal for e in effects])                        # (n, n_m)
    resp = h.static_effects + (h.xi - h.modal_load / bridge.omega**2) @ r.T
    return xs, np.max(np.abs(resp), axis=0)
