"""The test run is free of numerical warnings from vbikit's own code: pyproject.toml turns any
RuntimeWarning raised in a vbikit module into an error, and the sources the suite used to warn
from are fixed (a continuous beam of absurd length is refused before its element matrices
overflow); the documented examples run without any warning."""
from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def test_pytest_turns_runtime_warnings_from_vbikit_into_errors():
    options = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["pytest"]["ini_options"]
    assert "error::RuntimeWarning:vbikit" in options["filterwarnings"]


def test_a_span_beyond_the_float_range_of_the_element_matrices_is_refused_without_a_warning():
    from vbikit.bridge import ContinuousBeam

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow inside the FE assembly would raise here instead
        with pytest.raises(OverflowError, match=r"bridge\.spans: each span at most 100000 m, got 1e\+300 m"):
            ContinuousBeam(spans=(55.0, 1e300), EI=5e9, mass_per_length=5000.0)


@pytest.mark.parametrize("example", ["examples/bridges/three_span_continuous_hs20.toml",
                                     "examples/bridges/skew_grillage_hs20.toml"])
def test_documented_examples_run_without_any_warning(example):
    import vbikit

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        vbikit.run(str(ROOT / example))
    ours = [f"{w.filename}:{w.lineno}: {w.category.__name__}: {w.message}" for w in caught if "vbikit" in w.filename]
    assert not ours, ours
