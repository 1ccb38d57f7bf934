"""One style table for the design-code reference lines of every figure: each code its own colour,
dash and end marker, so that codes with close values (AASHTO LRFD 0.330, JTG D60-2015 0.336 for a
7.3 Hz bridge) stay apart.  The colours avoid matplotlib's first three cycle colours, which the
data lines of the study figures use."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class CodeStyle:
    """How a design code's allowance is drawn: ``label`` in the legend, matplotlib ``color``,
    ``linestyle`` and ``marker`` (drawn at the line's right end)."""

    label: str
    color: str
    linestyle: Any
    marker: str


#: design code key (``vbikit.analysis.codes.code_allowances``) → its style
CODE_STYLES: dict[str, CodeStyle] = {
    "aashto_lrfd": CodeStyle("AASHTO LRFD", "tab:red", "--", "v"),
    "aashto_standard": CodeStyle("AASHTO Standard 50/(L+125)", "tab:purple", ":", "s"),
    "csa_s6": CodeStyle("CSA S6", "tab:brown", "-.", "D"),
    "ohbdc_1983": CodeStyle("OHBDC 1983", "tab:gray", (0, (5, 1, 1, 1)), "^"),
    "jtg_d60_2015": CodeStyle("JTG D60-2015", "tab:olive", (0, (1, 1)), "o"),
}


def code_line(ax: Any, key: str, value: float, label: str | None = None) -> Any:
    """Draw the allowance ``value`` of code ``key`` across ``ax`` in its style (legend entry
    ``label``, default "<code> = <value>")."""
    s = CODE_STYLES[key]
    return ax.axhline(value, color=s.color, ls=s.linestyle, lw=1.0, marker=s.marker, markevery=[1], ms=5,
                      clip_on=False, label=label or f"{s.label} = {value:.3f}")
