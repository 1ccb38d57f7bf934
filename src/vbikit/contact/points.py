"""Contact points of a whole vehicle: the arrays the coupled solver works on."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit.contact.tires import ContactLayout, TireModel
from vbikit.vehicle.model import Vehicle


@dataclass(frozen=True)
class ContactPoints:
    """Every contact point of every wheel (n_cp points; each wheel's points are contiguous).

    Per point: ``setback`` [m] behind the front axle (x_p = x_front − setback); ``lateral`` [m]
    y relative to the vehicle centreline; ``wheel`` index; ``weight`` β_p, the point's share of
    the static wheel load; ``stiffness`` [N/m], ``damping`` [N·s/m]; ``fixed_load`` [N] (moving
    forces, already × β_p); ``gap`` g_p [m] (tire surface above its lowest point); ``width`` [m]
    of patch it stands for; ``gated`` (contact only while penetrating); ``slope_range`` (n_cp, 2)
    bounds of the tire-surface slope over the point's cell (envelope tires); ``rows`` (n_cp, n_dof).
    Per wheel: ``wheel_first``, ``wheel_count`` (point index range) and ``wheel_envelope``
    (acts through its highest point only: rigid disk).
    """

    setback: NDArray[np.float64]
    lateral: NDArray[np.float64]
    wheel: NDArray[np.int64]
    weight: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    fixed_load: NDArray[np.float64]
    gap: NDArray[np.float64]
    width: NDArray[np.float64]
    gated: NDArray[np.bool_]
    slope_range: NDArray[np.float64]
    rows: NDArray[np.float64]
    wheel_first: NDArray[np.int64]
    wheel_count: NDArray[np.int64]
    wheel_envelope: NDArray[np.bool_]

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
    """Lay the tire model's contact points under every wheel of ``vehicle``.

    Tires are calibrated per wheel from its single-point stiffness, damping and static load
    (the disk's radial stiffness depends on the load).  Wheels without a tire spring (moving
    forces) spread their fixed load by the layout's static shares.
    """
    wheels = vehicle.wheels
    if wheels and type(tire).contact_layout is TireModel.contact_layout and all(w.stiffness > 0 for w in wheels):
        return _shared_layout_points(vehicle, tire)
    loads = vehicle.static_wheel_loads()
    lays = []
    for w, load in zip(wheels, loads):
        if w.stiffness > 0:
            lay = tire.contact_layout(w.stiffness, w.damping, load - w.fixed_load)
        else:
            offsets, share = tire.layout()
            lay = ContactLayout(offsets, np.zeros_like(offsets), np.zeros_like(offsets), np.zeros_like(offsets), share,
                                np.zeros_like(offsets))
        lays.append(lay)
    count = np.array([lay.offsets.size for lay in lays], np.int64)
    n_cp = int(count.sum())
    n_dof = vehicle.n_dof

    def cat(values: list, dtype: type = float) -> NDArray:
        return np.concatenate([np.asarray(v, dtype).ravel() for v in values]) if values else np.zeros(0, dtype)

    def per_wheel(values: list, dtype: type = float) -> NDArray:
        return np.repeat(np.array(values, dtype), count)

    rows = np.repeat(np.array([w.row for w in wheels], float).reshape(len(wheels), n_dof), count, axis=0) if n_dof \
        else np.zeros((n_cp, 0))
    return ContactPoints(
        cat([w.offset - lay.offsets for w, lay in zip(wheels, lays)]),
        per_wheel([w.lateral for w in wheels]),
        np.repeat(np.arange(len(wheels), dtype=np.int64), count),
        cat([lay.static_share for lay in lays]),
        cat([lay.stiffness for lay in lays]),
        cat([lay.damping for lay in lays]),
        cat([lay.static_share * w.fixed_load for w, lay in zip(wheels, lays)]),
        cat([lay.gaps for lay in lays]),
        cat([lay.widths for lay in lays]),
        per_wheel([lay.gated for lay in lays], bool),
        cat([np.zeros((n, 2)) if lay.slope_range is None else lay.slope_range for n, lay in zip(count, lays)]).reshape(n_cp, 2),
        rows,
        np.concatenate([[0], np.cumsum(count)[:-1]]).astype(np.int64),
        count,
        np.array([lay.envelope for lay in lays], bool),
    )


def _shared_layout_points(vehicle: Vehicle, tire: TireModel) -> ContactPoints:
    """``contact_points`` of a tire whose layout is the same under every wheel, its springs and
    dashpots the wheel's shared by β_p (``TireModel.contact_layout``'s default: point and
    multi-point tires; wheels with a tire spring): the layout once, the per-point arrays as outer
    products of the per-wheel values and the layout (the same products as the per-wheel layouts')."""
    wheels = vehicle.wheels
    offsets, weights = tire.layout()
    offsets, weights = np.asarray(offsets, float).ravel(), np.asarray(weights, float).ravel()
    n_p, n_w, n_dof = offsets.size, len(wheels), vehicle.n_dof
    widths = np.zeros(n_p) if n_p == 1 else np.full(n_p, tire.patch_length / n_p)
    per_wheel = np.array([(w.offset, w.lateral, w.stiffness, w.damping, w.fixed_load) for w in wheels], float)
    count = np.full(n_w, n_p, np.int64)
    n_cp = n_w * n_p
    rows = np.repeat(np.array([w.row for w in wheels], float).reshape(n_w, n_dof), n_p, axis=0) if n_dof \
        else np.zeros((n_cp, 0))
    return ContactPoints(
        np.subtract.outer(per_wheel[:, 0], offsets).ravel(),
        np.repeat(per_wheel[:, 1], n_p),
        np.repeat(np.arange(n_w, dtype=np.int64), n_p),
        np.tile(weights, n_w),
        (weights * per_wheel[:, 2:3]).ravel(),
        (weights * per_wheel[:, 3:4]).ravel(),
        (weights * per_wheel[:, 4:5]).ravel(),
        np.zeros(n_cp),
        np.tile(widths, n_w),
        np.zeros(n_cp, bool),
        np.zeros((n_cp, 2)),
        rows,
        np.arange(0, n_cp, n_p, dtype=np.int64),
        count,
        np.zeros(n_w, bool),
    )


def stack_contact_points(parts: "list[ContactPoints]", dof_offsets: "tuple[int, ...]") -> ContactPoints:
    """The contact points of several vehicles (``parts``, each from [`contact_points`][vbikit.contact.contact_points] of its
    own vehicle and tire) as one set: points and wheels concatenated in vehicle order, wheel
    indices and point ranges shifted, rows padded into the stacked DOF vector (vehicle i owns
    DOFs ``dof_offsets[i]`` … ``dof_offsets[i + 1]``).  Setbacks stay relative to each
    vehicle's own front axle."""
    n_dof = int(dof_offsets[-1])
    wheel_shift = np.concatenate([[0], np.cumsum([p.wheel_first.size for p in parts])])
    point_shift = np.concatenate([[0], np.cumsum([p.n for p in parts])])
    rows = np.zeros((int(point_shift[-1]), n_dof))
    for i, p in enumerate(parts):
        rows[point_shift[i]:point_shift[i + 1], dof_offsets[i]:dof_offsets[i + 1]] = p.rows
    cat = np.concatenate
    return ContactPoints(
        cat([p.setback for p in parts]), cat([p.lateral for p in parts]),
        cat([p.wheel + wheel_shift[i] for i, p in enumerate(parts)]).astype(np.int64),
        cat([p.weight for p in parts]), cat([p.stiffness for p in parts]), cat([p.damping for p in parts]),
        cat([p.fixed_load for p in parts]), cat([p.gap for p in parts]), cat([p.width for p in parts]),
        cat([p.gated for p in parts]).astype(bool), cat([p.slope_range for p in parts]).reshape(-1, 2), rows,
        cat([p.wheel_first + point_shift[i] for i, p in enumerate(parts)]).astype(np.int64),
        cat([p.wheel_count for p in parts]).astype(np.int64), cat([p.wheel_envelope for p in parts]).astype(bool),
    )
