"""GIL-free entry points to the existing compiled integrators (same signatures, same code).

A numba function compiled with ``nogil=True`` releases the GIL for its whole call, including
the kernels it calls (they are compiled into it), so several crossings of a batch can run on
threads.  The arithmetic is exactly that of :func:`vbikit.solve.kernels.rk4` /
:func:`~vbikit.solve.kernels.newmark`.
"""
from __future__ import annotations

from numba import njit

from vbikit.solve import kernels


@njit(cache=True, nogil=True)
def rk4_nogil(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
              wheel_force, wheel_len):
    """:func:`vbikit.solve.kernels.rk4` without the GIL."""
    kernels.rk4(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
                wheel_force, wheel_len)


@njit(cache=True, nogil=True)
def newmark_nogil(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
                  wheel_force, wheel_len, active0, max_iterations):
    """:func:`vbikit.solve.kernels.newmark` without the GIL; returns its unsettled-step count."""
    return kernels.newmark(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi,
                           ddq, wheel_force, wheel_len, active0, max_iterations)
