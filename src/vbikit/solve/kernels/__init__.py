"""Compiled (numba) kernels of the coupled vehicle–bridge equations (paper Eq. 9, modal form).

State: bridge modal coordinates ξ (n_m) and vehicle coordinates q (n_d).

Contact-point kinematics (every point on its own).  Point p belongs to vehicle ``vehicle[p]``
and sits at

    x_p(t) = origin_p + dir_p · s_v(t),      dx_p/dt = dir_p · v_v(t)

where s_v(t) [m] and v_v(t) = ds_v/dt [m/s] ≥ 0 are the travel and speed of its vehicle v
(columns of ``Motion``, given on the half-step time grid, so each vehicle has its own
speed, acceleration, stop time and start), ``origin`` [m] is x_p at s_v = 0 and ``direction``
dir_p = +1 (driving towards +x) or −1 (towards −x).  One vehicle driving +x (a
[`vbikit.solve.Crossing`][vbikit.solve.Crossing]) has s_v = x_front(t), origin_p = −setback_p, dir_p = +1.

The contact law, written once (``contact_forces``, called by every integrator and by the
static start).  With mode-shape rows φ_p, φ'_p = ∂φ/∂x on the point's wheel track
``track[p]``, road elevation r_p on road line ``line[p]`` and the wheel's lowest point
z_w = h_w·q (row ``wheel_rows[wheel[p]]``):

    s_p  = φ_p·ξ + r_p                                   surface under the point
    ṡ_p  = φ_p·ξ̇ + dir_p v (φ'_p·ξ + r'(x_p))            (dir_p v φ'_p·ξ: convective deck rate)
    δ_p  = s_p − g_p − z_w                               penetration (gap g_p ≥ 0)
    F_p  = k_p δ_p + c_p (ṡ_p − ż_w) + f0_p              (compression > 0)
    gated points (disk tires, or all points with loss of contact): F_p = max(0, F_p) if δ_p > 0 else 0
    envelope wheels (rigid disk): only the point of largest s_p − g_p acts, with the surface
    rate along the travel direction clamped to the circle's slopes there (``slope_range``)
    ξ̈ + 2ζω ξ̇ + ω² ξ = −Σ_p φ_pᵀ F_p
    M_v q̈ + C_v q̇ + K_v q = F_G + Σ_w h_wᵀ Σ_{p∈w} F_p

The road rate r'(x_p) dir_p v.  RK4 evaluates the law at its stage times and reads the slope of the
point's road cell (the profile is linear between stations).  The implicit integrators (exact,
Newmark) evaluate it at step ends and integrate the dashpot's load as linear over each step (the
trapezoid), so they read the secant over the half steps around the step end,
dir_p v (r(x_p + a) − r(x_p − a)) / 2a with a = v dt/2 (``road_point``'s ``span`` = dt/2): the
trapezoid's sum dt (ṙ_n + ṙ_{n+1})/2 is then the road crossed, r(x_{n+3/2}) − r(x_{n−1/2}) over
two steps, whatever the point's offset in its cell.  With the cell's slope instead, that offset
drifts from step to step unless v dt is a whole number of stations, and the sampled slopes alias the
road's curvature at the beat frequency |v dt/h − round(v dt/h)|/dt into the deck's and axles' band
(impact factors that moved by up to 3.6e-3 for a 2 % change of step;
``benchmarks/bench_rate_alignment.py``, docs/verification.md).  At the run's start a point has no
road behind it: the static start and a kernel call's first evaluation when the call starts at the
run's start (``span`` < 0, ``integrators._span``) read the secant over the road ahead only (every
point, a rigid disk's candidates too: its envelope's rate is then that of the candidate in contact
over the cell it moves into, clamped),
v (r(x_p + a) − r(x_p)) / a driving +x (the mirror driving −x; ``secant_ends``), whose limit is the slope of the cell
the point moves into, as RK4 reads it: the two integrators then converge to one answer where a point
starts on a station (on it within rounding: ``contact.road_cell`` takes a point within ``ON_STATION``
of a cell's width of a station to be on it, so that RK4's cell is not the one behind the point).

A point on track k is on the deck while start_k ≤ x_p ≤ end_k (the track's own span: 0 … span,
shifted by y tan θ on a skew deck, whose oblique support lines cross each track elsewhere); off
it, φ_p = 0 (the road only).  Nothing in the kernels assumes φ = 0 at the deck ends or a single
span: the mode-shape tables may be any mode set (continuous beams, grillages, skew decks),
tabulated over [start_k, end_k] on each wheel track k.

Several vehicles.  The kernels only see contact points, wheels and vehicle DOFs; a traffic
event is one system whose vehicle matrices are block-diagonal (one block per vehicle), whose
wheels index rows of the stacked DOF vector and whose points carry their vehicle index,
origin and direction.  Wheels of one vehicle must be contiguous in points (``wheel_first``,
``wheel_count``), as for one vehicle.

Modules, by role: ``bundles`` (argument bundles and work spaces), ``lanes`` (lane-wise array
helpers), ``contact`` (the contact law and the right-hand side), ``explicit`` (RK4), ``implicit_step``
(the partitioned implicit step loop), ``newton`` (its contact solve), ``woodbury`` (the quasi-Newton
update's wheel part, shared by ``newton`` and ``lean_lanes``), ``dense`` (small LU systems), ``lean`` (the same step loop for
one lane and the one-evaluation steps only, flat; it stops at any other step), ``lean_lanes`` (the same
for many lanes, the lane index innermost; it freezes a lane at any other step), ``assembly`` (the
static modal load history), ``run_in`` (the run-in's road loads and a linear recursion, ``vbikit.solve.run_in``).  Everything is importable from this package, as when it was one module.

Argument bundles (NamedTuples of arrays, built by ``vbikit.solve.system``):
  ``Modes``     the bridge's mode set and its tables along the wheel tracks
  ``Vehicles``  vehicle matrices, wheel rows and wheel → point ranges
  ``Points``    per contact point: kinematics, track, road line, tire law
  ``Road``      road stations and elevations of every road line and lane
  ``Motion``    travel s_v and speed v_v of every vehicle on the half-step grid

Lanes.  The state carries a last axis of L *lanes*: L crossings that share everything but the
road (a batch of a study), integrated together.  Everything that does not depend on the road
(positions, mode shapes at the contact points, the step) is computed once for all lanes, and
the per-lane arithmetic runs in contiguous inner loops that the compiler vectorises.  Each
lane's arithmetic is that of a single crossing (L = 1 is ``simulate``).  The argument
``lanes`` selects one of two compiled variants: a 1-tuple (``ONE_LANE``) = one lane, a
compile-time constant, so that every lane loop disappears (and sums stay in registers); a
2-tuple (``MANY_LANES``) = many lanes, L read from the arrays at run time (the form the loop
vectoriser handles; its vector loops take 32 doubles at a time, hence the callers' 32-lane calls
padded to multiples of 8).  ``rk4`` runs a single crossing with the one-lane variant (2× faster
than the many-lane one at L = 1); ``implicit``, ``contact_forces`` called from Python and
``road_at`` are only called with many lanes, one lane too (L = 1 at run time): their one-lane
variants cost ≈ 17 s of cold compile for the rigid-disk crossings alone (1.2× faster there; a
crossing without rigid disks runs the flat ``lean`` and hands only contact events over to
``implicit``).  Hot loops index 2-D arrays directly rather than through row views (measured
faster here, ≈ 15 %).  Integer arguments of compiled helpers are never bare literals (``np.int64(0)``,
not ``0``, also for a counter's first value): numba compiles a call with a constant argument, or
with a counter still typed by its first ``= 0``, as a variant of its own (a ``Literal[int]``
signature), seconds of compile time for nothing.

Mode shapes along each wheel track are tabulated on a uniform grid with values and slopes and
evaluated by cubic Hermite interpolation (``vbikit.solve.tabulate``).  Road elevations are
interpolated linearly in the road's stations inside the kernels (station pointers move both
ways, so points may drive towards −x).  Both lazily: a gated point that no lane can bring into
contact (r_max − g_p − min z_w + B ≤ 0, with r_max the highest road elevation and
B = max_lanes Σ_m max|φ_m|·|ξ_m| the largest possible deck displacement) needs neither.
"""
from __future__ import annotations

from vbikit.solve.kernels.bundles import (
    Cache,
    ModalStep,
    Modes,
    Motion,
    Points,
    Road,
    VehicleStep,
    Vehicles,
    Work,
    new_cache,
    new_work,
)
from vbikit.solve.kernels.contact import (
    accelerations,
    contact_forces,
    point_kinematics,
    point_law,
    road_at,
    road_point,
    shape_point,
    shapes_at,
)
from vbikit.solve.kernels.explicit import rk4
from vbikit.solve.kernels.lanes import MANY_LANES, ONE_LANE
from vbikit.solve.kernels.assembly import static_modal_history
from vbikit.solve.kernels.newton import LEAN_CORRECTIONS, QUASI_ITERATIONS, RELAX_AFTER, TOUCH_STIFFNESS
from vbikit.solve.kernels.implicit_step import implicit
from vbikit.solve.kernels.lean import lean, lean_law, lean_quadratic, lean_work
from vbikit.solve.kernels.lean_lanes import lean_lanes, lean_lanes_quadratic
from vbikit.solve.kernels.run_in import linear_recursion, run_in_loads

__all__ = [
    "Cache", "ModalStep", "Modes", "Motion", "Points", "Road", "VehicleStep", "Vehicles", "Work", "new_cache",
    "new_work", "accelerations", "contact_forces", "point_kinematics", "point_law", "road_at", "road_point",
    "shape_point", "shapes_at", "rk4", "static_modal_history", "LEAN_CORRECTIONS", "QUASI_ITERATIONS",
    "RELAX_AFTER", "TOUCH_STIFFNESS", "implicit", "lean", "lean_law", "lean_work", "lean_lanes", "lean_quadratic", "lean_lanes_quadratic", "linear_recursion", "run_in_loads", "MANY_LANES",
    "ONE_LANE",
]
