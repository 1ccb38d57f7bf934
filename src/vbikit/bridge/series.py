"""A series of simply supported spans in a row, each its own bridge (deck), or rigid.

Spans k = 0 … n−1 occupy x ∈ [o_k, o_k + L_k] with o_k = Σ_{i<k} L_i.  Each span is a modal
bridge of its own (typically a [`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge] with its
own bearings) or ``None``: rigid (road on ground, no modes).  Nothing connects the spans (the
joints between them carry no moment or shear), so the modes of the series are the union of the
spans' modes, each zero outside its own span:

    φ_(k,i)(x, y) = φ_i^(k)(x − o_k, y) on span k, 0 elsewhere.

A mode is continuous (zero at the joint bearings) but its slope jumps at the joints; the solver
interpolates the tabulated shapes with cubics, so that jump is smoothed over one table cell
(L_total / (100 n_modes)), a local error at the joints only.  Responses are read by default on
the ``instrumented`` span (its midspan, its default girder); load effects are those of the span
containing the section, shifted by o_k.

A series whose instrumented span is a [`GirderDeck`][vbikit.bridge.GirderDeck] is one itself
(``SpanSeries(...)`` then returns a ``GirderSpanSeries``, with that span's girders).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any, Optional

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge.base import DescribesModes, GirderDeck, HasLoadEffects, ModalBridge
from vbikit.bridge.effects import LoadEffect
from vbikit.bridge.girder_deck import SlabOnGirderBridge


@dataclass(frozen=True, eq=False)
class SpanSeries(ModalBridge):
    """Simply supported spans in a row (see the module docstring).

    Parameters
    ----------
    spans : sequence of ModalBridge or None
        The spans in the direction of travel; None = a rigid span (of length from ``lengths``).
    lengths : sequence of float, optional
        Span lengths [m]; default each bridge's ``span`` (required for rigid spans).
    instrumented : int
        0-based index of the span whose midspan and default girder responses are read at.
    name : str
        Label.
    """

    spans: tuple[Optional[ModalBridge], ...]
    lengths: Optional[tuple[float, ...]] = None
    instrumented: int = -1
    name: str = "span-series"
    span: float = field(init=False)

    def __new__(cls, *args: Any, **kwargs: Any) -> "SpanSeries":
        """A ``GirderSpanSeries`` when the instrumented span is a girder deck."""
        if cls is SpanSeries and (args or "spans" in kwargs):
            spans = tuple(args[0] if args else kwargs["spans"])
            instrumented = args[2] if len(args) > 2 else kwargs.get("instrumented", -1)
            main = spans[instrumented % len(spans)] if spans else None
            if isinstance(main, GirderDeck):
                cls = GirderSpanSeries
        return super().__new__(cls)

    def __post_init__(self) -> None:
        spans = tuple(self.spans)
        if not spans:
            raise ValueError("a span series needs at least one span")
        lengths = tuple(float(b.span) if b is not None else np.nan for b in spans) if self.lengths is None \
            else tuple(float(v) for v in self.lengths)
        if len(lengths) != len(spans) or any(not (np.isfinite(v) and v > 0) for v in lengths):
            raise ValueError(f"lengths: one positive length [m] per span (rigid spans need one), got {self.lengths!r}")
        for k, (b, L) in enumerate(zip(spans, lengths)):
            if b is not None and abs(b.span - L) > 1e-9 * L:
                raise ValueError(f"span {k}: its bridge is {b.span:g} m long, not {L:g} m")
            if b is not None and b.deck_extent != (0.0, float(b.span)):
                raise ValueError(f"span {k}: a skew deck cannot be part of a span series (its ends are not at "
                                 "x = 0 and its span); give its spans to one deck with [bridge.deck] spans")
        k = self.instrumented % len(spans)
        if spans[k] is None:
            raise ValueError(f"instrumented span {k} is rigid: choose a span with a bridge model")
        if all(b is None for b in spans):
            raise ValueError("every span is rigid: nothing vibrates")
        object.__setattr__(self, "spans", spans)
        object.__setattr__(self, "lengths", lengths)
        object.__setattr__(self, "instrumented", k)
        object.__setattr__(self, "span", float(sum(lengths)))

    # ------------------------------------------------------------------ layout
    @property
    def offsets(self) -> NDArray[np.float64]:
        """x [m] of each span's entry support."""
        return np.concatenate([[0.0], np.cumsum(self.lengths)[:-1]])

    @property
    def instrumented_offset(self) -> float:
        """x [m] of the instrumented span's entry support."""
        return float(self.offsets[self.instrumented])

    @property
    def support_x(self) -> NDArray[np.float64]:
        return np.concatenate([[0.0], np.cumsum(self.lengths)])

    @cached_property
    def _order(self) -> tuple[NDArray[np.float64], NDArray[np.intp], NDArray[np.intp]]:
        """ω of all modes ascending, and for each its span and index within the span."""
        om, span, idx = [], [], []
        for k, b in enumerate(self.spans):
            if b is None:
                continue
            om.append(b.omega)
            span.append(np.full(b.omega.size, k))
            idx.append(np.arange(b.omega.size))
        om, span, idx = np.concatenate(om), np.concatenate(span), np.concatenate(idx)
        order = np.argsort(om, kind="stable")
        return om[order], span[order], idx[order]

    # ------------------------------------------------------------------ ModalBridge
    @property
    def omega(self) -> NDArray[np.float64]:
        return self._order[0]

    @property
    def damping_ratios(self) -> NDArray[np.float64]:
        _, span, idx = self._order
        return np.array([self.spans[k].damping_ratios[i] for k, i in zip(span, idx)])  # type: ignore[union-attr]

    def _assemble(self, method: str, x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
        x, y = np.broadcast_arrays(np.atleast_1d(np.asarray(x, float)), np.atleast_1d(np.asarray(y, float)))
        x, y = x.ravel(), y.ravel()
        _, span, idx = self._order
        out = np.zeros((x.size, span.size))
        for k, (b, o, L) in enumerate(zip(self.spans, self.offsets, self.lengths)):
            if b is None:
                continue
            on = (x >= o) & (x <= o + L)
            if np.any(on):
                cols = np.flatnonzero(span == k)
                out[np.ix_(on, cols)] = getattr(b, method)(x[on] - o, y[on])[:, idx[cols]]
        return out

    def mode_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self._assemble("mode_shapes", x, y)

    def mode_slopes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self._assemble("mode_slopes", x, y)

    def strain_shapes(self, x: ArrayLike, y: ArrayLike = 0.0) -> NDArray[np.float64]:
        return self._assemble("strain_shapes", x, y)

    # ------------------------------------------------------------------ defaults of the instrumented span
    @property
    def _main(self) -> ModalBridge:
        return self.spans[self.instrumented]  # type: ignore[return-value]

    @property
    def default_lateral_offset(self) -> float:  # type: ignore[override]
        return float(self._main.default_lateral_offset)

    @property
    def default_section(self) -> float:  # type: ignore[override]
        """Midspan [m] of the instrumented span."""
        return self.instrumented_offset + 0.5 * self.lengths[self.instrumented]

    @property
    def default_response_y(self) -> float:
        return float(self._main.default_response_y)

    @property
    def n_modes(self) -> int:
        """Number of modes of the series (the spans' modes added)."""
        return int(self.omega.size)

    @property
    def n_vibrating_spans(self) -> int:
        """Number of spans with a bridge model (not rigid)."""
        return sum(b is not None for b in self.spans)

    @property
    def element_count(self) -> int:
        """Elements along the whole series (the grillage spans' own counts added)."""
        return int(sum(b.element_count for b in self.spans if isinstance(b, SlabOnGirderBridge)))

    @property
    def span_lengths(self) -> tuple[float, ...]:
        """Length [m] of every span, entry first."""
        return tuple(self.lengths)  # type: ignore[arg-type]

    def span_index(self, x: float) -> int:
        xs = self.support_x
        return int(np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(self.lengths) - 1))

    def mode_descriptions(self) -> list[str]:
        """"span k: <the span's own description>" for every mode."""
        _, span, idx = self._order
        own = {k: (b.mode_descriptions() if isinstance(b, DescribesModes) else None)
               for k, b in enumerate(self.spans) if b is not None}
        return [f"span {k + 1}: " + (own[k][i] if own[k] is not None else f"mode {i + 1}") for k, i in zip(span, idx)]

    # ------------------------------------------------------------------ load effects
    def load_effect(self, kind: str, x: Optional[float] = None, support: Optional[int] = None,
                    girder: Optional[int] = None) -> LoadEffect:
        """The load effect of the span containing section x (reaction ``support``: 2 k = entry and
        2 k + 1 = exit bearing of span k), shifted to the series' x."""
        if kind == "reaction":
            if support is None or not 0 <= int(support) < 2 * len(self.spans):
                raise ValueError(f"reaction: support must be 0 … {2 * len(self.spans) - 1} (entry and exit of each span)")
            k, local = divmod(int(support), 2)
        else:
            if x is None or not 0.0 <= x <= self.span:
                raise ValueError(f"{kind}: section x must be within 0 … {self.span:g} m, got {x!r}")
            k = self.span_index(float(x))
            local = None
        b = self.spans[k]
        if not isinstance(b, HasLoadEffects):
            raise ValueError(f"{kind}: span {k} is rigid or offers no load effects")
        o = float(self.offsets[k])
        kw = {} if girder is None else {"girder": girder}
        e = b.load_effect(kind, x=None if x is None else float(x) - o, support=local, **kw)  # type: ignore[attr-defined]
        _, span, idx = self._order
        modal = np.zeros(span.size)
        cols = np.flatnonzero(span == k)
        modal[cols] = e.modal[idx[cols]]
        L = self.lengths[k]

        def influence(xp, yp, e=e, o=o, L=L):
            xp = np.asarray(xp, float).ravel()
            yp = np.broadcast_to(np.asarray(yp, float), xp.shape).ravel()
            out = np.zeros(xp.size)
            on = (xp >= o) & (xp <= o + L)
            if np.any(on):
                out[on] = e.influence(xp[on] - o, yp[on])
            return out

        return replace(e, x=e.x + o, modal=modal, influence=influence, support=None if local is None else int(support))

    def default_load_effects(self, girder: Optional[int] = None) -> list[LoadEffect]:
        """The instrumented span's default load effects."""
        o = self.instrumented_offset
        k = self.instrumented
        out = []
        if not isinstance(self._main, HasLoadEffects):
            raise ValueError(f"span {self.instrumented} offers no load effects")
        for e in self._main.default_load_effects(**({} if girder is None else {"girder": girder})):  # type: ignore[call-arg]
            if e.kind == "reaction":
                out.append(self.load_effect("reaction", support=2 * k + int(e.support), girder=girder))
            else:
                out.append(self.load_effect(e.kind, x=e.x + o, girder=girder))
        return out


@dataclass(frozen=True, eq=False)
class GirderSpanSeries(SpanSeries):
    """A ``SpanSeries`` whose instrumented span is a girder deck: its girders are the series' girders."""

    @property
    def _deck(self) -> GirderDeck:
        return self._main  # type: ignore[return-value]

    @property
    def default_girder(self) -> int:
        return int(self._deck.default_girder)

    @property
    def girder_y(self) -> NDArray[np.float64]:
        return self._deck.girder_y

    @property
    def deck_width(self) -> Optional[float]:
        """Deck width [m] of the instrumented span."""
        w = self._deck.deck_width
        return None if w is None else float(w)

    @property
    def n_girders(self) -> int:
        return int(self._deck.n_girders)

    def girder_index(self, girder: int) -> int:
        return self._deck.girder_index(girder)
