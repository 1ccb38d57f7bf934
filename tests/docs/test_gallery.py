"""Every gallery script runs and writes its figure (the site shows the figures these scripts make)."""
from __future__ import annotations

import re
import runpy
from pathlib import Path

import pytest

GALLERY = Path(__file__).resolve().parents[2] / "examples" / "gallery"
SCRIPTS = sorted(GALLERY.glob("plot_*.py"))


def test_there_are_at_least_six():
    assert len(SCRIPTS) >= 6


#: what each script's result must show (its module globals after the run)
CHECKS = {
    # least squares on the synthetic records recovers the truth (measured 1.1002 vs 1.10, 0.0252 vs 0.025)
    "field_calibration": lambda g: abs(g["cal"].stiffness_factor - g["truth"].stiffness_factor) < 0.005
    and abs(g["cal"].damping_ratio - g["truth"].damping_ratio) < 0.001,
    # the study has one dimension per axis: 2 tire settings × 5 speeds × 8 samples
    "parameter_study": lambda g: dict(g["ds"]["impact_factor"].sizes) == {"tire_n_points": 2, "crossing_speed_kmh": 5, "sample": 8},
    # the oblique mesh softens the transverse modes with skew (docs/bridges.md, "Skew supports")
    "skew_deck": lambda g: all(b[2] < a[2] for a, b in zip(g["frequencies"], g["frequencies"][1:])),
    # pseudo-excitation: sampled crossings stay inside ±3σ (99.7 % for a Gaussian; 20 roads, so ≥ 97 %
    # allows for their correlation), and the IM mean matches vbikit's 1,000 Monte-Carlo crossings
    # (0.197, docs/random.md) within twice their standard error (0.1/√1000 ≈ 0.003) plus the 0.5 % grid
    "random_vibration": lambda g: g["inside"] >= 0.97 and abs(g["s"]["impact_factor_mean"] - 0.197) < 0.01,
    # two vehicles in one run (one front-axle history each)
    "two_trucks": lambda g: g["result"].front_position.shape[1] == 2,
}


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_gallery_script_writes_its_figure(script, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.setenv("VBIKIT_GALLERY_OUT", str(tmp_path))
    result = runpy.run_path(str(script), run_name="__main__")
    plt.close("all")
    name = re.sub(r"^plot_(\d+_)?", "", script.stem)
    figure = tmp_path / f"{name}.png"
    assert figure.is_file() and figure.stat().st_size > 10_000
    if name in CHECKS:
        assert CHECKS[name](result), f"{script.name}: its result is not what its page says"
    assert (Path(__file__).resolve().parents[2] / "docs" / "gallery" / "figures" / figure.name).is_file(), \
        "run `python docs/scripts/generate.py --gallery` to put the figure on the site"
