"""Tire contact models: where a wheel touches the surface and how its tire spring is shared.

A tire model maps one wheel to n contact points, each with a longitudinal offset ξ_p [m]
from the wheel centre (positive forward, i.e. towards +x on the bridge) and a weight β_p
(Σ β_p = 1).  Point p carries a spring β_p·k and dashpot β_p·c, so the tire force is
(paper Eq. 6, β_p = 1/n):

    F = Σ_p β_p [ k (s(x_p) − z_w) + c (ṡ(x_p) − ż_w) ]

with s = deck displacement + road elevation at x_p and z_w the wheel-centre displacement
(z up; F > 0 is compression).  The single-point model is the multi-point model with n = 1,
and both run through the same code, so n = 1 reproduces the point model exactly.
"""
from __future__ import annotations

import abc
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

#: [public] AASHTO LRFD tire contact length 10 in [m]
AASHTO_CONTACT_LENGTH = 0.254


class TireModel(abc.ABC):
    """A contact layout: offsets [m] and weights [-] of the contact points of one tire."""

    @abc.abstractmethod
    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Return (offsets ξ_p [m], weights β_p [-]) of the contact points."""

    @property
    def point_count(self) -> int:
        """Number of contact points per tire."""
        return int(self.layout()[0].size)


@dataclass(frozen=True)
class PointTire(TireModel):
    """Single-point contact: one spring–dashpot under the wheel centre."""

    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return np.zeros(1), np.ones(1)


@dataclass(frozen=True)
class MultiPointTire(TireModel):
    """The paper's multi-point tire (Eq. 6): n spring–dampers of k/n, c/n along the patch.

    Parameters
    ----------
    n_points : int
        Number of contact points n ≥ 1 ([paper] recommends 6).
    contact_length : float
        Patch length a [m]; default 0.254 m [public] AASHTO 10 in, as the paper.
    layout_rule : {"ends", "cells"}
        "ends" [substitute, default]: points from −a/2 to +a/2 at spacing a/(n − 1), the
        paper's "span a length of 25.4 cm" read literally; "cells": each point at the centre
        of one of n equal cells (spacing a/n).  n = 1 is the centre in both.
    """

    n_points: int = 6
    contact_length: float = AASHTO_CONTACT_LENGTH
    layout_rule: Literal["ends", "cells"] = "ends"

    def __post_init__(self) -> None:
        if int(self.n_points) != self.n_points or self.n_points < 1:
            raise ValueError(f"n_points must be an integer >= 1, got {self.n_points!r}")
        if not self.contact_length > 0:
            raise ValueError(f"contact_length must be > 0 m, got {self.contact_length!r}")
        if self.layout_rule not in ("ends", "cells"):
            raise ValueError(f"layout_rule must be 'ends' or 'cells', got {self.layout_rule!r}")

    def layout(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        n, a = int(self.n_points), self.contact_length
        if n == 1:
            offsets = np.zeros(1)
        elif self.layout_rule == "ends":
            offsets = np.linspace(-a / 2, a / 2, n)
        else:
            offsets = (np.arange(n) + 0.5) * (a / n) - a / 2
        return offsets, np.full(n, 1.0 / n)

    def spacing(self) -> float:
        """Spacing between neighbouring points [m] (0 for n = 1)."""
        n = int(self.n_points)
        if n == 1:
            return 0.0
        return self.contact_length / (n - 1 if self.layout_rule == "ends" else n)

    def transfer(self, wavenumber: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """|H(ν)| = |Σ_p β_p exp(2πiνξ_p)|: how the points average a road harmonic of ν [cycle/m].

        For n equal weights at spacing s this is |sin(πνsn) / (n sin(πνs))| (domain-data §3),
        evaluated here without the 0/0 at νs = integer.
        """
        nu = np.asarray(wavenumber, dtype=float)
        offsets, weights = self.layout()
        return np.abs(np.exp(2j * np.pi * nu[..., None] * offsets) @ weights)
