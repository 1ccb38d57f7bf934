#!/usr/bin/env python3
"""Mutation check: do the verification tests catch deliberate physics errors?

Each mutation is a list of edits (file, pattern, replacement) applied to a fresh temporary copy
of ``src/``, one mutation at a time; the tests (default: ``tests/verification``, ``tests/unit``
and ``tests/study/test_batch.py``, the lanes-vs-simulate check) then run against that copy
(``PYTHONPATH``), stopping at the first failure.  A
mutation is *caught* when a test fails.  A pattern that no longer matches the source (the code
moved on) is an error, reported before anything runs, so the list stays in step with the code.

    python tools/mutate.py                 # all mutations, table at the end (≈ 30 s each)
    python tools/mutate.py --list          # check every pattern and list the mutations
    python tools/mutate.py damping wheel   # only mutations whose name contains one of the words
    python tools/mutate.py --markdown      # the table as Markdown (docs/verification.md)

Exit status 0 only if every selected mutation is caught.  Unchanged files keep their numba
cache (the copy keeps modification times), so only a mutated kernel is recompiled.
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KERNELS = "src/vbikit/solve/kernels.py"
#: the tests run on each mutant, quick and discriminating ones first (pytest stops at the first failure)
DEFAULT_TESTS = ["tests/verification/test_independent_checks.py", "tests/verification/test_kernel_paths.py",
                 "tests/verification", "tests/unit", "tests/study/test_batch.py"]
SYSTEM = "src/vbikit/solve/system.py"
CROSSING = "src/vbikit/solve/crossing.py"
MODAL_STEP = "src/vbikit/solve/modal_step.py"
#: the exact modal step and Newmark's step map of each mode (modal_step.exact_step, newmark_step)
EXACT_ZETA = ("    zeta = np.asarray(zeta, float)\n    if np.any(omega <= 0)",
              "    zeta = 0.5 * np.asarray(zeta, float)\n    if np.any(omega <= 0)")
NEWMARK_ZETA = ("c, k = 2.0 * np.asarray(zeta, float) * omega", "c, k = 1.0 * np.asarray(zeta, float) * omega")


@dataclass(frozen=True)
class Edit:
    """Replace ``pattern`` (a regular expression; ``literal``: plain text) in ``file`` by
    ``replacement``; it must match exactly ``count`` times (None: at least once)."""

    file: str
    pattern: str
    replacement: str
    count: int | None = 1
    literal: bool = True

    def apply(self, text: str) -> str:
        pat = re.escape(self.pattern) if self.literal else self.pattern
        n = len(re.findall(pat, text))
        if n == 0 or (self.count is not None and n != self.count):
            want = "at least 1" if self.count is None else str(self.count)
            raise LookupError(f"{self.file}: pattern {self.pattern!r} matches {n} times, expected {want}")
        return re.sub(pat, self.replacement.replace("\\", "\\\\") if self.literal else self.replacement, text)


@dataclass(frozen=True)
class Mutation:
    name: str
    description: str
    edits: tuple[Edit, ...]


def M(name: str, description: str, *edits: Edit) -> Mutation:
    return Mutation(name, description, edits)


def K(pattern: str, replacement: str, count: int | None = 1) -> Edit:
    """An edit of the kernels (the default integrator's code)."""
    return Edit(KERNELS, pattern, replacement, count)


MUTATIONS: list[Mutation] = [
    # ---------------------------------------------------------------- damping
    M("damping-halved-everywhere", "modal damping 2ζω → ζω in every integrator (and the assembled matrices)",
      K("a = 2.0 * zeta[m] * omega[m]", "a = zeta[m] * omega[m]", count=None),
      K("damp[m, m] = 2.0 * zeta[m] * omega[m]", "damp[m, m] = zeta[m] * omega[m]"),
      Edit(MODAL_STEP, *EXACT_ZETA), Edit(MODAL_STEP, *NEWMARK_ZETA)),
    M("damping-halved-rk4", "modal damping halved in the RK4 right-hand side only",
      K("ddxi[m, lane] = -a * dxi[m, lane] - b * xi[m, lane]", "ddxi[m, lane] = -0.5 * a * dxi[m, lane] - b * xi[m, lane]")),
    M("damping-halved-exact", "modal damping halved in the exact modal step (the default integrator) only",
      Edit(MODAL_STEP, *EXACT_ZETA)),
    M("damping-halved-newmark", "modal damping halved in Newmark's step map only", Edit(MODAL_STEP, *NEWMARK_ZETA)),
    M("damping-ratios-ignored", "the bridge's damping ratios replaced by 0 in the kernel data",
      Edit(SYSTEM, "np.ascontiguousarray(bridge.damping_ratios, float)", "0.0 * np.ascontiguousarray(bridge.damping_ratios, float)")),
    # ---------------------------------------------------------------- coupled equations: bridge side
    M("modal-stiffness-omega", "modal stiffness ω² → ω·ω₁ (RK4, accelerations, assembly)",
      K("b = omega[m] * omega[m]", "b = omega[m] * omega[0]", count=None),
      K("stiff[m, m] = omega[m] * omega[m]", "stiff[m, m] = omega[m] * omega[0]")),
    M("modal-frequency-exact", "the exact step of every mode at 1.01 ω (the default integrator)",
      Edit(MODAL_STEP, "w, theta = omega, omega * h", "w, theta = 1.01 * omega, 1.01 * omega * h")),
    M("modal-load-sign", "sign of the contact forces on the bridge, −Σφ F → +Σφ F (everywhere)",
      K("_modal_load(-1.0,", "_modal_load(1.0,", count=None),
      K("load[a] -= f[a] * ext", "load[a] += f[a] * ext")),
    M("modal-load-factor", "contact forces on the bridge × 0.9 (everywhere)",
      K("_modal_load(-1.0,", "_modal_load(-0.9,", count=None),
      K("load[a] -= f[a] * ext", "load[a] -= 0.9 * f[a] * ext")),
    M("end-state-load-sign", "implicit step: the end-of-step modal load enters the deck state with the wrong sign",
      K("x1[m, lane] = xf[m, lane] + c1 * p[m, lane]", "x1[m, lane] = xf[m, lane] - c1 * p[m, lane]")),
    M("deck-displacement-sign", "deck displacement under a point enters with the wrong sign (one lane)",
      K("a += phi[p, m] * xi[m, 0]", "a -= phi[p, m] * xi[m, 0]")),
    M("deck-displacement-lanes", "deck displacement under a point left out (many lanes: a study batch)",
      K("_axpy(phi[p, m], xi, m, s, 0, lanes)", "pass")),
    M("deck-velocity-ignored", "deck velocity φ·ξ̇ left out of the tire dashpot (one lane)",
      K("b += phi[p, m] * dxi[m, 0]", "b += 0.0")),
    M("convective-sign", "sign of the convective deck rate v·φ'·ξ, everywhere",
      K("c += vx * dphi[p, m] * xi[m, 0]", "c -= vx * dphi[p, m] * xi[m, 0]"),
      K("_axpy(vx * dphi[p, m], xi, m, sd, 0, lanes)", "_axpy(-vx * dphi[p, m], xi, m, sd, 0, lanes)"),
      K("sd += vx * dphi[p, m] * xi[m, lane]", "sd -= vx * dphi[p, m] * xi[m, lane]"),
      K("stiff[a, b] += k * f[a] * f[b] + c * vel * f[a] * g[b]", "stiff[a, b] += k * f[a] * f[b] - c * vel * f[a] * g[b]"),
      K("stiff[n_m + j, a] -= k * h[j] * f[a] + c * vel * h[j] * g[a]",
        "stiff[n_m + j, a] -= k * h[j] * f[a] - c * vel * h[j] * g[a]")),
    M("convective-dropped", "convective deck rate v·φ'·ξ left out, everywhere",
      K("c += vx * dphi[p, m] * xi[m, 0]", "c += 0.0"),
      K("_axpy(vx * dphi[p, m], xi, m, sd, 0, lanes)", "pass"),
      K("sd += vx * dphi[p, m] * xi[m, lane]", "sd += 0.0"),
      K("stiff[a, b] += k * f[a] * f[b] + c * vel * f[a] * g[b]", "stiff[a, b] += k * f[a] * f[b]"),
      K("stiff[n_m + j, a] -= k * h[j] * f[a] + c * vel * h[j] * g[a]", "stiff[n_m + j, a] -= k * h[j] * f[a]")),
    # ---------------------------------------------------------------- coupled equations: vehicle side
    M("wheel-force-sign", "tire forces on the vehicle with the wrong sign (every integrator)",
      K("_gemv(1.0, vehicles.wheel_rows, wheel_force, rhs, lanes, True)", "_gemv(-1.0, vehicles.wheel_rows, wheel_force, rhs, lanes, True)"),
      K("_gemv(1.0, vehicles.wheel_rows, g, rhs, lanes, True)", "_gemv(-1.0, vehicles.wheel_rows, g, rhs, lanes, True)"),
      Edit(MODAL_STEP, "a[n_d:2 * n_d, 2 * n_d:2 * n_d + n_w] = m_inv @ rows.T", "a[n_d:2 * n_d, 2 * n_d:2 * n_d + n_w] = -m_inv @ rows.T")),
    M("tire-load-sign", "implicit step: the nominal tire's part of the wheel load added with the wrong sign",
      K("out[w, lane] += h * (kw * q[j, lane] + cw * dq[j, lane])", "out[w, lane] -= h * (kw * q[j, lane] + cw * dq[j, lane])")),
    M("vehicle-damping-sign", "vehicle damping C_v with the wrong sign (every integrator)",
      K("_gemv(-1.0, vehicles.damping, dq, rhs, lanes, False)", "_gemv(1.0, vehicles.damping, dq, rhs, lanes, False)"),
      Edit(MODAL_STEP, "c_hat = vehicles.damping + rows.T", "c_hat = -vehicles.damping + rows.T")),
    M("vehicle-stiffness-factor", "vehicle stiffness K_v × 0.9 (every integrator)",
      K("_gemv(-1.0, vehicles.stiffness, q, rhs, lanes, False)", "_gemv(-0.9, vehicles.stiffness, q, rhs, lanes, False)"),
      Edit(MODAL_STEP, "k_hat = vehicles.stiffness + rows.T", "k_hat = 0.9 * vehicles.stiffness + rows.T")),
    M("gravity-factor", "gravity load F_G × 0.99 in the time stepping (every integrator; the static start keeps it)",
      K("rhs[i, lane] = vehicles.gravity[i]", "rhs[i, lane] = 0.99 * vehicles.gravity[i]", count=None),
      Edit(MODAL_STEP, "a[n_d:2 * n_d, -1] = m_inv @ vehicles.gravity", "a[n_d:2 * n_d, -1] = 0.99 * m_inv @ vehicles.gravity"),
      Edit(MODAL_STEP, "vehicles.gravity.reshape(n_d, 1))[:, 0]", "0.99 * vehicles.gravity.reshape(n_d, 1))[:, 0]")),
    M("vehicle-mass-factor", "vehicle mass 5 % off in the time stepping (every integrator)",
      K("_gemv(1.0, vehicles.mass_inv, rhs, ddq, lanes, False)", "_gemv(0.95, vehicles.mass_inv, rhs, ddq, lanes, False)"),
      Edit(MODAL_STEP, "m_inv, rows = vehicles.mass_inv, vehicles.wheel_rows", "m_inv, rows = 0.95 * vehicles.mass_inv, vehicles.wheel_rows"),
      Edit(MODAL_STEP, "s_inv = np.linalg.inv(vehicles.mass + ", "s_inv = np.linalg.inv(1.05 * vehicles.mass + ")),
    M("coupling-stiffness-sign", "bridge–vehicle stiffness coupling K_bv with the wrong sign (Newmark)",
      K("stiff[a, n_m + j] -= k * f[a] * h[j]", "stiff[a, n_m + j] += k * f[a] * h[j]")),
    # ---------------------------------------------------------------- tire force law
    M("tire-spring-factor", "tire spring k·δ × 1.1 (the contact law)",
      K("f = k * pen + c * rate + f0", "f = 1.1 * k * pen + c * rate + f0")),
    M("tire-dashpot-dropped", "tire dashpot c·δ̇ left out (the contact law)",
      K("f = k * pen + c * rate + f0", "f = k * pen + f0")),
    M("tire-dashpot-wheel-sign", "wheel velocity enters the dashpot with the wrong sign",
      K("sd[0, lane] + dr[0, lane] - dzw[lane]", "sd[0, lane] + dr[0, lane] + dzw[lane]")),
    M("fixed-load-dropped", "fixed (moving-force) load f0 left out (the contact law)",
      K("f = k * pen + c * rate + f0", "f = k * pen + c * rate")),
    M("gap-sign", "disk gaps g_p added instead of subtracted (penetration)",
      K("s[0, lane] - g - zw[lane]", "s[0, lane] + g - zw[lane]")),
    M("loss-of-contact-tension", "a gated point may pull (f > 0 condition dropped)",
      K("return f if not gate or (pen > 0.0 and f > 0.0) else 0.0", "return f if not gate or pen > 0.0 else 0.0")),
    M("loss-of-contact-ignored-kernel", "loss of contact ignored for point / multipoint tires (kernel)",
      K("gate = points.gated[p] or (unilateral and points.stiffness[p] > 0.0)", "gate = points.gated[p]")),
    M("loss-of-contact-ignored-scenario", "the scenario's tire.loss_of_contact ignored (always true)",
      Edit("src/vbikit/scenario/build.py", "loss_of_contact=scenario.tire.loss_of_contact", "loss_of_contact=True",
           count=None)),
    M("multipoint-weights", "multipoint: each point carries k/(n+1) instead of k/n",
      Edit("src/vbikit/contact/tires.py", "return offsets, np.full(n, 1.0 / n)", "return offsets, np.full(n, 1.0 / (n + 1))")),
    M("multipoint-layout", "multipoint: points over twice the contact length",
      Edit("src/vbikit/contact/tires.py", "offsets = np.linspace(-a / 2, a / 2, n)", "offsets = np.linspace(-a, a, n)")),
    M("disk-calibration", "disk: static compression 1.5 F/k → 1.2 F/k",
      Edit("src/vbikit/contact/tires.py", "return 1.5 * static_load / stiffness", "return 1.2 * static_load / stiffness")),
    M("disk-damping", "disk: damping per length without the factor 2 (c/√(2R d) instead of c/(2√(2R d)))",
      Edit("src/vbikit/contact/tires.py", "c_xi = damping / (2.0 * np.sqrt(2 * self.radius * d_s))",
           "c_xi = damping / np.sqrt(2 * self.radius * d_s)")),
    M("disk-gaps", "disk: gaps of a circle of radius 2R",
      Edit("src/vbikit/contact/tires.py", "gaps = radius - np.sqrt(np.clip(radius**2 - offsets**2, 0.0, None))",
           "gaps = 2 * radius - np.sqrt(np.clip(4 * radius**2 - offsets**2, 0.0, None))")),
    M("rigid-disk-first-point", "rigid disk acts through its first point instead of its highest one",
      K("if s - points.gap[p] > s_env:", "if p_env < 0:")),
    M("rigid-disk-slope-unclamped", "rigid disk: contact rate not clamped to the circle's slopes",
      K("sd_env = deck_rate + min(max(sd, v * points.slope_range[p, 0]), v * points.slope_range[p, 1])",
        "sd_env = deck_rate + sd")),
    # ---------------------------------------------------------------- mode shapes and normalisation
    M("beam-normalisation", "beam modes normalised to √(1/mL) instead of √(2/mL)",
      Edit("src/vbikit/bridge/beam.py", "return float(np.sqrt(2.0 / (self.mass_per_length * self.span)))",
           "return float(np.sqrt(1.0 / (self.mass_per_length * self.span)))")),
    M("deck-normalisation", "slab-on-girder modes scaled by 1/1.1 after mass normalisation",
      Edit("src/vbikit/bridge/girder_deck.py", "vec = vec / norms", "vec = vec / (1.1 * norms)")),
    M("hermite-slope", "mode-shape table: slope term of the cubic Hermite interpolation halved",
      K("phi_row[m] = h00 * a0 + h10 * b0 + h01 * a1 + h11 * b1", "phi_row[m] = h00 * a0 + 0.5 * h10 * b0 + h01 * a1 + h11 * b1")),
    # ---------------------------------------------------------------- wheel lines
    M("wheel-lines-swapped", "left and right wheel lines swapped (y > 0 follows the right profile)",
      Edit(SYSTEM, "(contact.lateral < 0.0).astype(np.int64)", "(contact.lateral > 0.0).astype(np.int64)")),
    M("lateral-mirrored", "wheel tracks mirrored on the deck (y → −y)",
      Edit(CROSSING, "np.ones(cp.n), cp.lateral + self.lateral_offset", "np.ones(cp.n), -(cp.lateral + self.lateral_offset)"),
      Edit(CROSSING, "return origin, sign, offset + sign * cp.lateral", "return origin, sign, -(offset + sign * cp.lateral)")),
    M("lateral-offset-ignored", "the vehicles' lateral offsets ignored on the deck",
      Edit(CROSSING, "np.ones(cp.n), cp.lateral + self.lateral_offset", "np.ones(cp.n), cp.lateral + 0.0 * self.lateral_offset"),
      Edit(CROSSING, "return origin, sign, offset + sign * cp.lateral", "return origin, sign, 0.0 * offset + sign * cp.lateral")),
    # ---------------------------------------------------------------- initial state
    M("static-start-flat", "static start ignores the road under the wheels",
      Edit("src/vbikit/solve/simulate.py", "static_state(crossing, data, road0[:, lane],",
           "static_state(crossing, data, 0.0 * road0[:, lane],")),
    M("static-start-no-rate", "static start ignores the road rate under the moving wheels",
      Edit("src/vbikit/solve/simulate.py", "road_rate=rate0[:, lane],", "road_rate=None,")),
    M("static-start-no-deck", "static start ignores the deck (ξ(0) = 0)",
      Edit(SYSTEM, "return u[:n_m], u[n_m:], active", "return 0.0 * u[:n_m], u[n_m:], active")),
    # ---------------------------------------------------------------- static reference, IM, strain
    M("static-reference-omega", "static reference −Σφ P/ω² → −Σφ P/(1.02 ω²)",
      Edit(SYSTEM, "return -force / crossing.bridge.omega**2", "return -force / (1.02 * crossing.bridge.omega**2)")),
    M("static-reference-shares", "static reference: every contact point carries the whole wheel load",
      Edit(SYSTEM, "loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]",
           "loads = crossing.vehicle.static_wheel_loads()[cp.wheel]")),
    M("impact-factor-formula", "IM = (R_dyn − R_st)/R_dyn instead of /R_st",
      Edit("src/vbikit/analysis/impact.py", "(sign * r_dyn - sign * r_st) / (sign * r_st)",
           "(sign * r_dyn - sign * r_st) / (sign * r_dyn)")),
    M("strain-lever-beam", "beam strain lever arm c → c/2",
      Edit("src/vbikit/bridge/beam.py", "return -self.neutral_axis_depth * self.wavenumbers**2",
           "return -0.5 * self.neutral_axis_depth * self.wavenumbers**2")),
    M("strain-lever-deck", "girder strain lever arm c → 0.9 c",
      Edit("src/vbikit/bridge/girder_deck.py", 'out["c"][j] = comp.neutral_axis_depth', 'out["c"][j] = 0.9 * comp.neutral_axis_depth')),
    # ---------------------------------------------------------------- road
    M("road-interpolation-step", "road read as a staircase (elevation of the station behind)",
      K("rv[p, lane] = z[i, lane] + slope * dx", "rv[p, lane] = z[i, lane]")),
    M("road-interpolation-shift", "road interpolated from the wrong end of the segment",
      K("dx = x - stations[i]", "dx = stations[i + 1] - x")),
    M("road-rate-dropped", "road rate v·r' left out of the tire dashpot",
      K("rr[p, lane] = slope * vx", "rr[p, lane] = 0.0")),
    M("road-psd-amplitude", "road harmonics √(2φΔn) → √(φΔn)",
      Edit("src/vbikit/road/psd.py", "amp = np.sqrt(2.0 * psd(n_k) / period)", "amp = np.sqrt(psd(n_k) / period)")),
]


def mutated_tree(mutation: Mutation, dest: Path) -> None:
    """Copy src/ to ``dest`` (keeping modification times: numba caches of unchanged files stay valid)
    and apply the mutation's edits there."""
    shutil.copytree(ROOT / "src", dest / "src", copy_function=shutil.copy2, symlinks=True)
    texts: dict[str, str] = {}
    for edit in mutation.edits:
        path = dest / edit.file
        texts[edit.file] = edit.apply(texts.get(edit.file, path.read_text()))
    for file, text in texts.items():
        (dest / file).write_text(text)


def check_patterns(mutations: list[Mutation]) -> list[str]:
    """Every edit must match the current source (applied in order per mutation)."""
    errors = []
    for mut in mutations:
        texts: dict[str, str] = {}
        for edit in mut.edits:
            try:
                texts[edit.file] = edit.apply(texts.get(edit.file, (ROOT / edit.file).read_text()))
            except LookupError as err:
                errors.append(f"{mut.name}: {err}")
    return errors


def run_tests(src: Path, tests: list[str], timeout: float) -> tuple[int, str, float]:
    """Run ``tests`` (paths under the repository) importing vbikit from ``src``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(src) + os.pathsep + env.get("PYTHONPATH", "")
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "--no-header", "-rfE", *tests]
    t0 = time.perf_counter()
    try:
        res = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return -1, "timeout", time.perf_counter() - t0
    out = res.stdout.strip().splitlines()
    failed = next((line.split()[1] for line in out if line.startswith("FAILED") or line.startswith("ERROR")), "")
    if not failed:
        failed = next((line for line in reversed(out) if "::" in line), out[-1] if out else "")
    return res.returncode, failed, time.perf_counter() - t0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("select", nargs="*", help="only mutations whose name contains one of these words")
    ap.add_argument("--tests", nargs="+", default=DEFAULT_TESTS, help="test paths to run")
    ap.add_argument("--list", action="store_true", help="check the patterns and list the mutations, run nothing")
    ap.add_argument("--markdown", action="store_true", help="print the result table as Markdown")
    ap.add_argument("--timeout", type=float, default=1200.0, help="seconds per mutation run")
    ap.add_argument("--no-baseline", action="store_true", help="skip the run on the unmutated source")
    args = ap.parse_args(argv)
    chosen = [m for m in MUTATIONS if not args.select or any(w in m.name for w in args.select)]
    names = [m.name for m in MUTATIONS]
    if len(set(names)) != len(names):
        print("duplicate mutation names", file=sys.stderr)
        return 2
    errors = check_patterns(chosen)
    if errors:
        print("PATTERNS NO LONGER MATCH THE SOURCE (update tools/mutate.py):", file=sys.stderr)
        for e in errors:
            print("  " + e, file=sys.stderr)
        return 2
    if args.list:
        for m in chosen:
            print(f"{m.name:36s} {m.description}")
        return 0
    if not args.no_baseline:
        rc, first, sec = run_tests(ROOT / "src", args.tests, args.timeout)
        if rc != 0:
            print(f"the unmutated source fails the tests ({first}); fix that first", file=sys.stderr)
            return 2
        print(f"baseline: tests pass ({sec:.0f} s)", flush=True)
    rows = []
    for m in chosen:
        with tempfile.TemporaryDirectory(prefix="vbikit-mutant-") as tmp:
            mutated_tree(m, Path(tmp))
            rc, first, sec = run_tests(Path(tmp) / "src", args.tests, args.timeout)
        status = {0: "NOT CAUGHT", 1: "caught", -1: "timeout"}.get(rc, f"error (exit {rc})")
        rows.append((m, status, first, sec))
        print(f"{status:12s} {m.name:36s} {sec:5.0f} s  {first}", flush=True)
    caught = sum(status == "caught" for _, status, _, _ in rows)
    print(f"\n{caught} of {len(rows)} mutations caught")
    if args.markdown:
        print("\n| mutation | what it changes | result | first failing test |\n|---|---|---|---|")
        for m, status, first, _ in rows:
            print(f"| `{m.name}` | {m.description} | {status} | `{first.split('::')[-1] if first else ''}` |")
    return 0 if caught == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
