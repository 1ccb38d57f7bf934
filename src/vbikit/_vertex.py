"""What every peak taken between the samples of a history shares: the parabola through three samples
(``vbikit.analysis.impact.smooth_vertices``, the railway sweep's compiled loop
``vbikit.solve.moving_loads._peaks``) and the offset at which the one-sided limits beside a jump or
kink are read (``vbikit.analysis.instants``, ``vbikit.solve.moving_loads.instant_table``).  A leaf:
it imports no other part of vbikit, and the parabola is plain Python arithmetic that numba compiles
as it stands."""
from __future__ import annotations

#: the one-sided limits at an instant τ are read at τ ∓ this fraction of the run's step
KNOT_OFFSET = 1e-6


def parabola(s0: float, s2: float, y0: float, y1: float, y2: float) -> tuple[float, float, float]:
    """(a, b, c) of y = a s² + b s + c through (s0, y0), (0, y1), (s2, y2), s0 < 0 < s2 (Newton's divided
    differences)."""
    d0 = (y1 - y0) / -s0
    d2 = (y2 - y1) / s2
    a = (d2 - d0) / (s2 - s0)
    return a, d0 - a * s0, y1
