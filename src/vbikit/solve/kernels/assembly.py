"""The static modal load history. (``vbikit.solve.kernels``: the equations and conventions; the coupled
system matrices at one instant are assembled in numpy, ``vbikit.solve.system.coupled_system``.)"""
from __future__ import annotations

from vbikit.solve.kernels.bundles import _flat
from vbikit.solve.kernels.contact import hermite_shape


@_flat
def static_modal_history(travel, origin, direction, vehicle, track, loads, start, end, grid_h, values, slopes, out, phi,
                         dphi):
    """Σ_p φ(x_p(t)) P_p into ``out`` (n_t, n_m), zeroed, for downward point loads ``loads`` P_p [N] at
    x_p = ``origin``_p + ``direction``_p·s_v(t) on ``track``_p, ``travel`` (n_t, n_vehicles) [m] (the
    fields of ``Points`` and ``Modes`` one by one; tabulated shapes, as the solver; ``phi``, ``dphi``
    (n_m,) work space); ξ_st = −that / ω²."""
    for t in range(len(travel)):
        for p in range(origin.size):
            if loads[p] == 0.0:
                continue
            x = origin[p] + direction[p] * travel[t, vehicle[p]]
            if start[track[p]] <= x <= end[track[p]]:
                hermite_shape(x, track[p], start, grid_h, values, slopes, phi, dphi)
                for m in range(phi.size):
                    out[t, m] += phi[m] * loads[p]
