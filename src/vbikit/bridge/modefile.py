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
    # deck_width = 10.3                    [m], optional: total width (the x extent of a skew deck)
    # skew = 20.0                          [°], optional: skew of the support lines (default 0)
    # skew_tan = 0.36397...                optional: overrides tan(skew) (exact round trip)
    x,y,w_1,w_2,...,dwdx_1,...,dwdy_1,...
    0,-4.26,0,0,...

* Nodes lie on a rectangular grid: every distinct y (a longitudinal line, e.g. a girder) has a
  node at every distinct x (a station); x runs from 0 to the span.  Row order is free.
* Skew supports (``skew`` = θ, −90 < θ < 90): line j's node i lies at x = ξ_i + y_j tan θ (the
  oblique mesh).  The first column is then either ``x``, the node's plan x (as FE programs export
  it; ξ = x − y tan θ must give every line the same stations within 1e-6 of the span), or ``xi``,
  the station ξ itself (what ``write_modes`` writes: an exact round trip).
* ``w_k`` is the vertical (z up) component of mode k, **mass-normalised** (φᵀ M φ = 1, units
  kg^-1/2), as OpenSees, ANSYS and SAP2000 export them by default.
* ``dwdx_k`` and ``dwdy_k`` (optional, both or neither) are the slopes ∂w/∂x and ∂w/∂y.  From
  nodal rotations with x along the span, y to the left and z up: ∂w/∂y = θ_x and ∂w/∂x = −θ_y.
  Without them, slopes are taken from cubic splines through the nodal w (not-a-knot) along each
  line and across each station (on a skew deck across the lines at constant ξ, the derivative
  along the oblique members, ∂w/∂y + tan θ ∂w/∂x, from which ∂w/∂y follows).
* Between nodes, ``NodalModes`` interpolates (Hermite along x and
  across y), so a file written by ``write_modes`` from a vbikit model reproduces that model
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

from vbikit._files import atomic_write, read_text
from vbikit.bridge.base import GirderDeck, ModalBridge
from vbikit.bridge.girder_deck import SlabOnGirderBridge
from vbikit.bridge.nodal import NodalModes, girder_line_strain
from vbikit.errors import VbikitError

log = logging.getLogger(__name__)

MAGIC = "vbikit-modes 1"
#: strain lever arm used when a file gives none [m] (the beam's default)
DEFAULT_LEVER_ARM = 0.5
#: largest |default_lateral_offset| a file may give [m] (the scenario's limit of a lateral offset)
MAX_LATERAL_OFFSET = 50.0
#: widest deck a file may give [m]
MAX_DECK_WIDTH = 200.0


class ModeFileError(VbikitError):
    """A mode file that does not follow the format; the message names the problem."""


@dataclass(frozen=True, eq=False)
class ImportedModalBridge(ModalBridge):
    """A bridge given by nodal modes (``NodalModes``), e.g. read by ``modes_from_file``.

    ``strain_lever_arm`` [m] per node line (distance from the neutral axis down to the bottom
    fibre); ``girder_y`` [m] the girder lines (Girder 1 first) for per-girder responses;
    ``deck_width`` [m] the deck's total width, centred on y = 0, when known (it only sets the deck's
    x extent on a skew deck).

    Skew support lines (``modes.skew_tan`` = tan θ ≠ 0): line j's stations lie at x = ξ_i + y_j tan θ
    (``vbikit.bridge.nodal``), the deck point (x, y) has ξ = x − y tan θ ([`span_coordinate`][vbikit.bridge.ModalBridge.span_coordinate]),
    responses default to the midspan of the line at y ([`default_x_at`][vbikit.bridge.ModalBridge.default_x_at]), and strains are read on
    the lines at the point's own ξ.  The deck's x extent runs from the entry support line's x at the
    deck's lateral edges to the exit line's: the edges are ±deck_width/2, or — without a deck width —
    the outermost node lines (a wheel outside them then sees the rigidly extrapolated overhang only
    within that extent).
    """

    modes: NodalModes
    circular_frequencies: NDArray[np.float64]  # ω [rad/s]
    damping: NDArray[np.float64]
    strain_lever_arm: NDArray[np.float64]
    girder_lines: Optional[NDArray[np.float64]] = None
    default_lateral_offset: float = 0.0
    default_girder: int = 1
    name: str = ""
    deck_width: Optional[float] = None
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
        if self.deck_width is not None:
            if isinstance(self.deck_width, bool) or not (np.isfinite(self.deck_width) and self.deck_width > 0):
                raise ModeFileError(f"deck_width must be a positive width [m], got {self.deck_width!r}")
            object.__setattr__(self, "deck_width", float(self.deck_width))

    @property
    def skew_tan(self) -> float:
        """tan θ of the support lines' skew [-] (0: square supports)."""
        return self.modes.skew_tan

    @property
    def lateral_edges(self) -> tuple[float, float]:
        """y [m] of the deck's edges (they set a skew deck's x extent): ±deck_width/2, or the outermost
        node lines when no width is known (whichever reach further)."""
        lo, hi = float(self.modes.y[0]), float(self.modes.y[-1])
        if self.deck_width is None:
            return lo, hi
        return min(lo, -0.5 * self.deck_width), max(hi, 0.5 * self.deck_width)

    @property
    def omega(self) -> NDArray[np.float64]:
        return self.circular_frequencies

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        return self.damping

    @property
    def nodal_modes(self) -> NodalModes:
        """The nodal modes (``modes``), under the name the FE models use."""
        return self.modes

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
        """c ∂²w/∂x² on the node line(s) at y (linear between lines, clamped beyond; on a skew deck
        at the point's ξ)."""
        return girder_line_strain(self.modes, self.strain_lever_arm, x, y)


#: the longest strain lever arm of a mode file [m]: the neutral axis of the deepest bridge girders lies a few metres
#: above their bottom fibre
MAX_LEVER_ARM = 20.0


def _floats(text: str, key: str) -> NDArray[np.float64]:
    try:
        return np.array([float(v) for v in text.replace(",", " ").split()])
    except ValueError:
        raise ModeFileError(f"header {key!r}: not a list of numbers: {text!r}") from None


def _one_float(header: dict[str, str], key: str, path: Path) -> Optional[float]:
    """The single number of header ``key``, or None when the file has no such header."""
    if key not in header:
        return None
    v = _floats(header[key], key)
    if v.size != 1:
        raise ModeFileError(f"{path}: header {key!r} must be one number, got {header[key]!r}")
    return float(v[0])


def _skew_tan(skew: float) -> float:
    """tan θ [-] of a skew angle θ [°] (the slab-on-girder deck's formula: a file's skew reads back exactly)."""
    return float(np.tan(np.radians(skew))) if skew else 0.0


def _skew_degrees(skew_tan: float, skew: Optional[float] = None) -> float:
    """θ [°] for ``skew_tan``: the bridge's own ``skew`` when it has one and it gives that tan θ, else
    arctan, moved by up to 64 ulps to an angle that ``_skew_tan`` maps exactly to ``skew_tan`` if
    there is one (else the file also gets a ``skew_tan`` header)."""
    if skew is not None and _skew_tan(float(skew)) == skew_tan:
        return float(skew)
    theta = float(np.degrees(np.arctan(skew_tan)))
    for direction in (np.inf, -np.inf):
        candidate = theta
        for _ in range(64):
            if _skew_tan(candidate) == skew_tan:
                return candidate
            candidate = float(np.nextafter(candidate, direction))
    return theta


def _stations_from_plan(xi: NDArray[np.float64], y: NDArray[np.float64], span: float, path: Path) -> NDArray[np.float64]:
    """The common station of every node from its ξ = x − y tan θ: the mean over the lines, with the first
    and last stations set to 0 and the span when that close; every node within 1e-6 of the span of its station."""
    ys = np.unique(y)
    rows = [np.flatnonzero(y == v) for v in ys]
    if len({r.size for r in rows}) != 1:
        raise ModeFileError(f"{path}: every node line needs the same number of nodes "
                            f"(found {sorted({r.size for r in rows})}) to form an oblique grid")
    order = [r[np.argsort(xi[r], kind="stable")] for r in rows]
    grid = np.array([xi[r] for r in order])  # (n_lines, n_st)
    stations = grid.mean(axis=0)
    tol = 1e-6 * span
    if abs(stations[0]) <= tol:
        stations[0] = 0.0
    if abs(stations[-1] - span) <= tol:
        stations[-1] = span
    off = np.abs(grid - stations[None, :])
    if off.max() > tol:
        j, i = np.unravel_index(np.argmax(off), off.shape)
        raise ModeFileError(f"{path}: the node at x - y tan(skew) = {float(grid[j, i])!r} on line y = {float(ys[j])!r} is "
                            f"{off[j, i]:.3g} m from station {i} ({float(stations[i])!r}, the mean over the lines; allowed "
                            f"1e-6 of the span = {tol:.3g} m): "
                            "with a skew, every line needs a node at every station x = xi + y tan(skew)")
    out = np.empty_like(xi)
    for r in order:
        out[r] = stations
    return out


def write_modes(bridge: ModalBridge, path: str | Path, modes: NodalModes | None = None) -> Path:
    """Write a bridge's nodal modes in the ``vbikit-modes 1`` format (full float precision; a skew
    deck with its ``skew`` header and its stations in an ``xi`` column, so that it reads back exactly).

    ``modes`` defaults to ``bridge.nodal_modes`` (the grid of the slab-on-girder model, the continuous
    beam, imported modes).  The lever arms are the bridge's ``strain_lever_arm`` (a slab-on-girder deck,
    imported modes).
    """
    modes = modes if modes is not None else bridge.nodal_modes  # type: ignore[attr-defined]
    path = Path(path)
    c = bridge.strain_lever_arm if isinstance(bridge, (ImportedModalBridge, SlabOnGirderBridge)) else None
    lines = [f"# {MAGIC}", f"# span = {modes.span!r}",
             "# frequencies_hz = " + ", ".join(repr(float(f)) for f in bridge.frequencies_hz),
             "# omega = " + ", ".join(repr(float(f)) for f in bridge.omega),
             "# damping_ratios = " + ", ".join(repr(float(z)) for z in bridge.damping_ratios)]
    deck = bridge if isinstance(bridge, GirderDeck) else None
    if deck is not None:
        lines.append("# girder_y = " + ", ".join(repr(float(v)) for v in deck.girder_y))
    if c is not None:
        lines.append("# strain_lever_arm = " + ", ".join(repr(float(v)) for v in np.broadcast_to(c, modes.y.shape)))
    lines.append(f"# default_lateral_offset = {bridge.default_lateral_offset!r}")
    if deck is not None:
        lines.append(f"# default_girder = {deck.default_girder!r}")
        if deck.deck_width is not None:
            lines.append(f"# deck_width = {float(deck.deck_width)!r}")
    if modes.skew_tan:
        theta = _skew_degrees(modes.skew_tan, bridge.skew)
        lines.append(f"# skew = {theta!r}")
        if _skew_tan(theta) != modes.skew_tan:  # no angle in degrees gives this tan θ exactly
            lines.append(f"# skew_tan = {modes.skew_tan!r}")
    n = modes.n_modes
    lines.append(",".join(["xi" if modes.skew_tan else "x", "y", *(f"w_{k + 1}" for k in range(n)),
                           *(f"dwdx_{k + 1}" for k in range(n)), *(f"dwdy_{k + 1}" for k in range(n))]))
    yy, xx = np.meshgrid(modes.y, modes.x, indexing="ij")
    table = np.column_stack([xx.ravel(), yy.ravel(), modes.w.reshape(-1, n), modes.wx.reshape(-1, n), modes.wy.reshape(-1, n)])
    def write(tmp: Path) -> None:
        with tmp.open("w") as fh:
            fh.write("\n".join(lines) + "\n")
            np.savetxt(fh, table, fmt="%.17g", delimiter=",")

    return atomic_write(path, write)


def modes_from_file(path: str | Path, damping_ratio: float = 0.02, n_modes: int | None = None) -> ImportedModalBridge:
    """Read a ``vbikit-modes 1`` file (see the module docstring) into an ``ImportedModalBridge``.

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
    _check_frequencies(freqs, "frequencies_hz", "Hz", path)
    omega = _floats(header["omega"], "omega") if "omega" in header else 2.0 * np.pi * freqs
    if omega.size != n:
        raise ModeFileError(f"{path}: omega has {omega.size} values but frequencies_hz has {n}")
    _check_frequencies(omega, "omega", "rad/s", path)
    if not np.allclose(omega, 2.0 * np.pi * freqs, rtol=1e-6, atol=0.0):
        k = int(np.argmax(np.abs(omega - 2.0 * np.pi * freqs) / omega))
        raise ModeFileError(f"{path}: header 'omega' must be 2π × frequencies_hz (within 1e-6): mode {k + 1} has omega "
                            f"{float(omega[k])!r} rad/s and frequencies_hz {float(freqs[k])!r} Hz")
    span = _one_float(header, "span", path)
    if not (np.isfinite(span) and span > 0):
        raise ModeFileError(f"{path}: header 'span' must be one length > 0 [m], got {header['span']!r}")
    skew = _floats(header["skew"], "skew") if "skew" in header else np.zeros(1)
    if skew.size != 1 or not (np.isfinite(skew[0]) and abs(skew[0]) < 90.0):
        raise ModeFileError(f"{path}: header 'skew' must be one angle in degrees, -90 < skew < 90, got {header['skew']!r}")
    skew_tan = _skew_tan(float(skew[0]))
    if "skew_tan" in header:  # exact tan θ (written when no angle in degrees gives it exactly)
        t = _one_float(header, "skew_tan", path)
        if not (np.isfinite(t) and abs(float(np.degrees(np.arctan(t))) - float(skew[0])) <= 1e-6):
            raise ModeFileError(f"{path}: header 'skew_tan' = {header['skew_tan']!r} must be tan(skew) of the header "
                                f"'skew' = {float(skew[0])!r}° (within 1e-6°)")
        skew_tan = float(t)
    want = ["y", *(f"w_{k + 1}" for k in range(n))]
    slopes = [*(f"dwdx_{k + 1}" for k in range(n)), *(f"dwdy_{k + 1}" for k in range(n))]
    if columns[:1] not in (["x"], ["xi"]) or columns[1: 2 + n] != want or columns[2 + n:] not in ([], slopes):
        raise ModeFileError(f"{path}: columns must be x (or xi), y, w_1 … w_{n} [, dwdx_1 … dwdx_{n}, dwdy_1 … dwdy_{n}]; "
                            f"got {columns[:6]}…")
    try:
        table = np.loadtxt(lines[data_start:], delimiter=",", ndmin=2)
    except ValueError:
        raise ModeFileError(f"{path}: every row needs {len(columns)} finite numbers") from None
    if table.shape[1] != len(columns) or not np.all(np.isfinite(table)):
        raise ModeFileError(f"{path}: every row needs {len(columns)} finite numbers")
    if columns[0] == "x" and skew_tan:  # plan x of an oblique mesh: the stations along the lines
        table[:, 0] = _stations_from_plan(table[:, 0] - table[:, 1] * skew_tan, table[:, 1], span, path)
    xs, ys = np.unique(table[:, 0]), np.unique(table[:, 1])
    if table.shape[0] != xs.size * ys.size:
        along = " along the lines" if skew_tan else ""
        raise ModeFileError(f"{path}: nodes must form a full rectangular grid of lines × stations{along} ({ys.size} lines × "
                            f"{xs.size} stations = {xs.size * ys.size} nodes, found {table.shape[0]} rows)")
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
        if skew_tan:  # the spline across the lines runs at constant ξ: d/dy = ∂/∂y + tan θ ∂/∂x
            wy = wy - skew_tan * wx
    keep = n if n_modes is None else min(int(n_modes), n)
    modes = NodalModes(xs, ys, w[:, :, :keep], wx[:, :, :keep], wy[:, :, :keep], skew_tan)
    if "damping_ratios" in header:
        ratios = _floats(header["damping_ratios"], "damping_ratios")
        if ratios.size not in (1, n) or not np.all(np.isfinite(ratios) & (ratios >= 0) & (ratios < 1)):
            raise ModeFileError(f"{path}: header 'damping_ratios' must be 1 or {n} ratios in [0, 1), got "
                                f"{header['damping_ratios']!r}")
        damping = ratios[:keep] if ratios.size == n else ratios
    else:
        damping = damping_ratio
    if "strain_lever_arm" in header:
        lever = _floats(header["strain_lever_arm"], "strain_lever_arm")
        if lever.size not in (1, ys.size):
            raise ModeFileError(f"{path}: strain_lever_arm needs 1 or {ys.size} values, got {lever.size}")
        if not np.all(np.isfinite(lever) & (lever > 0) & (lever <= MAX_LEVER_ARM)):
            raise ModeFileError(f"{path}: header 'strain_lever_arm' must be lengths in (0, {MAX_LEVER_ARM:g}] m (neutral axis to bottom "
                                f"fibre), got {header['strain_lever_arm']!r}")
    else:
        log.warning("%s gives no strain_lever_arm; using %.2f m for strains", path, DEFAULT_LEVER_ARM)
        lever = np.array([DEFAULT_LEVER_ARM])
    girders = _floats(header["girder_y"], "girder_y") if "girder_y" in header else None
    if girders is not None:
        lo, hi = float(ys[0]), float(ys[-1])
        if girders.size < 1 or not np.all(np.isfinite(girders)) or np.any(np.diff(girders) <= 0) \
                or girders[0] < lo - 1e-9 * max(1.0, abs(lo)) or girders[-1] > hi + 1e-9 * max(1.0, abs(hi)):
            raise ModeFileError(f"{path}: header 'girder_y' must be ascending y [m] within the node lines "
                                f"{lo!r} … {hi!r} m, got {header['girder_y']!r}")
    offset = _one_float(header, "default_lateral_offset", path)
    if offset is not None and not (np.isfinite(offset) and abs(offset) <= MAX_LATERAL_OFFSET):
        raise ModeFileError(f"{path}: header 'default_lateral_offset' must be within ±{MAX_LATERAL_OFFSET:g} m, got "
                            f"{header['default_lateral_offset']!r}")
    n_girders = ys.size if girders is None else girders.size
    girder = _one_float(header, "default_girder", path)
    if girder is not None and not (np.isfinite(girder) and girder == int(girder) and 1 <= girder <= n_girders):
        raise ModeFileError(f"{path}: header 'default_girder' must be an integer 1 … {n_girders} (the girders, or node "
                            f"lines, of the file), got {header['default_girder']!r}")
    width = _one_float(header, "deck_width", path)
    if width is not None and not (np.isfinite(width) and float(ys[-1] - ys[0]) <= width <= MAX_DECK_WIDTH):
        raise ModeFileError(f"{path}: header 'deck_width' must be a width [m] from the node lines' spread "
                            f"{float(ys[-1] - ys[0])!r} to {MAX_DECK_WIDTH:g} m, got {header['deck_width']!r}")
    return ImportedModalBridge(
        modes, omega[:keep], damping, lever, girders,
        default_lateral_offset=0.0 if offset is None else offset,
        default_girder=1 if girder is None else int(girder), name=path.stem,
        deck_width=width,
    )


def _check_frequencies(values: NDArray[np.float64], key: str, unit: str, path: Path) -> None:
    """Refuse frequencies that are not finite, > 0 and ascending (header ``key``)."""
    if values.size < 1 or not np.all(np.isfinite(values) & (values > 0)):
        raise ModeFileError(f"{path}: header {key!r} must be one finite frequency > 0 [{unit}] per mode, got "
                            f"{', '.join(map(repr, values.tolist())) or 'none'}")
    if np.any(np.diff(values) < 0):
        raise ModeFileError(f"{path}: header {key!r} must be ascending (the lowest mode first)")

