"""Element matrices of the finite-element bridge models (the continuous beam and the grillage deck).

Euler–Bernoulli beam element of length h [m], DOFs (w₁, θ₁, w₂, θ₂) with θ = ∂w/∂s along the element,
cubic Hermite shape functions (``vbikit.bridge.nodal.hermite_basis``); St Venant torsion (or any
bar) element with linear shape functions on (r₁, r₂).  Sources: Przemieniecki, *Theory of Matrix
Structural Analysis*, 1968, §5.3 (stiffness) and §11.3 (consistent mass); the Hermite–linear coupling
is ∫ N_Hermiteᵀ N_linear ds in closed form (checked against Gauss quadrature in
``tests/verification/test_girder_deck.py``).
"""
from __future__ import annotations

from typing import Optional

import numpy as np
from numpy.typing import NDArray


def beam_element_stiffness(EI: float, h: float) -> NDArray[np.float64]:
    """Euler–Bernoulli element stiffness [N/m …] for DOFs (w₁, θ₁, w₂, θ₂), bending stiffness EI [N·m²],
    length h [m] (Przemieniecki 1968, §5.3)::

        K_e = EI/h³ [[ 12,   6h,  −12,   6h ],
                     [ 6h,  4h²,  −6h,  2h² ],
                     [−12,  −6h,   12,  −6h ],
                     [ 6h,  2h²,  −6h,  4h² ]]
    """
    return EI / h**3 * np.array(
        [[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h], [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]]
    )


def beam_element_mass(m: float, h: float) -> NDArray[np.float64]:
    """Consistent element mass [kg …] of a beam with m [kg/m] for DOFs (w₁, θ₁, w₂, θ₂), length h [m]
    (∫ m Nᵀ N ds with the Hermite cubics; Przemieniecki 1968, §11.3)::

        M_e = m h/420 [[156,   22h,   54,  −13h ],
                       [22h,   4h²,  13h,  −3h² ],
                       [ 54,   13h,  156,  −22h ],
                       [−13h, −3h², −22h,   4h² ]]
    """
    return m * h / 420.0 * np.array(
        [[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h], [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]]
    )


def bar_element_stiffness(k: float) -> NDArray[np.float64]:
    """Two-node bar (torsion) element stiffness k [[1, −1], [−1, 1]] with k = GJ/h [N·m] (linear shape functions)."""
    return k * np.array([[1.0, -1.0], [-1.0, 1.0]])


def bar_element_mass(J: float, h: float) -> NDArray[np.float64]:
    """Consistent mass of a linear two-node element: J h/6 [[2, 1], [1, 2]], with J the rotary inertia per
    length [kg·m] (∫ J Nᵀ N ds, linear N) and h [m] the length."""
    return J * h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])


def hermite_linear_coupling(h: float) -> NDArray[np.float64]:
    """∫₀ʰ N_Hermite(s)ᵀ N_linear(s) ds, shape (4, 2), rows (w₁, θ₁, w₂, θ₂), columns (r₁, r₂)::

        [[7h/20,   3h/20 ],
         [h²/20,   h²/30 ],
         [3h/20,   7h/20 ],
         [−h²/30, −h²/20 ]]

    (closed form; times the first moment of mass S [kg] it couples bending and twist)."""
    return np.array([[7 * h / 20, 3 * h / 20], [h * h / 20, h * h / 30], [3 * h / 20, 7 * h / 20], [-h * h / 30, -h * h / 20]])


def oblique_member_rotation(skew: float) -> Optional[NDArray[np.float64]]:
    """T (6, 6) with u_local = T u_nodes for a transverse member along the support lines' skew θ [°]:
    local (w_a, r_a, w_b, r_b, n_a, n_b) — r the slope along the member e = (sin θ, cos θ),
    n = ∂w/∂x cos θ − ∂w/∂y sin θ the slope across it (its twist) — from the nodes'
    (w, ∂w/∂x, ∂w/∂y) at a then b.  None for θ = 0 (r = ∂w/∂y, n = ∂w/∂x: no transformation)."""
    if not skew:
        return None
    c, s = np.cos(np.radians(skew)), np.sin(np.radians(skew))
    T = np.zeros((6, 6))
    for end, (row_w, row_r, row_n) in enumerate(((0, 1, 4), (2, 3, 5))):
        col = 3 * end
        T[row_w, col] = 1.0
        T[row_r, col + 1], T[row_r, col + 2] = s, c
        T[row_n, col + 1], T[row_n, col + 2] = c, -s
    return T
