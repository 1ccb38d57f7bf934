"""Contact points of a whole vehicle: the arrays the coupled solver works on."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit.contact.tires import TireModel
from vbikit.vehicle.model import Vehicle


@dataclass(frozen=True)
class ContactPoints:
    """Every contact point of every wheel (n_cp points).

    ``setback`` [m]: distance of the point behind the front axle (x_p = x_front − setback);
    ``lateral`` [m]: y of the point relative to the vehicle centreline; ``wheel`` index of its
    wheel; ``weight`` its share β_p of the wheel's tire; ``stiffness`` [N/m], ``damping`` [N·s/m] and ``fixed_load`` [N] already multiplied
    by the point's weight β_p; ``rows`` (n_cp, n_dof) wheel-centre displacement rows.
    """

    setback: NDArray[np.float64]
    lateral: NDArray[np.float64]
    wheel: NDArray[np.int64]
    weight: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    fixed_load: NDArray[np.float64]
    rows: NDArray[np.float64]

    @property
    def n(self) -> int:
        return int(self.setback.size)

    def wheel_sum(self, per_point: NDArray[np.float64], n_wheels: int) -> NDArray[np.float64]:
        """Sum a (..., n_cp) array over the points of each wheel → (..., n_wheels)."""
        out = np.zeros(per_point.shape[:-1] + (n_wheels,))
        for w in range(n_wheels):
            out[..., w] = per_point[..., self.wheel == w].sum(axis=-1)
        return out


def contact_points(vehicle: Vehicle, tire: TireModel) -> ContactPoints:
    """Lay the tire model's contact points under every wheel of ``vehicle``."""
    offsets, weights = tire.layout()
    n_dof = vehicle.n_dof
    setback, lateral, wheel, weight, k, c, f0, rows = [], [], [], [], [], [], [], []
    for i, w in enumerate(vehicle.wheels):
        for xi, beta in zip(offsets, weights):
            setback.append(w.offset - xi)
            lateral.append(w.lateral)
            wheel.append(i)
            weight.append(beta)
            k.append(beta * w.stiffness)
            c.append(beta * w.damping)
            f0.append(beta * w.fixed_load)
            rows.append(w.row if n_dof else np.zeros(0))
    return ContactPoints(
        np.array(setback, float),
        np.array(lateral, float),
        np.array(wheel, np.int64),
        np.array(weight, float),
        np.array(k, float),
        np.array(c, float),
        np.array(f0, float),
        np.array(rows, float).reshape(len(setback), n_dof),
    )
