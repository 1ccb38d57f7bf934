"""``vbikit run --plot`` / ``Report.plot``: every requested point drawn (on main only the headline
point), and no panel or legend overlapping another panel (on main the tire-force legend sat on
its curves)."""
from __future__ import annotations

import numpy as np
import pytest

import vbikit
import vbikit.plot.crossing as pc

SCENARIO = """
[bridge]
model = "continuous-beam"
spans = [12.0, 12.0]
EI = 8.323e9
mass_per_length = 2303.0
n_modes = 6
[vehicle]
model = "hs20-44"
[road]
class = "none"
[crossing]
speed = 20.0
approach = 0.0
[[response.points]]
name = "west"
x = 6.0
[[response.points]]
name = "east"
x = 18.0
[[response.points]]
name = "pier"
x = 12.5
"""


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    report = vbikit.run(SCENARIO)
    figs = []
    real = pc.save_figure
    pc.save_figure = lambda fig, path, **kw: figs.append(fig) or real(fig, path, **kw)
    try:
        path = report.plot(tmp_path_factory.mktemp("fig") / "crossing.png")
    finally:
        pc.save_figure = real
    return report, figs[0], path


def test_every_requested_point_is_drawn(drawn):
    report, fig, path = drawn
    assert path.stat().st_size > 10_000
    disp = fig.axes[0]
    for p in report.points:  # each point's dynamic displacement [mm] is one of the panel's lines
        assert any(np.array_equal(line.get_ydata(), p.displacement * 1e3) for line in disp.get_lines()), p.x
    legend = [t.get_text() for t in disp.get_legend().get_texts()]
    assert [t.split(" ")[0] for t in legend[:3]] == ["west", "east", "pier"]
    for name in ("west", "east", "pier"):
        assert name in disp.get_title()


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_no_panel_or_legend_overlaps_another_panel(drawn):
    _, fig, _ = drawn
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()  # the saved figure's canvas was released
    fig.draw(renderer)
    panels = [ax.get_tightbbox(renderer) for ax in fig.axes]  # ticks, labels and legends included
    for i in range(len(panels)):
        for j in range(i + 1, len(panels)):
            assert not _overlap(panels[i], panels[j]), (i, j)
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is not None:  # a legend covers no plotting area, its own or another's
            box = legend.get_window_extent(renderer)
            for other in fig.axes:
                assert not _overlap(box, other.get_window_extent(renderer))
    assert fig.axes[3].get_legend() is not None  # the tire forces are named
