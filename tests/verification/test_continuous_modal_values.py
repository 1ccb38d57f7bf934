# Modal values r_i of the continuous beam's load effects (what the mode-acceleration correction and
# mode superposition use), on unequal spans with per-span EI and mass, springs and an end spring.
#
# With every mode of the FE model kept, the static flexibility is Σ_i φ_i φ_iᵀ/ω_i² (spectral
# decomposition of K⁻¹ with φᵀMφ = 1), so Σ_i r_i φ_i(x)/ω_i² equals the full-stiffness influence
# I(x) for a load outside the section's element.  I(x) itself is checked against pycba and an
# independent direct-stiffness solve in test_continuous_general.py; the modal inertia terms
# (ω² ∫ m φ) enter r_i with the sign fixed by equilibrium and would break the identity otherwise.
from __future__ import annotations

import math

import numpy as np
import pytest

from vbikit.bridge.continuous import ContinuousBeam

INF = math.inf


@pytest.fixture(scope="module")
def beam():
    b = ContinuousBeam([9.0, 14.0, 11.0], [2.0e9, 4.5e9, 3.0e9], [5000.0, 8000.0, 6500.0], elements_per_span=30,
                       n_modes=1000, support_stiffness=[INF, 9.0e7, INF, 4.0e7], rotational_stiffness=(1.5e9, 0.0))
    return b


@pytest.mark.parametrize("kind, kw", [
    ("shear", {"x": 4.5}), ("shear", {"x": 9.0}), ("shear", {"x": 20.0}), ("shear", {"x": 30.0}),
    ("moment", {"x": 4.5}), ("moment", {"x": 23.0}), ("moment", {"x": 9.0}),
    ("reaction", {"support": 0}), ("reaction", {"support": 1}), ("reaction", {"support": 3}),
])
def test_all_modes_superpose_to_the_influence_line(beam, kind, kw):
    assert beam.omega.size == 2 * beam.nodes.size - 2  # every mode: 2 DOFs per node, the 2 rigid supports removed
    e = beam.load_effect(kind, **kw)
    xp = np.array([1.3, 7.7, 12.1, 17.9, 26.6, 32.4])
    if kind != "reaction":  # away from the section's element (a point load inside it: the kink the cubics miss)
        xp = xp[np.abs(xp - kw["x"]) > 2.5]
    modal = (beam.mode_shapes(xp) / beam.omega**2) @ e.modal
    # measured: ≤ 4.5e-6 of the largest ordinate (the M-projection of the kinked arm (s − x)₊ onto the
    # cubics); a rigid support's modal reaction K φ − ω² M φ carries the consistent-mass coupling of
    # the support node, which the identity misses by O(h): 1.3e-3 at the entry support
    tol = 3e-3 if (kind == "reaction" and kw["support"] == 0) else 2e-5
    np.testing.assert_allclose(modal, e.influence(xp), atol=tol * np.abs(e.influence(xp)).max())
