"""The tire-model interface: the contact points a model lays under a wheel ([`ContactLayout`][vbikit.contact.ContactLayout]),
its scenario parameters ([`TireParameters`][vbikit.contact.TireParameters]) and the abstract [`TireModel`][vbikit.contact.TireModel] (equations
in ``vbikit.contact.tires``)."""
from __future__ import annotations

import abc
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray
from pydantic import BaseModel, ConfigDict


@dataclass(frozen=True)
class ContactLayout:
    """The contact points of one tire on one wheel.

    ``offsets`` ξ_p [m], ``stiffness`` k_p [N/m], ``damping`` c_p [N·s/m], ``gaps`` g_p [m],
    ``static_share`` β_p (share of the static wheel load carried by the point on flat ground,
    Σ β_p = 1; used for moving-force wheels and the static reference), ``widths`` [m] (length
    of patch each point stands for, summed over points in contact to report the patch
    length), ``gated`` (points whose contact is geometric: disk tires), ``envelope`` (the wheel
    acts through its highest point only: rigid disk).
    """

    offsets: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    gaps: NDArray[np.float64]
    static_share: NDArray[np.float64]
    widths: NDArray[np.float64]
    gated: bool = False
    envelope: bool = False
    #: envelope tires: range of the tire-surface slope g'(ξ) over each point's cell [ξ_p ∓ Δξ/2]
    slope_range: NDArray[np.float64] | None = None


class TireParameters(BaseModel):
    """The scenario parameters of a tire model: the keys of its ``[tire]`` table besides ``model``.

    Subclass it with one pydantic field per key (range, default and a description ending in the
    unit in brackets); values are checked strictly (no "12" for 12, no 1.5 for an integer).
    """

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class TireModel(abc.ABC):
    """A tire model: lays contact points under a wheel.

    A concrete model sets the class attributes below and is registered with
    [`register_tire`][vbikit.contact.register_tire].
    """

    #: scenario name of the model ([tire] model = ...)
    name: ClassVar[str] = ""
    #: one line for catalogues (``vbikit presets``)
    description: ClassVar[str] = ""
    #: keys of :data:`vbikit.references.REFERENCES` the model relies on (``vbikit cite``)
    references: ClassVar[tuple[str, ...]] = ()
    #: the model's scenario parameters
    Parameters: ClassVar[type[TireParameters]] = TireParameters

    @classmethod
    def from_parameters(cls, parameters: TireParameters) -> TireModel:
        """The model built from its validated scenario parameters (default: keys = constructor arguments)."""
        return cls(**parameters.model_dump())

    @abc.abstractmethod
    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Return (offsets ξ_p [m], static shares β_p [-]) of the contact points."""

    def contact_layout(self, stiffness: float, damping: float, static_load: float) -> ContactLayout:
        """Contact points for a wheel whose single-point tire has ``stiffness`` [N/m], ``damping``
        [N·s/m] and carries ``static_load`` [N].  Default: linear springs shared by β_p."""
        offsets, weights = self.layout()
        widths = np.zeros_like(offsets) if offsets.size == 1 else np.full_like(offsets, self.patch_length / offsets.size)
        return ContactLayout(offsets, weights * stiffness, weights * damping, np.zeros_like(offsets), weights, widths)

    @property
    def patch_length(self) -> float:
        """Nominal contact-patch length [m] (0 for a point)."""
        return 0.0

    @property
    def point_count(self) -> int:
        """Number of contact points per tire."""
        return int(self.layout()[0].size)
