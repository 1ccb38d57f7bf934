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
    python tools/mutate.py --new --only-targeted   # the models added since the paper, each against its own tests

A mutation may name the tests expected to catch it; they run first, then ``--tests``.

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
KERNELS = "src/vbikit/solve/kernels"  # the kernels' package: K() finds the module of each pattern
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
    """``tests``: the test files expected to catch it, run before the others (pytest stops at the
    first failure, so a caught mutation costs only its own tests)."""

    name: str
    description: str
    edits: tuple[Edit, ...]
    tests: tuple[str, ...] = ()


def M(name: str, description: str, *edits: Edit | tuple[Edit, ...]) -> Mutation:
    return Mutation(name, description, _flat(edits))


def N(name: str, description: str, tests: tuple[str, ...], *edits: Edit | tuple[Edit, ...]) -> Mutation:
    """A mutation of a model added since the paper, with the physics tests that should catch it."""
    return Mutation(name, description, _flat(edits), tests)


def K(pattern: str, replacement: str, count: int | None = 1) -> tuple[Edit, ...]:
    """Edits of the kernels (the default integrator's code): of the module of the kernels' package
    that holds ``pattern`` (``count`` times there), or with ``count=None`` of every module that does."""
    files = sorted(str(p.relative_to(ROOT)) for p in (ROOT / KERNELS).glob("*.py") if pattern in p.read_text())
    if count is not None or not files:
        return (Edit(files[0] if len(files) == 1 else KERNELS + "/__init__.py", pattern, replacement, count),)
    return tuple(Edit(f, pattern, replacement, None) for f in files)


def _flat(edits: tuple) -> tuple[Edit, ...]:
    """``edits`` with K()'s tuples spliced in."""
    return tuple(e for x in edits for e in (x if isinstance(x, tuple) else (x,)))


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
      Edit(MODAL_STEP, "m_inv, rows = vehicles.mass_inv, vehicles.wheel_rows", "m_inv, rows = 0.95 * vehicles.mass_inv, vehicles.wheel_rows",
           count=None),
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
      Edit(CROSSING, "return origin, sign, offset + sign * cp.lateral", "return origin, sign, -(offset + sign * cp.lateral)")),
    M("lateral-offset-ignored", "the vehicles' lateral offsets ignored on the deck",
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


# ====================================================================== models added since the paper
CONT = "src/vbikit/bridge/continuous.py"
DAMAGE = "src/vbikit/bridge/damage.py"
DECK_EFFECTS = "src/vbikit/bridge/deck_effects.py"
EFFECTS = "src/vbikit/analysis/effects.py"
CODES = "src/vbikit/analysis/codes.py"
EVENTS = "src/vbikit/traffic/events.py"
TRAFFIC = "src/vbikit/traffic/study.py"
RECORDS = "src/vbikit/traffic/records.py"
AXLES = "src/vbikit/vehicle/axles.py"
FIELD = "src/vbikit/field/workflow.py"
FIELD_IO = "src/vbikit/field/io.py"
V = "tests/verification/"
T_CONT = (V + "test_continuous_general.py", V + "test_continuous_modal_values.py", V + "test_continuous_beam.py")
T_DAMAGE = (V + "test_continuous_general.py", V + "test_deck_damage_inside_elements.py", V + "test_deck_damage_and_effects.py")
T_DECK = (V + "test_deck_load_effects_element.py", V + "test_deck_damage_and_effects.py", V + "test_load_effects.py", V + "test_opensees_deck_effects.py")
T_EFFECTS = (V + "test_tire_load_effects.py", V + "test_continuous_general.py", V + "test_load_effects.py",
             V + "test_axle_truck_damping_and_codes.py")
T_CODES = (V + "test_axle_truck_damping_and_codes.py", "tests/unit/test_codes.py")
T_TRAFFIC = (V + "test_traffic_events_partition.py", V + "test_traffic_on_deck.py", "tests/traffic/test_records_events.py", "tests/traffic/test_traffic_study.py")
T_AXLES = (V + "test_axle_truck_damping_and_codes.py", "tests/unit/test_axles.py")
T_FIELD = (V + "test_field_calibration.py", "tests/field/test_synthetic_truth.py")

NEW_MUTATIONS: list[Mutation] = [
    # ---------------------------------------------------------------- continuous beam
    N("cont-EI-spans-reversed", "continuous beam: per-span EI taken in reverse span order", T_CONT,
      Edit(CONT, "EI = np.asarray(self.EI)[k].astype(float)", "EI = np.asarray(self.EI)[::-1][k].astype(float)")),
    N("cont-mass-spans-reversed", "continuous beam: per-span mass taken in reverse span order", T_CONT,
      Edit(CONT, "return EI, np.asarray(self.mass_per_length)[k].astype(float)",
           "return EI, np.asarray(self.mass_per_length)[::-1][k].astype(float)")),
    N("cont-span-of-element", "continuous beam: an element's span index one too high (clipped)", T_CONT,
      Edit(CONT, 'k = np.clip(np.searchsorted(self.support_x, mid, side="right") - 1, 0, len(self.spans) - 1)',
           'k = np.clip(np.searchsorted(self.support_x, mid, side="right"), 0, len(self.spans) - 1)')),
    N("cont-rotational-ends-swapped", "continuous beam: entry and exit rotational springs swapped", T_CONT,
      Edit(CONT, "for end, k in zip((0, -1), self.rotational_stiffness):", "for end, k in zip((-1, 0), self.rotational_stiffness):")),
    N("cont-support-springs-reversed", "continuous beam: support stiffnesses in reverse support order", T_CONT,
      Edit(CONT, "zip(node_of, self.support_stiffness, self.support_x)", "zip(node_of, self.support_stiffness[::-1], self.support_x)")),
    N("cont-couple-on-deflection", "continuous beam: rotational spring on the deflection DOF", T_CONT,
      Edit(CONT, 'out.append(("couple", 2 * int(node_of[end]) + 1, k,', 'out.append(("couple", 2 * int(node_of[end]), k,')),
    N("cont-spring-reaction-sign", "continuous beam: spring support reaction field +k u instead of −k u", T_CONT,
      Edit(CONT, "z[free, a] = -k * lu.solve(e)", "z[free, a] = k * lu.solve(e)")),
    N("cont-spring-modal-sign", "continuous beam: spring support modal reaction +k φ instead of −k φ", T_CONT,
      Edit(CONT, "modal[a] = -k * full[dof]", "modal[a] = k * full[dof]")),
    N("cont-rigid-modal-inertia-sign", "continuous beam: rigid support modal reaction K φ + ω² M φ", T_CONT,
      Edit(CONT, "modal[a] = Kphi[dof] - omega**2 * Mphi[dof]", "modal[a] = Kphi[dof] + omega**2 * Mphi[dof]")),
    N("cont-couple-moment-sign", "continuous beam: the end spring's couple enters the moment with + sign", T_CONT,
      Edit(CONT, "comb[a] = -1.0", "comb[a] = 1.0")),
    N("cont-moment-arm-sign", "continuous beam: lever arm of a support reaction x_j − s instead of s − x_j", T_CONT,
      Edit(CONT, "comb[a] = s - xa", "comb[a] = xa - s")),
    N("cont-shear-section-exclusive", "continuous beam: a support at the section not counted left of it (shear)", T_CONT,
      Edit(CONT, 'elif what == "force" and xa <= s + tol:', 'elif what == "force" and xa < s - tol:')),
    N("cont-inertia-arm-sign", "continuous beam: inertia moment arm x − s instead of s − x", T_CONT,
      Edit(CONT, "moment += (wq * (s - xq)) @ phi", "moment += (wq * (xq - s)) @ phi")),
    N("cont-inertia-force-sign", "continuous beam: modal shear's inertia term with the wrong sign", T_CONT,
      Edit(CONT, "modal = comb @ modal_actions + omega**2 * force_int", "modal = comb @ modal_actions - omega**2 * force_int")),
    N("cont-mass-normalisation", "continuous beam: modes normalised to φᵀMφ = 2 instead of 1", T_CONT,
      Edit(CONT, 'vec = vec / np.sqrt(np.einsum("im,im->m", vec, Mf @ vec))', 'vec = vec / np.sqrt(0.5 * np.einsum("im,im->m", vec, Mf @ vec))')),
    N("cont-load-vector-node-shift", "continuous beam: a point load assembled on the next element's DOFs", T_CONT,
      Edit(CONT, "F[2 * e:2 * e + 4] += f * np.array([float(v) for v in n])",
           "F[2 * e + 2:2 * e + 6] += f * np.array([float(v) for v in n])[:F[2 * e + 2:2 * e + 6].size]")),
    N("cont-damage-end-not-a-node", "continuous beam: the end of a damaged region is not made a node", T_DAMAGE,
      Edit(CONT, "pts.append(np.array([d.position, min(d.end, self.span)]))", "pts.append(np.array([d.position]))")),
    # ---------------------------------------------------------------- damage
    N("damage-fraction-not-divided", "damage: EI loss × overlap [m] instead of × overlap / element length", T_DAMAGE,
      Edit(DAMAGE, "factor -= d.severity * d.overlap(a, b) / (b - a)", "factor -= d.severity * d.overlap(a, b)")),
    N("damage-overlap-min-max", "damage: overlap measured from min(a, start) instead of max(a, start)", T_DAMAGE,
      Edit(DAMAGE, "return max(0.0, min(b, self.end) - max(a, self.position))",
           "return max(0.0, min(b, self.end) - min(a, self.position))")),
    N("damage-end-half-length", "damage: the region ends at position + length/2", T_DAMAGE,
      Edit(DAMAGE, "return self.position + self.length", "return self.position + 0.5 * self.length")),
    # ---------------------------------------------------------------- deck load effects
    N("deck-moment-row-couple-sign", "deck: girder moment from the element's end couple with + sign", T_DECK,
      Edit(DECK_EFFECTS, 'row = (s - a) * ke[0] - ke[1] if kind == "moment" else ke[0]',
           'row = (s - a) * ke[0] + ke[1] if kind == "moment" else ke[0]')),
    N("deck-moment-modal-sign", "deck: modal girder moment −EI φ'' instead of EI φ''", T_DECK,
      Edit(DECK_EFFECTS, "modal = EI * modes.line_values(np.array([s]), 2)[j, 0]", "modal = -EI * modes.line_values(np.array([s]), 2)[j, 0]")),
    N("deck-shear-inertia-arm", "deck: modal shear's inertia term about the element start instead of its middle", T_DECK,
      Edit(DECK_EFFECTS, "omega**2 * m_line * phi * (s - 0.5 * (a + b))", "omega**2 * m_line * phi * (s - a)")),
    N("deck-reaction-inertia-sign", "deck: rigid bearing modal reaction K φ + ω² M φ", T_DECK,
      Edit(DECK_EFFECTS, "modal = (K @ full)[d] - omega**2 * (M @ full)[d]", "modal = (K @ full)[d] + omega**2 * (M @ full)[d]")),
    N("deck-local-moment-arm-sign", "deck: a load inside the section's element adds x − s instead of s − x", T_DECK,
      Edit(DECK_EFFECTS, "np.where(xi < s, s - xi, 0.0)", "np.where(xi < s, xi - s, 0.0)")),
    N("deck-local-share-girder", "deck: a load inside the section's element uses girder 1's share", T_DECK,
      Edit(DECK_EFFECTS, "c = shares[inside, j]", "c = shares[inside, 0]")),
    # ---------------------------------------------------------------- load effects (mode acceleration)
    N("effects-damping-correction-half", "mode acceleration: damping term ζω ξ̇ instead of 2ζω ξ̇", T_EFFECTS,
      Edit(EFFECTS, "result.xi_dot * (2.0 * zeta * omega)", "result.xi_dot * (1.0 * zeta * omega)")),
    N("effects-correction-sign", "mode acceleration: dynamic correction added instead of subtracted", T_EFFECTS,
      Edit(EFFECTS, 'dynamic = -np.einsum("tp,tp->t", infl, dyn_forces) - correction',
           'dynamic = -np.einsum("tp,tp->t", infl, dyn_forces) + correction')),
    N("effects-static-shares-dropped", "load effects: static reference with every contact point carrying the whole wheel", T_EFFECTS,
      Edit(EFFECTS, "static_loads = share * result.crossing.vehicle.static_wheel_loads()[cp.wheel]",
           "static_loads = result.crossing.vehicle.static_wheel_loads()[cp.wheel]")),
    N("effects-dynamic-shares-dropped", "load effects: dynamic wheel force not spread by the static shares", T_EFFECTS,
      Edit(EFFECTS, "dyn_forces = result.wheel_forces[:, cp.wheel] * share[None, :]", "dyn_forces = result.wheel_forces[:, cp.wheel]")),
    N("effects-path-direction-sign", "load effects: contact points move against their direction", T_EFFECTS,
      Edit(EFFECTS, "x = origin[None, :] + direction[None, :] * s[:, crossing.point_vehicle]",
           "x = origin[None, :] - direction[None, :] * s[:, crossing.point_vehicle]")),
    N("effects-axle-count-wheels", "code allowances: axles counted as wheels", T_EFFECTS,
      Edit(EFFECTS, "return len({round(float(w.offset), 3) for w in vehicle.wheels})", "return len(vehicle.wheels)")),
    N("effects-loaded-length-first-span", "code allowances: the loaded length always the first span", T_EFFECTS,
      Edit(EFFECTS, "return float(spans[bridge.span_index(float(bridge.span_coordinate(x, y)))])", "return float(spans[0])")),
    # ---------------------------------------------------------------- design codes
    N("codes-aashto-metres", "AASHTO Standard: L in m instead of ft", T_CODES,
      Edit(CODES, "min(50.0 / (loaded_length * FT_PER_M + 125.0), 0.30)", "min(50.0 / (loaded_length + 125.0), 0.30)")),
    N("codes-ohbdc-rise-slope", "OHBDC: rising branch over 2.5 Hz instead of 1.5 Hz", T_CODES,
      Edit(CODES, "return 0.20 + 0.20 * (f - 1.0) / 1.5", "return 0.20 + 0.20 * (f - 1.0) / 2.5")),
    N("codes-ohbdc-fall-start", "OHBDC: falling branch measured from 4.0 Hz", T_CODES,
      Edit(CODES, "return 0.40 - 0.20 * (f - 4.5) / 1.5", "return 0.40 - 0.20 * (f - 4.0) / 1.5")),
    N("codes-ohbdc-plateau-end", "OHBDC: plateau ends at 4.0 Hz", T_CODES,
      Edit(CODES, "    if f <= 4.5:\n        return 0.40", "    if f <= 4.0:\n        return 0.40")),
    N("codes-jtg-log10", "JTG: log10 instead of the natural logarithm", T_CODES,
      Edit(CODES, "return 0.1767 * math.log(f) - 0.0157", "return 0.1767 * math.log10(f) - 0.0157")),
    N("codes-jtg-low-breakpoint", "JTG: the 0.05 floor below 1.0 Hz instead of 1.5 Hz", T_CODES,
      Edit(CODES, "    if f < 1.5:\n        return 0.05", "    if f < 1.0:\n        return 0.05")),
    N("codes-csa-axle-index", "CSA S6: 0.30 for three axles instead of two", T_CODES,
      Edit(CODES, "0.30 if n_axles == 2 or cl_w_front_axles", "0.30 if n_axles == 3 or cl_w_front_axles")),
    N("codes-ohbdc-swapped-argument", "code allowances: OHBDC given the loaded length instead of the frequency", T_CODES,
      Edit(CODES, '"ohbdc_1983": ohbdc_1983(first_frequency),', '"ohbdc_1983": ohbdc_1983(loaded_length),')),
    # ---------------------------------------------------------------- traffic
    N("events-length-ignored", "traffic events: a vehicle leaves when its front axle does (length ignored)", T_TRAFFIC,
      Edit(EVENTS, "t + (float(span) + float(reach) + np.asarray(lengths, float)) / v", "t + (float(span) + float(reach)) / v")),
    N("events-end-not-max", "traffic events: an event ends when its latest member leaves, not its last", T_TRAFFIC,
      Edit(EVENTS, "t1 = max(t1, end[i])", "t1 = end[i]")),
    N("traffic-entry-time-absolute", "traffic: vehicles enter at their record time, not relative to the event", T_TRAFFIC,
      Edit(TRAFFIC, "entry_time=r.time - t0,", "entry_time=r.time,")),
    N("traffic-lane-index", "traffic: lane n placed at lanes[−n] instead of lanes[n − 1]", T_TRAFFIC,
      Edit(TRAFFIC, "else self.lanes[r.lane - 1]\n            motions", "else self.lanes[-r.lane]\n            motions")),
    N("traffic-default-lanes-mirrored", "traffic: default lane 1 at y > 0", T_TRAFFIC,
      Edit(TRAFFIC, "return (-float(width) / 4.0, float(width) / 4.0)", "return (float(width) / 4.0, -float(width) / 4.0)")),
    N("traffic-vehicle-wheels-off-by-one", "traffic: a vehicle's outputs include the next vehicle's first wheel", T_TRAFFIC,
      Edit(TRAFFIC, "f = forces[:, offsets[j]:offsets[j + 1]]", "f = forces[:, offsets[j]:offsets[j + 1] + 1]")),
    N("records-kmh-factor", "traffic records: km/h converted with 1/3", T_TRAFFIC,
      Edit(RECORDS, '"speed": {"km/h": 1 / 3.6, "m/s": 1.0},', '"speed": {"km/h": 1 / 3.0, "m/s": 1.0},')),
    N("records-kN-factor", "traffic records: kN read as 100 N", T_TRAFFIC,
      Edit(RECORDS, '"axle_loads": {"kN": 1e3, "N": 1.0},', '"axle_loads": {"kN": 1e2, "N": 1.0},')),
    # ---------------------------------------------------------------- trucks from axle records
    N("axles-tire-damping-mass", "axle truck: tire damper from √(k m_u) instead of √(k m_u/2)", T_AXLES,
      Edit(AXLES, "c_t = 2 * tire_damping_ratio * math.sqrt(k_t * 0.5 * masses[i])", "c_t = 2 * tire_damping_ratio * math.sqrt(k_t * masses[i])")),
    N("axles-suspension-damping-load", "axle truck: suspension damper from the whole axle's sprung load", T_AXLES,
      Edit(AXLES, "c_s = 2 * suspension_damping_ratio * math.sqrt(k_s * 0.5 * sprung[i] / GRAVITY) if suspension else 0.0",
           "c_s = 2 * suspension_damping_ratio * math.sqrt(k_s * sprung[i] / GRAVITY) if suspension else 0.0")),
    N("axles-bogie-damping-load", "axle truck: walking-beam suspension damper from the whole group's load", T_AXLES,
      Edit(AXLES, "c_s = 2 * suspension_damping_ratio * math.sqrt(k_s * 0.5 * p / GRAVITY)",
           "c_s = 2 * suspension_damping_ratio * math.sqrt(k_s * p / GRAVITY)")),
    N("axles-tire-stiffness-axle", "axle truck: each tire sized for the whole axle load", T_AXLES,
      Edit(AXLES, "k_t = 0.5 * loads[i] / tire_deflection", "k_t = loads[i] / tire_deflection")),
    N("axles-dampers-swapped", "axle truck: suspension and tire dampers swapped (arguments)", T_AXLES,
      Edit(AXLES, "return AxleSpec(float(s_axle[i]), float(masses[i]), k_s, c_s, k_t, c_t)",
           "return AxleSpec(float(s_axle[i]), float(masses[i]), k_s, c_t, k_t, c_s)")),
    # ---------------------------------------------------------------- field calibration
    N("field-weighting-dropped", "calibration: residuals not divided by each channel's measured RMS", T_FIELD,
      Edit(FIELD, "out.append((s_at - m) / np.sqrt(np.mean(m**2)))", "out.append(s_at - m)")),
    N("field-inflation-halved", "calibration: low-pass covariance inflation f_s/(4 f_c) instead of f_s/(2 f_c)", T_FIELD,
      Edit(FIELD, "c.record.sampling_rate / (2.0 * c.lowpass_hz)", "c.record.sampling_rate / (4.0 * c.lowpass_hz)")),
    N("field-s2-factor", "calibration: s² = cost/(m − n) instead of 2·cost/(m − n)", T_FIELD,
      Edit(FIELD, "s2 = 2.0 * sol.cost / (m - n)", "s2 = sol.cost / (m - n)")),
    N("field-drift-sign", "calibration: the accelerometer drift line added instead of removed", T_FIELD,
      Edit(FIELD, "m = m - (d.offset + d.drift * (t_meas - d.t_ref))", "m = m + (d.offset + d.drift * (t_meas - d.t_ref))")),
    N("field-microstrain-factor", "field records: microstrain read as 1e-5", T_FIELD,
      Edit(FIELD_IO, '"microstrain": ("strain", 1e-6),', '"microstrain": ("strain", 1e-5),')),
]
MUTATIONS += NEW_MUTATIONS


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
    ap.add_argument("--new", action="store_true", help="only the mutations of models added since the paper")
    ap.add_argument("--only-targeted", action="store_true",
                    help="run each mutation's own tests only (not --tests after them)")
    args = ap.parse_args(argv)
    pool = NEW_MUTATIONS if args.new else MUTATIONS
    chosen = [m for m in pool if not args.select or any(w in m.name for w in args.select)]
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
    def tests_of(m: Mutation) -> list[str]:
        own = list(m.tests)
        return own if (args.only_targeted and own) else list(dict.fromkeys(own + list(args.tests)))

    if not args.no_baseline:
        base_tests = list(dict.fromkeys([t for m in chosen for t in tests_of(m)]))
        rc, first, sec = run_tests(ROOT / "src", base_tests, args.timeout)
        if rc != 0:
            print(f"the unmutated source fails the tests ({first}); fix that first", file=sys.stderr)
            return 2
        print(f"baseline: tests pass ({sec:.0f} s)", flush=True)
    rows = []
    for m in chosen:
        with tempfile.TemporaryDirectory(prefix="vbikit-mutant-") as tmp:
            mutated_tree(m, Path(tmp))
            rc, first, sec = run_tests(Path(tmp) / "src", tests_of(m), args.timeout)
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
