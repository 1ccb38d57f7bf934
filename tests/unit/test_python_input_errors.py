"""Bad inputs given from Python get a clear error naming the argument and what is allowed, not an error from
inside (a new user's trial: ``vbikit.run(42)`` raised ``TypeError: argument of type 'int' is not iterable``,
``EulerBernoulliBeam(span="25")`` numpy's ``ufunc 'isfinite' not supported``, ``paper_beam(16.76, "zzz")`` a bare
``KeyError``)."""
from __future__ import annotations

import pytest

import vbikit
from vbikit.bridge import EulerBernoulliBeam
from vbikit.bridge.presets import paper_beam
from vbikit.scenario import ScenarioError


@pytest.mark.parametrize("source", [42, 2.5, None, ["a.toml"]])
def test_run_names_what_a_scenario_may_be(source):
    with pytest.raises(ScenarioError, match=r"a scenario is a file path, TOML text, a dict of its tables or a Scenario"):
        vbikit.run(source)


@pytest.mark.parametrize("span", ["25", True, float("nan"), -1.0, 0])
def test_a_beam_refuses_a_span_that_is_not_a_positive_number(span):
    with pytest.raises(ValueError, match=r"span must be a positive finite number, got"):
        EulerBernoulliBeam(span=span, EI=8.323e9, mass_per_length=2303.0)


def test_a_paper_beam_names_the_girder_types():
    with pytest.raises(ValueError, match=r"girder_type: unknown 'zzz'; allowed: I, II, III, IV, V, VI"):
        paper_beam(16.76, "zzz")
    assert paper_beam(16.76, "II").span == 16.76
