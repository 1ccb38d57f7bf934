"""The numbers the docs quote are what the code computes today (docs/scripts/doc_numbers.py wrote
docs/figures/numbers.json; the pages render it through generated blocks)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


STORED = json.loads((ROOT / "docs" / "figures" / "numbers.json").read_text())
HINT = "the code no longer gives the numbers the docs quote: run python docs/scripts/doc_numbers.py, then generate.py"


def test_fig9_table_is_reproduced(docs_script):
    # the same four crossings again; the solver is deterministic (measured: equal to the last digit)
    now = docs_script("doc_numbers").fig9()
    for label, row in STORED["fig9"].items():
        for key, value in row.items():
            assert now[label][key] == pytest.approx(value, rel=1e-9, abs=1e-9), f"{label} {key}: {HINT}"


def test_roughness_readings_are_reproduced(docs_script):
    now = docs_script("doc_numbers").roughness()
    for key, value in STORED["roughness"].items():
        assert now[key] == pytest.approx(value, rel=1e-9), f"{key}: {HINT}"


def _close(now, stored, where, hint: str = HINT, abs_tol: float = 1e-12):
    """Every number in ``stored`` (nested dicts and lists) equals the one in ``now`` (rel 1e-9, ``abs_tol``;
    ``hint``: what to run when they differ).  Also used by tests/verification/test_convergence_numbers.py."""
    if isinstance(stored, dict):
        assert set(now) == set(stored), f"{where}: {hint}"
        for key, value in stored.items():
            _close(now[key], value, f"{where}.{key}", hint, abs_tol)
    elif isinstance(stored, list):
        assert len(now) == len(stored), f"{where}: {hint}"
        for i, (a, b) in enumerate(zip(now, stored)):
            _close(a, b, f"{where}[{i}]", hint, abs_tol)
    elif isinstance(stored, float):
        assert now == pytest.approx(stored, rel=1e-9, abs=abs_tol), f"{where}: {hint}"
    else:
        assert now == stored, f"{where}: {hint}"


def test_demo_numbers_and_figure_are_reproduced(docs_script):
    # the README and the docs home show docs/figures/demo.png and quote the demo's IM: both must be
    # what `vbikit demo` gives today (the figure records the IM it was drawn with)
    from PIL import Image

    module = docs_script("doc_numbers")
    now = module.demo()
    _close(now, STORED["demo"], "demo")
    with Image.open(ROOT / "docs" / "figures" / "demo.png") as png:
        note = png.info.get("Description")
    assert note == module.demo_figure_note(STORED["demo"]), \
        f"docs/figures/demo.png was not drawn from the demo's numbers ({note!r}): {HINT}"


def test_example_load_effects_are_reproduced(docs_script):
    _close(docs_script("doc_numbers").examples(), STORED["examples"], "examples")


def test_field_example_numbers_are_reproduced(docs_script):
    # the synthetic field test of docs/field.md, calibration included (about a minute)
    _close(docs_script("doc_numbers").field(), STORED["field"], "field")
