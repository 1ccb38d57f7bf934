"""docs/random.md quotes the numbers docs/scripts/random_numbers.py wrote to
docs/figures/random-numbers.json (run the script again when the code changes them); a slow test
recomputes them."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGE = (ROOT / "docs" / "random.md").read_text(encoding="utf-8")
STORED = ROOT / "docs" / "figures" / "random-numbers.json"


def quoted(n: dict) -> list[str]:
    """The strings of ``n`` the page must contain."""
    qc, d = n["quarter_car_error_pct"], n["demo"]
    disp, acc = d["displacement"], d["acceleration"]

    def rng(r):
        return f"{r[0]:.4f}–{r[1]:.4f}"

    q = " / ".join
    return [f"body displacement {qc['body_displacement']:g} %", f"body acceleration {qc['body_acceleration']:g} %",
            f"{qc['tire_force']:g} %",
            f"against {d['crossings']:,} Monte-Carlo", f"at {disp['inside_pct']:g} % (mid-span displacement)",
            f"{acc['inside_pct']:g} %", f"median {disp['ratio_median']:.4f} (5–95 %: {rng(disp['ratio_5_95'])})",
            f"{acc['ratio_median']:.4f} ({rng(acc['ratio_5_95'])})",
            f"by PEM {d['im_pem']['mean']:.3f} (sampling error\n{d['im_sampling_error']:.4f}) and "
            + q(f"{d['im_pem'][k]:.3f}" for k in ("0.5", "0.9", "0.95")),
            f"by Monte Carlo {d['im_mc']['mean']:.3f} and " + q(f"{d['im_mc'][k]:.3f}" for k in ("0.5", "0.9", "0.95")),
            "cross-check gives " + q(f"{d['im_crossings'][k]:.3f}" for k in ("0.5", "0.9", "0.95")),
            f"({d['n_lines']} lines,"]


def test_page_quotes_the_stored_numbers():
    numbers = json.loads(STORED.read_text())
    missing = [s for s in quoted(numbers) if s not in PAGE]
    assert not missing, f"docs/random.md does not quote {missing}: run python docs/scripts/random_numbers.py"
    # what the page claims of them
    assert max(numbers["quarter_car_error_pct"].values()) < 1.0
    assert numbers["demo"]["displacement"]["inside_pct"] >= 95 and numbers["demo"]["acceleration"]["inside_pct"] >= 95


@pytest.mark.slow
def test_stored_numbers_are_current(tmp_path):
    before = STORED.read_text()
    try:
        subprocess.run([sys.executable, str(ROOT / "docs" / "scripts" / "random_numbers.py"), "--no-figure"], check=True, cwd=ROOT,
                       capture_output=True)
        assert json.loads(STORED.read_text()) == json.loads(before)
    finally:
        STORED.write_text(before)
