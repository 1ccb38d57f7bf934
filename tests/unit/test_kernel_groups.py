"""``kernel_groups`` (the test run's workers share its groups out) does ``compile_kernels``' work:
every variant of every integrator in exactly one group, so that nothing ``vbikit compile``
compiles is left to the tests and no variant is run by two groups, the run-in's crossing with the
default integrator's one-lane variant (whose kernel it runs) and the static start's kernels in a group
of their own, first (checked on the variant kinds and on the calls made; nothing is compiled here)."""
from __future__ import annotations

from collections import Counter

import pytest

from vbikit.solve import warmup
from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR
from vbikit.solve.integrators import get_integrator, integrator_names


def test_every_variant_of_every_integrator_is_in_exactly_one_group(monkeypatch):
    calls: list[tuple[str, str]] = []

    def recording_variants(name: str) -> dict:
        kinds = ["one-lane", "lanes"] if get_integrator(name).explicit else ["one-lane", "rigid-disk", "lanes"]
        return {k: (lambda k=k: calls.append((name, k))) for k in kinds}

    expected = Counter((name, k) for name in integrator_names() for k in recording_variants(name))
    monkeypatch.setattr(warmup, "_variants", recording_variants)
    monkeypatch.setattr(warmup, "_moving_loads", lambda: calls.append(("moving-loads", "sweep")))
    monkeypatch.setattr(warmup, "_run_in", lambda: calls.append(("run-in", "loops")))
    monkeypatch.setattr(warmup, "_static_starts", lambda: calls.append(("static-starts", "start")))
    by_group = {}
    for group, run in warmup.kernel_groups().items():
        calls.clear()
        run()
        by_group[group] = list(calls)
    got = Counter(call for group_calls in by_group.values() for call in group_calls)
    assert got == expected + Counter({("moving-loads", "sweep"): 1, ("run-in", "loops"): 1, ("static-starts", "start"): 1})
    assert list(by_group)[0] == warmup.SHARED_GROUP and by_group[warmup.SHARED_GROUP] == [("static-starts", "start")]
    # the run-in's crossing (the default integrator, one lane) runs in the group compiling that variant, after it
    run_in_group = next(g for g, c in by_group.items() if ("run-in", "loops") in c)
    assert by_group[run_in_group][-1] == ("run-in", "loops")
    assert (DEFAULT_INTEGRATOR, "one-lane") in by_group[run_in_group]


def test_the_variant_kinds_are_those_of_the_warm_up_crossings():
    """The kinds the test above assumes are the ones ``_variants`` builds (its crossings are built,
    not run)."""
    for name in integrator_names():
        kinds = list(warmup._variants(name))
        want = ["one-lane", "lanes"] if get_integrator(name).explicit else ["one-lane", "rigid-disk", "lanes"]
        assert kinds == want
        if not get_integrator(name).explicit:
            grouped = [k for ks in warmup.IMPLICIT_GROUPS.values() for k in ks]
            assert sorted(grouped) == sorted(want)  # each implicit kind in one group


@pytest.mark.parametrize("name", ["static-starts", "implicit-lean", "implicit-full", "implicit-lanes", "rk4", "moving-loads"])
def test_the_groups_are_named(name):
    assert name in warmup.kernel_groups()
