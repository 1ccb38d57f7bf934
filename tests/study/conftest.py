"""Small studies shared by the study tests (Bridge 2 beam, 4 modes, short roads: ~10 ms a crossing)."""
from __future__ import annotations

import copy

import pytest

SMALL = {
    "name": "small test study",
    "seed": 11,
    "batch_size": 3,
    "base": {
        "bridge": {"model": "paper-bridge-2-beam", "n_modes": 4},
        "vehicle": {"model": "two-axle"},
        "tire": {"model": "multipoint", "n_points": 3},
        "road": {"class": "C", "length": 200},
        "crossing": {"speed_kmh": 90},
    },
    "axes": {
        "tire.n_points": [1, 4],
        "road.class": ["B", "D"],
        "road.seed": {"samples": 3},
    },
}


@pytest.fixture
def small_study_dict():
    return copy.deepcopy(SMALL)
