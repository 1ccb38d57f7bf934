"""Benchmark: vbikit's default integrator against a partitioned vehicle–bridge analysis in OpenSeesPy.

Run from the repository root (openseespy is a test dependency)::

    python benchmarks/bench_peers.py              # 5 timed samples of each, ≈ 40 s
    python benchmarks/bench_peers.py --repeat 9
    python benchmarks/bench_peers.py --stages     # and where vbikit's crossing spends its time

The case: the Yang & Yau (1997) sprung mass crossing a simply supported beam (L = 25 m,
EI = 2.87e9 × 2.9 N·m², m = 2303 kg/m, undamped; M_v = 5750 kg, k_v = 1595 kN/m, undamped;
100 km/h, smooth road; published midspan peak ≈ 2.41 mm), from entry to exit (0.9 s).

* **vbikit**: ``simulate(Crossing(...))`` with the default integrator and automatic step, 20 modes
  (everything a crossing costs: step choice, mode tabulation, static start, integration), and the
  midspan deflection history from it (its minimum is the peak, as on the OpenSees side).  Two
  figures: a *new model* each run (beam, vehicle and ``Crossing`` built anew, as the OpenSees side
  builds its model each run: the mode tables are tabulated again) and the *same crossing again*
  (the ``Crossing`` object run again: it keeps its plan, time grid, kernel data and static start,
  ``Crossing.kept``, so this is what re-running one crossing costs; a new ``Crossing`` on the same
  bridge and vehicle objects plans and starts again); of the latter, the thread CPU time of the
  step loop (the lean kernel the default integrator runs, ``_args.default_step_loops``).
* **OpenSeesPy, partitioned** (written here, the usual way a VBI is coupled to a general FE
  code): 20 ``elasticBeamColumn`` elements with lumped masses, Newmark average acceleration,
  dt = 1 ms, linear algorithm (the matrix factored once, ``-factorOnce``, which makes the stepping
  ≈ 2.3× cheaper; not for the iterative coupling, whose restoring of the state needs a new
  factorisation); the sprung mass integrated beside it by the same Newmark rule;
  the contact force F = k_v (u_b(x_c) − z) applied as consistent nodal loads (Hermite shape
  functions) of the element under the mass, and the deck displacement u_b(x_c) read back with
  the same shape functions (once per analysis).  Two couplings:

  - *iterative*: per step, analyse, update F from the new deck and vehicle states, restore the
    beam's committed state (``setNodeDisp/Vel/Accel … -commit``, ``domainChange``) and analyse
    again, until F changes by < 1e-8 of the weight;
  - *staggered*: one analysis per step with F from the predicted vehicle position (explicit
    in the coupling, the common cheap variant).

  and its *floor*: the same beam stepped over the crossing by one ``analyze`` call under a fixed
  load (no coupling, no Python per step), the least a partitioned analysis at that step costs.
  All three again at vbikit's step (same number of steps: a check that dt = 1 ms is not what
  makes the peer slow).

Reported: thread CPU time per crossing (``time.thread_time``: OpenSees and numba run in this
thread; BLAS is held to one thread), the minimum of ``--repeat`` samples after a warm-up (numba's
cache load is in the warm-up only), each sample the mean of as many runs as take ≥ 20 ms; the
midspan peaks and the ratios, measured in the same run.  The machine is shared: CPU time moves
much less with its load than wall time, and the ratios less still.
"""
from __future__ import annotations

import argparse
import ctypes
import importlib.util
import os
import sys
import time

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one BLAS thread: thread CPU time then counts all of a run's work

import numpy as np  # noqa: E402

L, E, I, M_BEAM = 25.0, 2.87e9, 2.9, 2303.0
MV, KV, V = 5750.0, 1595e3, 100 / 3.6
G = 9.80665
N_ELEMENTS = 20
DT_OPENSEES = 1e-3
N_MODES = 20


def load_opensees():
    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.submodule_search_locations:
        lib = os.path.join(spec.submodule_search_locations[0], "lib", "libblas.so.3")
        if os.path.exists(lib):  # the wheel's LAPACK needs libblas.so.3
            ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


def hermite(s: float, le: float) -> np.ndarray:
    """Cubic Hermite shape functions of a beam element at s = ξ/le (v_i, θ_i, v_j, θ_j)."""
    return np.array([1 - 3 * s**2 + 2 * s**3, le * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3, le * (-s**2 + s**3)])


class OpenSeesVBI:
    """The partitioned vehicle–bridge analysis (module docstring) at step ``dt`` [s]."""

    def __init__(self, ops, coupling: str, dt: float = DT_OPENSEES):
        self.ops, self.coupling, self.dt = ops, coupling, dt
        self.le = L / N_ELEMENTS

    def build(self) -> None:
        ops, le = self.ops, self.le
        ops.wipe()
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        for i in range(N_ELEMENTS + 1):
            ops.node(i + 1, i * le, 0.0)
            m = M_BEAM * le * (0.5 if i in (0, N_ELEMENTS) else 1.0)
            ops.mass(i + 1, m, m, 0.0)
        ops.fix(1, 1, 1, 0)
        ops.fix(N_ELEMENTS + 1, 0, 1, 0)
        ops.geomTransf("Linear", 1)
        for e in range(N_ELEMENTS):
            ops.element("elasticBeamColumn", e + 1, e + 1, e + 2, 1.0, E, I, 1)
        ops.timeSeries("Constant", 1)
        ops.constraints("Plain")
        ops.numberer("RCM")
        ops.system("BandGeneral")
        ops.test("NormDispIncr", 1e-12, 10)
        # the beam is linear and the step fixed: factor its matrix once, except when the iterative
        # coupling restores the committed state (domainChange), after which OpenSees must factor again
        ops.algorithm("Linear", *(() if self.coupling == "iterative" else ("-factorOnce",)))
        ops.integrator("Newmark", 0.5, 0.25)
        ops.analysis("Transient")

    def _element(self, x: float) -> tuple[int, tuple[float, float, float, float]]:
        """The element under x (0-based) and its Hermite shape functions there (plain floats)."""
        e = min(int(x / self.le), N_ELEMENTS - 1)
        return e, tuple(float(v) for v in hermite((x - e * self.le) / self.le, self.le))

    def _apply(self, e: int, n, force: float) -> None:
        """The contact force (compression > 0, acting down on the deck) as nodal loads of element e."""
        ops = self.ops
        ops.remove("loadPattern", 1)
        ops.pattern("Plain", 1, 1)
        ops.load(e + 1, 0.0, -force * n[0], -force * n[1])
        ops.load(e + 2, 0.0, -force * n[2], -force * n[3])

    def _deck(self, e: int, n) -> float:
        """Deck displacement under the mass (z up) from the element's end displacements."""
        ops = self.ops
        vi, ti = ops.nodeDisp(e + 1)[1:]
        vj, tj = ops.nodeDisp(e + 2)[1:]
        return n[0] * vi + n[1] * ti + n[2] * vj + n[3] * tj

    def _snapshot(self):
        ops = self.ops
        return [(k, ops.nodeDisp(k), ops.nodeVel(k), ops.nodeAccel(k)) for k in range(1, N_ELEMENTS + 2)]

    def _restore(self, snap, t: float) -> None:
        ops = self.ops
        for k, u, v, a in snap:
            for d in (1, 2, 3):
                ops.setNodeDisp(k, d, u[d - 1], "-commit")
                ops.setNodeVel(k, d, v[d - 1], "-commit")
                ops.setNodeAccel(k, d, a[d - 1], "-commit")
        ops.setTime(t)
        ops.domainChange()  # the integrator re-reads the committed state from the domain

    def floor(self) -> int:
        """The same beam stepped alone over the crossing (one ``analyze`` call, the weight at midspan,
        no coupling): the least a partitioned analysis at this step can cost.  Returns the steps."""
        ops, h = self.ops, self.dt
        self.build()
        ops.pattern("Plain", 1, 1)
        ops.load(N_ELEMENTS // 2 + 1, 0.0, -MV * G, 0.0)
        n_steps = int(round(L / V / h))
        ops.analyze(n_steps, h)
        return n_steps

    def run(self) -> tuple[float, int]:
        """Midspan peak deflection [m] (z up: negative) and the number of beam analyses."""
        ops, h = self.ops, self.dt
        self.build()
        ops.pattern("Plain", 1, 1)
        n_steps = int(round(L / V / h))
        z, dz = -MV * G / KV, 0.0  # the unstretched spring carries the weight on the undeflected deck at entry
        ddz = 0.0
        force = MV * G
        mid, peak, analyses = N_ELEMENTS // 2 + 1, 0.0, 0
        for n in range(n_steps):
            t1 = (n + 1) * h
            e, shape = self._element(min(V * t1, L * (1 - 1e-12)))

            def vehicle(u_deck):  # Newmark average acceleration of the mass, given the deck at t_{n+1}
                a1 = (-MV * G + KV * (u_deck - (z + h * dz + 0.25 * h * h * ddz))) / (MV + 0.25 * h * h * KV)
                z1 = z + h * dz + 0.25 * h * h * (ddz + a1)
                return z1, dz + 0.5 * h * (ddz + a1), a1

            if self.coupling == "staggered":
                z_pred = z + h * dz + 0.5 * h * h * ddz
                self._apply(e, shape, KV * (self._deck(e, shape) - z_pred))
                ops.analyze(1, h)
                analyses += 1
                deck = self._deck(e, shape)
                z, dz, ddz = vehicle(deck)
                force = KV * (deck - z)
            else:
                snap = self._snapshot()
                t0 = ops.getTime()
                for it in range(50):
                    if it:
                        self._restore(snap, t0)
                    self._apply(e, shape, force)
                    ops.analyze(1, h)
                    analyses += 1
                    deck = self._deck(e, shape)
                    z1, dz1, a1 = vehicle(deck)
                    new = KV * (deck - z1)
                    done = abs(new - force) < 1e-8 * MV * G
                    force = new
                    if done:
                        break
                z, dz, ddz = z1, dz1, a1
            peak = min(peak, ops.nodeDisp(mid, 2))
        return peak, analyses


def cpu_per_call(fn, repeat: int, min_batch: float = 0.02):
    """Thread CPU time [s] of one call of ``fn``: after a warm-up call, ``repeat`` samples, each the
    mean over a batch of calls lasting at least ``min_batch`` s of CPU; the minimum sample (the
    machine is shared: other jobs only ever add time).  Also returns the last call's value."""
    out = fn()  # warm-up (numba's cache load for vbikit)
    t0 = time.thread_time()
    out = fn()
    batch = max(1, int(min_batch / max(time.thread_time() - t0, 1e-6)))
    samples = []
    for _ in range(max(1, repeat)):
        t0 = time.thread_time()
        for _ in range(batch):
            out = fn()
        samples.append((time.thread_time() - t0) / batch)
    return min(samples), out


#: the stages of a crossing timed by ``--stages`` (module, function; inclusive thread CPU per crossing)
STAGES = (("vbikit.solve.simulate", "plan_run"), ("vbikit.solve.plan", "choose_time_step"),
          ("vbikit.solve.system", "kernel_data"), ("vbikit.solve.tabulate", "_tabulate"),
          ("vbikit.solve.simulate", "integrate"), ("vbikit.solve.system", "static_state"),
          ("vbikit.solve.modal_step", "exact_step"), ("vbikit.solve.modal_step", "vehicle_step"),
          ("vbikit.solve.kernels", "lean"), ("vbikit.solve.kernels", "lean_quadratic"),  # (the default's: the wheel
          ("vbikit.solve.simulate", "check_finite"))  # loads held quadratic)


def stage_times(runs: dict, repeat: int) -> None:
    """Print the inclusive thread CPU time per crossing of each of ``STAGES`` in each of ``runs``
    (name: function running one crossing), the minimum over ``repeat`` rounds of 50 crossings (the
    functions are wrapped for the measurement: ≈ 1 µs a stage more)."""
    import importlib

    spent: dict[str, float] = {}
    originals = []
    for module_name, name in STAGES:
        module = importlib.import_module(module_name)
        original = getattr(module, name)
        originals.append((module, name, original))

        def timed(*a, _f=original, _name=name, **k):
            t0 = time.thread_time()
            try:
                return _f(*a, **k)
            finally:
                spent[_name] = spent.get(_name, 0.0) + time.thread_time() - t0

        setattr(module, name, timed)
    try:
        for label, fn in runs.items():
            fn()
            best: dict[str, float] = {}
            for _ in range(max(1, repeat)):
                spent.clear()
                t0 = time.thread_time()
                for _ in range(50):
                    fn()
                spent["whole"] = time.thread_time() - t0
                for key, value in spent.items():
                    best[key] = min(best.get(key, np.inf), value / 50)
            print(f"  stages, {label} [ms per crossing, inclusive]: "
                  + ", ".join(f"{k} {v * 1e3:.3f}" for k, v in sorted(best.items(), key=lambda kv: -kv[1])))
    finally:
        for module, name, original in originals:
            setattr(module, name, original)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=5, help="timed samples of each (default 5; the minimum is reported)")
    ap.add_argument("--stages", action="store_true", help="also time vbikit's stages of a crossing (STAGES)")
    args = ap.parse_args()

    from vbikit.analysis import point_response
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.solve import Crossing, kernels, simulate
    from vbikit.vehicle import sprung_mass

    def make() -> Crossing:
        return Crossing(EulerBernoulliBeam(L, E * I, M_BEAM, 0.0, n_modes=N_MODES), sprung_mass(MV, KV, 0.0),
                        speed=V, approach=0.0, free_vibration=0.0)

    same = make()

    def vbikit_fresh():  # a new model each run, as the OpenSees side builds its model each run
        res = simulate(make())
        return res.displacement(L / 2).min(), res

    def vbikit_again():  # the same Crossing again: its mode tables and checks are kept (a study's next run)
        res = simulate(same)
        return res.displacement(L / 2).min(), res

    print(f"Yang & Yau sprung mass, {V * 3.6:.0f} km/h, entry to exit; python {sys.version.split()[0]}, "
          f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f}; thread CPU time per crossing, "
          f"minimum of {args.repeat} samples")
    t_fresh, (peak_v, res) = cpu_per_call(vbikit_fresh, args.repeat)
    t_again, _ = cpu_per_call(vbikit_again, args.repeat)
    from _args import default_step_loops

    name = default_step_loops()[0]  # (the one-lane lean kernel's variant the default integrator runs)
    lean, loop = getattr(kernels, name), []

    def timed_lean(*a):
        t0 = time.thread_time()
        out = lean(*a)
        loop.append(time.thread_time() - t0)
        return out

    setattr(kernels, name, timed_lean)
    try:
        cpu_per_call(vbikit_again, args.repeat)
    finally:
        setattr(kernels, name, lean)
    t_loop = min(loop) if loop else float("nan")
    hermite_peak = point_response(res, L / 2).displacement_impact.dynamic_peak
    print(f"vbikit {res.crossing.integrator}, {N_MODES} modes, {res.n_steps} steps of {res.dt * 1e3:.2f} ms: "
          f"peak {-peak_v * 1e3:.4f} mm (between samples {-hermite_peak * 1e3:.4f} mm)")
    print(f"  new model each run {t_fresh * 1e3:.2f} ms; the same crossing again {t_again * 1e3:.2f} ms, "
          f"of which the step loop (kernels.{name}) {t_loop * 1e3:.2f} ms")
    if args.stages:
        stage_times({"new model": vbikit_fresh, "same crossing again": vbikit_again}, args.repeat)

    ops = load_opensees()
    ops.logFile(os.devnull, "-noEcho")
    rows = []
    for dt, label in ((DT_OPENSEES, f"dt {DT_OPENSEES * 1e3:g} ms"), (res.dt, f"vbikit's dt {res.dt * 1e3:.2f} ms")):
        floor_runner = OpenSeesVBI(ops, "floor", dt)
        t_floor, n_steps = cpu_per_call(floor_runner.floor, args.repeat)
        print(f"OpenSeesPy, {N_ELEMENTS} elements, Newmark, {label} ({n_steps} steps): beam alone, one analyze "
              f"call (floor) {t_floor * 1e3:.2f} ms -> vbikit {t_floor / t_fresh:.1f}x (new model) / "
              f"{t_floor / t_again:.1f}x (again)")
        for coupling in ("iterative", "staggered"):
            t_o, (peak_o, analyses) = cpu_per_call(OpenSeesVBI(ops, coupling, dt).run, args.repeat)
            rows.append((label, coupling, t_o))
            print(f"  {coupling}: {analyses} analyses, peak {-peak_o * 1e3:.4f} mm ({peak_o / peak_v - 1:+.2%} vs vbikit), "
                  f"{t_o * 1e3:.1f} ms -> vbikit {t_o / t_fresh:.1f}x (new model) / {t_o / t_again:.1f}x (again) faster")
    sys.stdout.flush()  # before OpenSees's own exit message
    return 0


if __name__ == "__main__":
    sys.exit(main())
