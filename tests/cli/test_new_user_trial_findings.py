"""What a new user's trial of the shipped examples found (2026-12-06, main at 226cc2d), each test
failing on the code before its fix:

1. ``vbikit run SCENARIO --random`` printed ``peak displacement -2.3691 ± 0.1981 mm`` with no word
   of what ± means (a standard deviation over the road's realisations, not a confidence interval)
   and closed with ``wavenumber lines: 254, grid check 0.69%; 2.5 s`` — a bare time and a check
   without its meaning.
"""
from __future__ import annotations

from types import SimpleNamespace

from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()


def _random_summary() -> dict:
    """A PEM summary with the keys the text report reads (the demo's numbers, rounded)."""
    return {
        "name": "demo", "method": "pseudo-excitation", "warnings": [], "effects": [],
        "points": [{"x": 8.38, "y": 0.0, "displacement_peak_mean": -2.369e-3, "displacement_peak_std": 0.198e-3,
                    "static_peak": -1.969e-3, "impact_factor_mean": 0.203, "impact_factor_std": 0.101,
                    "impact_factor_quantiles": {"0.5": 0.196, "0.9": 0.337, "0.95": 0.381},
                    "displacement_std_max": 0.314e-3, "acceleration_std_max": 0.586, "strain_std_max": 8.6e-6}],
        "wheel_force_std_max": {}, "vehicle_acceleration_std_max": {}, "lift_off_probability": 0.0052,
        "n_lines": 254, "grid_change": 0.0069, "seconds": 2.5, "quality": "…",
    }


def test_random_report_says_what_plus_minus_and_the_closing_numbers_are(tmp_path, monkeypatch):
    import vbikit.scenario.pipeline as pipeline

    monkeypatch.setattr(pipeline, "run_random", lambda scenario, limits=None: SimpleNamespace(summary=_random_summary()))
    scenario = tmp_path / "s.toml"
    scenario.write_text("[bridge]\n", encoding="utf-8")  # (not read: the run is replaced)
    out = runner.invoke(app, ["run", str(scenario), "--random"])
    assert out.exit_code == 0, out.output
    text = out.stdout
    assert "mean ± standard deviation over the road's realisations" in text
    assert text.index("standard deviation") < text.index("peak displacement")  # said before the first ±
    assert "grid check 0.69% (σ on every second line against every line); run time 2.5 s" in text
