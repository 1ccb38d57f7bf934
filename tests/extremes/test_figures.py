"""The Gumbel plot is drawn for block-maximum and peaks-over-threshold fits."""
from __future__ import annotations

import numpy as np
from scipy import stats

from vbikit.extremes import fit_block_maxima, fit_peaks_over_threshold, plot_gumbel


def test_gumbel_plot_files(tmp_path):
    rng = np.random.default_rng(1)
    bm = fit_block_maxima(stats.gumbel_r.rvs(loc=50, scale=4, size=120, random_state=rng), "gev", blocks_per_year=250)
    out = plot_gumbel(bm, tmp_path / "gumbel.png", unit="kN m")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pot = fit_peaks_over_threshold(10 + stats.genpareto.rvs(0.1, size=200, random_state=rng), 10.0, rate_per_year=20)
    out = plot_gumbel(pot, tmp_path / "pot.png", periods=[10, 100])
    assert out.stat().st_size > 10_000
