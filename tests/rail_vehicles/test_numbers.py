# The rail-vehicle numbers the docs quote (docs/figures/railveh-numbers.json, written by
# docs/scripts/railveh_numbers.py) are what the code computes now.
from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "docs" / "scripts" / "railveh_numbers.py"
NUMBERS = ROOT / "docs" / "figures" / "railveh-numbers.json"


def _script():
    spec = importlib.util.spec_from_file_location("railveh_numbers", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_presets_and_track_numbers_are_current():
    stored = json.loads(NUMBERS.read_text(encoding="utf-8"))
    script = _script()
    assert stored["presets"] == script.presets()
    assert stored["track"] == script.track()
    assert (ROOT / "docs" / "figures" / "railveh-track-spectra.png").is_file()


@pytest.mark.slow
def test_stiff_contact_numbers_are_current():
    stored = json.loads(NUMBERS.read_text(encoding="utf-8"))["stiff_contact"]
    now = _script().stiff_contact()
    for key, values in stored.items():
        for name, value in values.items():
            if name != "run_s":  # measured wall time, dated in the JSON
                assert now[key][name] == value, (key, name)


@pytest.mark.slow
def test_train_numbers_are_current():
    stored = json.loads(NUMBERS.read_text(encoding="utf-8"))["train"]
    assert _script().train() == stored
