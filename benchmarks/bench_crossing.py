"""Benchmark: one HS20-44 crossing of Bridge 2 (16.76 m composite beam) with vbikit, against scipy.

Run from the repository root::

    python benchmarks/bench_crossing.py            # default: numba's on-disk cache as it is
    python benchmarks/bench_crossing.py --cold     # fresh numba cache: the warm-up includes JIT compilation
    python benchmarks/bench_crossing.py --repeat 9 --no-baseline

The case: ``paper_beam(16.76, "II", n_modes=20)``, ``hs20_44()``, ``MultiPointTire(n_points=6)``
(36 contact points), ISO 8608 class C random road (seed 1), 75 km/h, the default integrator
(exact modal stepping) with its automatic time step, ``vbikit.solve.simulate(Crossing(...))``,
against RK4 at its automatic step in the same run (the ratio is the figure to read); the same
pair on the 3D ``paper-bridge-2`` deck (20 modes, Girder 4); and the cost of the default against
the number of modes (5 … 80) at a fixed step.

Measured (wall clock, ``time.perf_counter``):

* warm-up: the first ``simulate`` call of the process (JIT compilation, or loading the compiled
  kernels from numba's cache, plus one run); reported separately;
* vbikit: median (and min/max) of ``--repeat`` further calls of ``simulate`` (everything a crossing
  costs: time-step choice, road sampling, mode tabulation, static start, integration);
* baseline: one ``scipy.integrate.solve_ivp`` (RK45, rtol 1e-6, atol 1e-10) of the same equations
  written independently here in numpy, from the same initial state (vbikit's row 0);
* agreement: max |midspan displacement difference| / |peak midspan displacement| and the
  impact factor from each history;
* ratios: RK4 / default on the beam and on the 3D deck (same run);
* context: the same crossing with Newmark (average acceleration) and with the point tire (n = 1);
* modes: the default at dt = 0.96 ms with 5, 10, 20, 40, 80 modes (time per crossing and per mode).

The library is not modified; nothing is written except numba's cache.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

from _args import benchmark_args


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--no-baseline", action="store_true", help="skip the (slow, ~1-2 min) solve_ivp baseline")
    return benchmark_args(__doc__, "timed vbikit runs after the warm-up (default 5, min 1)", p)


ARGS = parse_args()  # before numba is imported (--cold)

import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from vbikit.analysis import point_response  # noqa: E402
from vbikit.bridge import paper_beam  # noqa: E402
from vbikit.contact import MultiPointTire, PointTire  # noqa: E402
from vbikit.road import RoadPSD, random_profile  # noqa: E402
from vbikit.solve import Crossing, kernels, simulate  # noqa: E402
from vbikit.vehicle import hs20_44  # noqa: E402

SPEED = 75.0 / 3.6  # [m/s]
N_MODES = 20
N_POINTS = 6
RTOL, ATOL = 1e-6, 1e-10


# ----------------------------------------------------------------------------- helpers
def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def time_runs(crossing: Crossing, repeat: int):
    """Warm-up call, then ``repeat`` timed calls; returns (warm-up s, list of s, last result)."""
    warm, result = timed(lambda: simulate(crossing))
    runs = []
    for _ in range(repeat):
        dt, result = timed(lambda: simulate(crossing))
        runs.append(dt)
    return warm, runs, result


def _integration_time(crossing: Crossing, repeat: int) -> float:
    """Median time [s] of the step loop alone over ``repeat`` runs of ``crossing``: the kernel calls
    of each run summed (``kernels.lean`` and ``lean_quadratic``, the default path, and ``kernels.implicit`` where a crossing
    needs it or RK4's kernel; the rest of a ``simulate`` is the fixed per-crossing work)."""
    from _args import default_step_loops

    names = ("lean", default_step_loops()[0], "implicit", "rk4")
    originals = {name: getattr(kernels, name) for name in names if hasattr(kernels, name)}
    current: list[float] = []

    def timed(original):
        def kernel(*args, **kwargs):
            t0 = time.perf_counter()
            out = original(*args, **kwargs)
            current.append(time.perf_counter() - t0)
            return out
        return kernel

    spent = []
    for name, original in originals.items():
        setattr(kernels, name, timed(original))
    try:
        for _ in range(repeat):
            current.clear()
            simulate(crossing)
            spent.append(sum(current))
    finally:
        for name, original in originals.items():
            setattr(kernels, name, original)
    return statistics.median(spent)


def cache_state() -> str:
    hits = misses = 0
    for name in ("rk4", "implicit", "shapes_at", "road_at", "accelerations", "contact_forces"):
        stats = getattr(kernels, name).stats
        hits += sum(stats.cache_hits.values())
        misses += sum(stats.cache_misses.values())
    if misses and not hits:
        return "compiled (numba cache empty)"
    if hits and not misses:
        return "loaded from numba cache"
    return f"numba cache hits {hits}, misses {misses}"


def fmt_runs(runs: list[float]) -> str:
    return f"median {statistics.median(runs):.3f} s (min {min(runs):.3f}, max {max(runs):.3f}, n={len(runs)})"


def impact_factor(dyn: np.ndarray, st: np.ndarray) -> float:
    """IM = (max downward dynamic − max downward static) / max downward static (z up)."""
    return float((np.max(-dyn) - np.max(-st)) / np.max(-st))


# ----------------------------------------------------------------------------- baseline
class Baseline:
    """The coupled equations (kernels.py docstring), written independently in numpy.

    Bridge: simply supported beam, exact modes φₙ = √(2/mL) sin(nπx/L), ωₙ = (nπ/L)²√(EI/m).
    Vehicle: M, C, K, F_G and wheel rows from the Vehicle object.  Contact: per wheel, n points
    at offsets −a/2 … +a/2 (spacing a/(n−1), the "ends" layout), each k/n, c/n.
    State y = [ξ, ξ̇, q, q̇].
    """

    def __init__(self, beam, vehicle, road, speed, approach, n_points, contact_length):
        self.L = beam.span
        self.n_m = beam.n_modes
        self.k1 = np.pi / self.L  # wavenumber of mode 1 [1/m]
        self.kn = self.k1 * np.arange(1, self.n_m + 1)
        self.amp = np.sqrt(2.0 / (beam.mass_per_length * self.L))
        self.omega = self.kn**2 * np.sqrt(beam.EI / beam.mass_per_length)
        self.c_modal = 2.0 * beam.damping_ratio * self.omega
        self.v = speed
        offsets = np.linspace(-contact_length / 2, contact_length / 2, n_points) if n_points > 1 else np.zeros(1)
        setback, k, c, rows, wheel = [], [], [], [], []
        for iw, w in enumerate(vehicle.wheels):
            for o in offsets:  # o > 0 is ahead of the wheel centre
                setback.append(w.offset - o)
                k.append(w.stiffness / n_points)
                c.append(w.damping / n_points)
                rows.append(w.row)
                wheel.append(iw)
        self.x_at_t0 = -approach - np.array(setback)  # x_p(t) = x_at_t0 + v t
        self.k, self.c = np.array(k), np.array(c)
        self.H = np.array(rows)  # (n_cp, n_d): z_wheel of point p = H[p] · q
        self.wheel = np.array(wheel)
        self.n_points = n_points
        self.n_d = vehicle.n_dof
        self.M_inv = np.linalg.inv(vehicle.mass)
        self.C, self.K, self.F_G = vehicle.damping, vehicle.stiffness, vehicle.gravity
        self.vehicle = vehicle
        # road: piecewise-linear interpolation of the RoadProfile's samples (right-hand slope)
        self.rx, self.rz = road.x, road.z
        self.rslope = np.diff(road.z) / np.diff(road.x)
        self.n_calls = 0

    def road(self, x):
        seg = np.clip(np.searchsorted(self.rx, x, side="right") - 1, 0, self.rx.size - 2)
        slope = self.rslope[seg]
        return self.rz[seg] + slope * (x - self.rx[seg]), slope

    def shapes(self, x):
        """φ, φ' (n_x, n_modes) at stations x inside the span; sin(nθ), cos(nθ) from e^{inθ}."""
        e = np.cumprod(np.broadcast_to(np.exp(1j * self.k1 * x)[:, None], (x.size, self.n_m)), axis=1)
        return self.amp * e.imag, self.amp * self.kn * e.real

    def rhs(self, t, y):
        self.n_calls += 1
        n_m, n_d, v = self.n_m, self.n_d, self.v
        xi, dxi = y[:n_m], y[n_m : 2 * n_m]
        q, dq = y[2 * n_m : 2 * n_m + n_d], y[2 * n_m + n_d :]
        x = self.x_at_t0 + v * t
        r, slope = self.road(x)
        # F_p = k (φ·ξ + r − h·q) + c (φ·ξ̇ + v φ'·ξ + v r' − h·q̇), compression positive
        force = self.k * (r - self.H @ q) + self.c * (v * slope - self.H @ dq)
        ddxi = -self.c_modal * dxi - self.omega**2 * xi
        on = (x >= 0.0) & (x <= self.L)
        if on.any():
            phi, dphi = self.shapes(x[on])
            f_on = force[on] + self.k[on] * (phi @ xi) + self.c[on] * (phi @ dxi + v * (dphi @ xi))
            force[on] = f_on
            ddxi -= phi.T @ f_on
        ddq = self.M_inv @ (self.F_G - self.C @ dq - self.K @ q + self.H.T @ force)
        return np.concatenate((dxi, ddxi, dq, ddq))

    def static_midspan(self, t):
        """Midspan deflection under the static wheel loads moved along the same path (same modes)."""
        veh = self.vehicle
        k_tire = sum(w.stiffness * np.outer(w.row, w.row) for w in veh.wheels)
        q_s = np.linalg.solve(veh.stiffness + k_tire, veh.gravity)
        loads = np.array([-w.stiffness * (w.row @ q_s) for w in veh.wheels])  # downward positive [N]
        p = loads[self.wheel] / self.n_points
        phi_mid = self.amp * np.sin(self.kn * self.L / 2)
        out = np.zeros(t.size)
        for i, ti in enumerate(t):
            x = self.x_at_t0 + self.v * ti
            on = (x >= 0.0) & (x <= self.L)
            if on.any():
                phi, _ = self.shapes(x[on])
                xi_st = -(phi.T @ p[on]) / self.omega**2
                out[i] = phi_mid @ xi_st
        return out

    def midspan(self, xi_history):
        return xi_history @ (self.amp * np.sin(self.kn * self.L / 2))


# ----------------------------------------------------------------------------- main
def main() -> int:
    repeat = max(1, ARGS.repeat)
    t_start = time.perf_counter()
    beam = paper_beam(16.76, "II", n_modes=N_MODES)
    truck = hs20_44()
    road = random_profile(RoadPSD.iso("C"), seed=1)
    tire = MultiPointTire(n_points=N_POINTS)
    crossing = Crossing(beam, truck, tire, road, speed=SPEED)

    print("vbikit crossing benchmark: Bridge 2 beam (16.76 m, Type II, 20 modes), HS20-44, "
          f"{N_POINTS}-point tire, ISO C road seed 1, {SPEED * 3.6:.0f} km/h")
    print(f"python {sys.version.split()[0]}, numpy {np.__version__}, {os.cpu_count()} CPUs"
          + (", fresh numba cache (--cold)" if ARGS.cold else ""))

    warm, runs, res = time_runs(crossing, repeat)
    pr = point_response(res)
    im_vbikit = pr.displacement_impact.impact_factor
    print(f"\n{crossing.integrator} (default), n = {N_POINTS}: dt = {res.dt:.3e} s (auto), {res.n_steps} steps, "
          f"{crossing.contact.n} contact points, {res.q.shape[1]} vehicle DOFs")
    print(f"  warm-up (first call): {warm:.3f} s  [{cache_state()}]")
    print(f"  timed:                {fmt_runs(runs)}")
    print(f"  midspan peak {pr.displacement.min() * 1e3:.4f} mm, static {pr.static_displacement.min() * 1e3:.4f} mm, "
          f"IM = {im_vbikit:.5f}")
    t_vbikit = statistics.median(runs)
    kernel = _integration_time(crossing, repeat)
    print(f"  of which the integration (the compiled kernel): median {kernel * 1e3:.1f} ms; the fixed per-crossing "
          f"work (step choice, tables, static start, set-up): {(t_vbikit - kernel) * 1e3:.1f} ms "
          f"({(t_vbikit - kernel) / kernel:.2f} of the integration)")

    rk4 = Crossing(beam, truck, tire, road, speed=SPEED, integrator="rk4")
    w4, r4, res4 = time_runs(rk4, repeat)
    im4 = point_response(res4).displacement_impact.impact_factor
    print(f"RK4, same crossing: dt = {res4.dt:.3e} s (auto), {res4.n_steps} steps, warm-up {w4:.3f} s, {fmt_runs(r4)}, "
          f"IM = {im4:.5f}")
    print(f"  ratio RK4 / default: {statistics.median(r4) / t_vbikit:.1f}x ({res4.n_steps / res.n_steps:.1f}x fewer steps), "
          f"IM difference {im_vbikit - im4:+.1e}")

    # the 3D deck: paper-bridge-2, 20 modes, Girder 4
    from vbikit.bridge import paper_deck

    deck = paper_deck(2, n_modes=N_MODES)
    girder_y = float(deck.girder_y[3])
    pairs = {}
    for integ in ("exact", "rk4"):
        cr = Crossing(deck, truck, tire, road, speed=SPEED, integrator=integ,
                      lateral_offset=float(getattr(deck, "default_lateral_offset", 0.0)))
        w, rs, rr = time_runs(cr, repeat)
        pairs[integ] = (statistics.median(rs), rr, point_response(rr, None, girder_y).displacement_impact.impact_factor)
        print(f"paper-bridge-2 (3D, {N_MODES} modes, Girder 4), {integ}: {rr.n_steps} steps, {fmt_runs(rs)}, "
              f"IM = {pairs[integ][2]:.5f}")
    print(f"  ratio RK4 / default: {pairs['rk4'][0] / pairs['exact'][0]:.1f}x, IM difference "
          f"{pairs['exact'][2] - pairs['rk4'][2]:+.1e}")

    # context: Newmark and the point tire
    context = [("Newmark, n = 6", Crossing(beam, truck, tire, road, speed=SPEED, integrator="newmark")),
               ("default, point tire (n = 1)", Crossing(beam, truck, PointTire(), road, speed=SPEED)),
               ("RK4, point tire (n = 1)", Crossing(beam, truck, PointTire(), road, speed=SPEED, integrator="rk4"))]
    print("\ncontext (same truck, road, speed, automatic dt):")
    for name, cr in context:
        w, rs, rr = time_runs(cr, repeat)
        prr = point_response(rr)
        extra = ""
        if cr.tire == tire:
            diff = np.max(np.abs(prr.displacement - np.interp(rr.time, res4.time, point_response(res4).displacement)))
            extra = f", max |Δu_mid| vs RK4 = {diff / np.max(np.abs(pr.displacement)):.2e} of peak"
        print(f"  {name:28s} warm-up {w:.3f} s, {fmt_runs(rs)}; {rr.n_steps} steps, "
              f"IM = {prr.displacement_impact.impact_factor:.5f}{extra}")

    print("\ncost against the number of modes (default integrator, dt = 0.96 ms fixed):")
    base_t = None
    for n_modes in (5, 10, 20, 40, 80):
        cr = Crossing(paper_beam(16.76, "II", n_modes=n_modes), truck, tire, road, speed=SPEED, dt=9.6e-4)
        w, rs, rr = time_runs(cr, repeat)
        t = statistics.median(rs)
        base_t = base_t or t / 5
        print(f"  {n_modes:3d} modes: {t * 1e3:7.1f} ms per crossing ({t / n_modes * 1e3:.2f} ms per mode), "
              f"{rr.n_steps} steps, IM = {point_response(rr).displacement_impact.impact_factor:.5f}")

    if ARGS.no_baseline:
        print(f"\n(baseline skipped)  total {time.perf_counter() - t_start:.1f} s")
        return 0

    # baseline: scipy solve_ivp on an independent numpy formulation
    base = Baseline(beam, truck, road, SPEED, crossing.approach, N_POINTS, tire.contact_length)
    y0 = np.concatenate((res.xi[0], np.zeros(N_MODES), res.q[0], np.zeros(truck.n_dof)))
    t_ivp, sol = timed(lambda: solve_ivp(base.rhs, (0.0, res.time[-1]), y0, method="RK45", rtol=RTOL, atol=ATOL,
                                          t_eval=res.time))
    if sol.status != 0:
        print(f"solve_ivp failed: {sol.message}")
        return 1
    u_base = base.midspan(sol.y[:N_MODES].T)
    u_st_base = base.static_midspan(res.time)
    im_base = impact_factor(u_base, u_st_base)
    peak = np.max(np.abs(pr.displacement))
    rel = np.max(np.abs(u_base - pr.displacement)) / peak
    print(f"\nbaseline: scipy solve_ivp RK45, rtol={RTOL:g}, atol={ATOL:g}, independent numpy right-hand side")
    print(f"  time {t_ivp:.2f} s (single run), {sol.nfev} rhs calls, {sol.t.size} output times")
    print(f"  ratio solve_ivp / vbikit median: {t_ivp / t_vbikit:.0f}x")
    print(f"  agreement: max |u_mid(vbikit) - u_mid(solve_ivp)| = {rel:.2e} of the peak ({peak * 1e3:.4f} mm)")
    print(f"  impact factor: vbikit {im_vbikit:.5f} (vbikit.analysis), solve_ivp {im_base:.5f} (independent static "
          f"reference), difference {abs(im_vbikit - im_base):.1e}")
    st_diff = np.max(np.abs(u_st_base - pr.static_displacement)) / np.max(np.abs(pr.static_displacement))
    print(f"  static references agree to {st_diff:.1e} of the static peak")
    print(f"\ntotal wall time {time.perf_counter() - t_start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
