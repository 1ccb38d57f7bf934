"""GIL-free entry points to the existing compiled integrators (same signatures, same code).

A numba function compiled with ``nogil=True`` releases the GIL for its whole call, including
the kernels it calls (they are compiled into it), so several crossings of a batch can run on
threads.  The arithmetic is exactly that of :func:`vbikit.solve.kernels.rk4` /
:func:`~vbikit.solve.kernels.newmark`.

Not cached on disk (``cache=False``) on purpose: numba's cache of a function does not notice
changes in the functions it calls from other files, so a cached wrapper could keep running an
old version of the kernels.  They are compiled on first use (a few seconds per process) and only
used when a batch runs on several threads; the single-thread path calls the kernels directly.
"""
from __future__ import annotations

from numba import njit

from vbikit.solve import kernels


@njit(cache=False, nogil=True)
def rk4_nogil(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
              wheel_force, wheel_len):
    """:func:`vbikit.solve.kernels.rk4` without the GIL."""
    kernels.rk4(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
                wheel_force, wheel_len)


@njit(cache=False, nogil=True)
def newmark_nogil(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
                  wheel_force, wheel_len, active0, max_iterations):
    """:func:`vbikit.solve.kernels.newmark` without the GIL; returns its unsettled-step count."""
    return kernels.newmark(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi,
                           ddq, wheel_force, wheel_len, active0, max_iterations)
