"""Modes from other FE programs (OpenSees, ANSYS, SAP2000, …) through a documented text file.

File format ``vbikit-modes 1`` (a CSV file with ``#`` header lines; full reference in
``docs/bridges.md``)::

    # vbikit-modes 1
    # span = 16.76                         [m], required
    # frequencies_hz = 7.31, 8.11, ...     [Hz], required, one per mode, ascending
    # omega = 45.9, 50.9, ...            [rad/s], optional: overrides frequencies_hz (exact round trip)
    # damping_ratios = 0.02, 0.02, ...     [-], optional (else the ``damping_ratio`` argument)
    # girder_y = -4.26, -2.13, ...         [m], optional: girder lines (default: every node line)
    # strain_lever_arm = 0.747, ...        [m], optional: bottom fibre to neutral axis, one per node line
    # default_lateral_offset = 1.4         [m], optional
    # default_girder = 4                   optional, 1-based
    x,y,w_1,w_2,...,dwdx_1,...,dwdy_1,...
    0,-4.26,0,0,...

* Nodes lie on a rectangular grid: every distinct y (a longitudinal line, e.g. a girder) has a
  node at every distinct x (a station); x runs from 0 to the span.  Row order is free.
* ``w_k`` is the vertical (z up) component of mode k, **mass-normalised** (φᵀ M φ = 1, units
  kg^-1/2), as OpenSees, ANSYS and SAP2000 export them by default.
* ``dwdx_k`` and ``dwdy_k`` (optional, both or neither) are the slopes ∂w/∂x and ∂w/∂y.  From
  nodal rotations with x along the span, y to the left and z up: ∂w/∂y = θ_x and ∂w/∂x = −θ_y.
  Without them, slopes are taken from cubic splines through the nodal w (not-a-knot) along each
  line and across each station.
* Between nodes, :class:`~vbikit.bridge.nodal.NodalModes` interpolates (Hermite along x and
  across y), so a file written by :func:`write_modes` from a vbikit model reproduces that model
  exactly.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from vbikit._files import read_text
from vbikit.bridge.base import ModalBridge
from vbikit.bridge.girder_deck import girder_line_strain
from vbikit.bridge.nodal import NodalModes

log = logging.getLogger(__name__)

MAGIC = "vbikit-modes 1"
#: strain lever arm used when a file gives none [m] (the beam's default)
DEFAULT_LEVER_ARM = 0.5


class ModeFileError(ValueError):
    """A mode file that does not follow the format; the message names the problem."""


@dataclass(frozen=True, eq=False)
class ImportedModalBridge(ModalBridge):
    """A bridge given by nodal modes (:class:`NodalModes`), e.g. read by :func:`modes_from_file`.

    ``strain_lever_arm`` [m] per node line (distance from the neutral axis down to the bottom
    fibre); ``girder_y`` [m] the girder lines (Girder 1 first) for per-girder responses.
    """

    modes: NodalModes
    circular_frequencies: NDArray[np.float64]  # ω [rad/s]
    damping: NDArray[np.float64]
    strain_lever_arm: NDArray[np.float64]
    girder_lines: Optional[NDArray[np.float64]] = None
    default_lateral_offset: float = 0.0
    default_girder: int = 1
    name: str = ""
    span: float = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "span", self.modes.span)
        f = np.asarray(self.circular_frequencies, float)
        if f.shape != (self.modes.n_modes,) or np.any(~np.isfinite(f)) or np.any(f <= 0):
            raise ModeFileError(f"need {self.modes.n_modes} positive frequencies, got {f}")
        if np.any(np.diff(f) < 0):
            raise ModeFileError("frequencies must be ascending")
        object.__setattr__(self, "circular_frequencies", f)
        object.__setattr__(self, "damping", np.broadcast_to(np.asarray(self.damping, float), f.shape).copy())
        c = np.broadcast_to(np.asarray(self.strain_lever_arm, float), self.modes.y.shape).copy()
        object.__setattr__(self, "strain_lever_arm", c)
        if self.girder_lines is not None:
            object.__setattr__(self, "girder_lines", np.asarray(self.girder_lines, float))

    @property
    def omega(self) -> NDArray[np.float64]:
        return self.circular_frequencies

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        return self.damping

    @property
    def girder_y(self) -> NDArray[np.float64]:
        return self.modes.y if self.girder_lines is None else self.girder_lines

    @property
    def n_girders(self) -> int:
        return int(self.girder_y.size)

    @property
    def default_response_y(self) -> float:
        """y [m] of the default girder's line (responses are read there unless y is given)."""
        return float(self.girder_y[self.girder_index(self.default_girder)])

    def girder_index(self, girder: int) -> int:
        if not 1 <= int(girder) <= self.n_girders:
            raise ValueError(f"girder must be 1 … {self.n_girders}, got {girder!r}")
        return int(girder) - 1

    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.modes.evaluate(x, y, 0)

    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self.modes.evaluate(x, y, 1)

    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        """c ∂²w/∂x² on the node line(s) at y (linear between lines, clamped beyond)."""
        return girder_line_strain(self.modes, self.strain_lever_arm, x, y)


def _floats(text: str, key: str) -> NDArray[np.float64]:
    try:
        return np.array([float(v) for v in text.replace(",", " ").split()])
    except ValueError:
        raise ModeFileError(f"header {key!r}: not a list of numbers: {text!r}") from None


def write_modes(bridge: ModalBridge, path: str | Path, modes: NodalModes | None = None) -> Path:
    """Write a bridge's nodal modes in the ``vbikit-modes 1`` format (full float precision).

    ``modes`` defaults to ``bridge.nodal_modes`` (the slab-on-girder model's grid).  The lever arms
    are the bridge's ``line_properties["c"]`` or ``strain_lever_arm`` when it has them.
    """
    modes = modes if modes is not None else getattr(bridge, "nodal_modes", None) or getattr(bridge, "modes")
    path = Path(path)
    c = getattr(bridge, "strain_lever_arm", None)
    if c is None and hasattr(bridge, "line_properties"):
        c = bridge.line_properties["c"]
    lines = [f"# {MAGIC}", f"# span = {modes.span!r}",
             "# frequencies_hz = " + ", ".join(repr(float(f)) for f in bridge.frequencies_hz),
             "# omega = " + ", ".join(repr(float(f)) for f in bridge.omega),
             "# damping_ratios = " + ", ".join(repr(float(z)) for z in bridge.damping_ratios)]
    if hasattr(bridge, "girder_y"):
        lines.append("# girder_y = " + ", ".join(repr(float(v)) for v in bridge.girder_y))
    if c is not None:
        lines.append("# strain_lever_arm = " + ", ".join(repr(float(v)) for v in np.broadcast_to(c, modes.y.shape)))
    for key in ("default_lateral_offset", "default_girder"):
        if hasattr(bridge, key):
            lines.append(f"# {key} = {getattr(bridge, key)!r}")
    n = modes.n_modes
    lines.append(",".join(["x", "y", *(f"w_{k + 1}" for k in range(n)), *(f"dwdx_{k + 1}" for k in range(n)),
                           *(f"dwdy_{k + 1}" for k in range(n))]))
    yy, xx = np.meshgrid(modes.y, modes.x, indexing="ij")
    table = np.column_stack([xx.ravel(), yy.ravel(), modes.w.reshape(-1, n), modes.wx.reshape(-1, n), modes.wy.reshape(-1, n)])
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w") as fh:
        fh.write("\n".join(lines) + "\n")
        np.savetxt(fh, table, fmt="%.17g", delimiter=",")
    return path


def modes_from_file(path: str | Path, damping_ratio: float = 0.02, n_modes: int | None = None) -> ImportedModalBridge:
    """Read a ``vbikit-modes 1`` file (see the module docstring) into an :class:`ImportedModalBridge`.

    ``damping_ratio`` applies when the file has no ``damping_ratios``; ``n_modes`` keeps only the first modes.
    """
    path = Path(path)
    lines = read_text(path, ModeFileError, "mode file").splitlines()
    header: dict[str, str] = {}
    columns: list[str] | None = None
    data_start = 0
    if not lines or lines[0].strip().lstrip("#").strip() != MAGIC:  # no echo: the file may be anything
        raise ModeFileError(f"{path}: not a vbikit mode file (its first line must be '# {MAGIC}')")
    for i, line in enumerate(lines[1:], start=1):
        s = line.strip()
        if not s:
            continue
        if s.startswith("#"):
            if "=" in s:
                k, v = s.lstrip("#").split("=", 1)
                header[k.strip()] = v.strip()
            continue
        columns = [c.strip() for c in s.split(",")]
        data_start = i + 1
        break
    if columns is None:
        raise ModeFileError(f"{path}: no column header line")
    for key in ("span", "frequencies_hz"):
        if key not in header:
            raise ModeFileError(f"{path}: missing header '# {key} = ...'")
    freqs = _floats(header["frequencies_hz"], "frequencies_hz")
    n = freqs.size
    omega = _floats(header["omega"], "omega") if "omega" in header else 2.0 * np.pi * freqs
    if omega.size != n:
        raise ModeFileError(f"{path}: omega has {omega.size} values but frequencies_hz has {n}")
    want = ["x", "y", *(f"w_{k + 1}" for k in range(n))]
    slopes = [*(f"dwdx_{k + 1}" for k in range(n)), *(f"dwdy_{k + 1}" for k in range(n))]
    if columns[: 2 + n] != want or columns[2 + n:] not in ([], slopes):
        raise ModeFileError(f"{path}: columns must be x, y, w_1 … w_{n} [, dwdx_1 … dwdx_{n}, dwdy_1 … dwdy_{n}]; got {columns[:6]}…")
    try:
        table = np.loadtxt(lines[data_start:], delimiter=",", ndmin=2)
    except ValueError:
        raise ModeFileError(f"{path}: every row needs {len(columns)} finite numbers") from None
    if table.shape[1] != len(columns) or not np.all(np.isfinite(table)):
        raise ModeFileError(f"{path}: every row needs {len(columns)} finite numbers")
    xs, ys = np.unique(table[:, 0]), np.unique(table[:, 1])
    if table.shape[0] != xs.size * ys.size:
        raise ModeFileError(f"{path}: nodes must form a full rectangular grid ({ys.size} lines × {xs.size} stations "
                            f"= {xs.size * ys.size} nodes, found {table.shape[0]} rows)")
    span = float(_floats(header["span"], "span")[0])
    if xs[0] != 0.0 or not np.isclose(xs[-1], span, rtol=1e-12, atol=0):
        raise ModeFileError(f"{path}: stations must run from x = 0 to the span {span} m (found {xs[0]} … {xs[-1]})")
    order = np.lexsort((table[:, 0], table[:, 1]))  # by line, then station
    t = table[order]
    if np.any(t[:, 0].reshape(ys.size, xs.size) != xs[None, :]):
        raise ModeFileError(f"{path}: duplicate nodes")
    grid = t[:, 2:].reshape(ys.size, xs.size, -1)
    w = grid[:, :, :n]
    if grid.shape[2] == 3 * n:
        wx, wy = grid[:, :, n:2 * n], grid[:, :, 2 * n:]
    else:
        wx = CubicSpline(xs, w, axis=1)(xs, 1) if xs.size > 2 else np.repeat((w[:, 1:] - w[:, :1]) / (xs[1] - xs[0]), 2, axis=1)
        if ys.size > 2:
            wy = CubicSpline(ys, w, axis=0)(ys, 1)
        elif ys.size == 2:
            wy = np.repeat((w[1:] - w[:1]) / (ys[1] - ys[0]), 2, axis=0)
        else:
            wy = np.zeros_like(w)
    keep = n if n_modes is None else min(int(n_modes), n)
    modes = NodalModes(xs, ys, w[:, :, :keep], wx[:, :, :keep], wy[:, :, :keep])
    damping = _floats(header["damping_ratios"], "damping_ratios")[:keep] if "damping_ratios" in header else damping_ratio
    if "strain_lever_arm" in header:
        lever = _floats(header["strain_lever_arm"], "strain_lever_arm")
        if lever.size not in (1, ys.size):
            raise ModeFileError(f"{path}: strain_lever_arm needs 1 or {ys.size} values, got {lever.size}")
    else:
        log.warning("%s gives no strain_lever_arm; using %.2f m for strains", path, DEFAULT_LEVER_ARM)
        lever = np.array([DEFAULT_LEVER_ARM])
    girders = _floats(header["girder_y"], "girder_y") if "girder_y" in header else None
    return ImportedModalBridge(
        modes, omega[:keep], damping, lever, girders,
        default_lateral_offset=float(header.get("default_lateral_offset", 0.0)),
        default_girder=int(float(header.get("default_girder", 1))), name=path.stem,
    )
