"""The extremes between the samples (``vbikit.analysis.impact.smooth_vertices``) written out for the
tests that check the library's peaks against a reference: per history and sense its extreme sample,
unless an instant of ``kinks`` lies within the two steps around it (ends included), the vertex of
``np.polyfit``'s parabola through the three samples, both histories' parabolas read there."""
from __future__ import annotations

import numpy as np


def written_out_vertices(t, dynamic, static, kinks):
    """(times, dynamic, static) of the vertices (module docstring); ``kinks`` [s] any order."""
    kinks = np.asarray(kinks, float)
    out = []
    for which, history in enumerate((dynamic, static)):
        for s in (1.0, -1.0):
            i = int(np.argmax(s * history))
            if not 0 < i < t.size - 1 or np.any((kinks >= t[i - 1]) & (kinks <= t[i + 1])):
                continue
            fits = [np.polyfit(t[i - 1:i + 2] - t[i], h[i - 1:i + 2], 2) for h in (dynamic, static)]
            if s * fits[which][0] < 0:
                v = -fits[which][1] / (2 * fits[which][0])
                out.append((t[i] + v, np.polyval(fits[0], v), np.polyval(fits[1], v)))
    return tuple(np.array(c) for c in zip(*out)) if out else (np.zeros(0),) * 3
