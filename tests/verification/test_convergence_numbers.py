"""The default integrator's convergence study in docs/verification.md ("Exact modal stepping:
convergence"): the page quotes docs/figures/convergence-numbers.json (written by
docs/scripts/convergence_numbers.py), the stored numbers keep the page's bound at the automatic step,
and (slow: about half a minute once numba's cache is warm) the script computes them again.

The reference of every ΔIM is independent of the integrator under study: classical RK4 at its own
automatic step (and at a quarter of it, the reference's own error)."""
from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HINT = "run python docs/scripts/convergence_numbers.py, then python docs/scripts/generate.py"


def _script(name: str = "convergence_numbers"):
    """docs/scripts/``name``.py loaded as a module (also used by test_paper_accuracy_numbers.py)."""
    spec = importlib.util.spec_from_file_location(f"vbikit_docs_{name}", ROOT / "docs" / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_page_quotes_the_stored_numbers():
    script = _script()
    numbers = script.stored()
    page = (ROOT / "docs" / "verification.md").read_text(encoding="utf-8")
    assert script.render_steps(numbers) in page, HINT
    assert script.render_automatic(numbers) in page, HINT


def test_stored_numbers_are_the_scripts_cases():
    # every case of the script is stored, the step study's cases with one change per fixed step
    script = _script()
    numbers = script.stored()
    assert list(numbers["cases"]) == list(script.CASES), HINT
    assert numbers["steps"] == list(script.STEPS) and numbers["near_steps"] == list(script.NEAR_STEPS), HINT
    for name, case in numbers["cases"].items():
        assert ("steps" in case) == (name in script.STEP_STUDY), name
        assert len(case.get("steps", script.STEPS)) == len(script.STEPS), name


def test_every_case_is_within_the_bound_at_the_automatic_step():
    """The claim of the page (its bound is ``BOUND`` of the script, rendered into the page): at the
    automatic step |IM(exact) − IM(RK4 reference)| ≤ BOUND on every listed case, with fewer steps
    than the reference."""
    script = _script()
    numbers = script.stored()
    for name, case in numbers["cases"].items():
        auto, ref = case["automatic"], case["reference"]
        assert abs(auto["im_change"]) <= script.BOUND, f"{name}: ΔIM = {auto['im_change']:.2e} > {script.BOUND}"
        assert auto["n_steps"] < ref["n_steps"], name
    page = (ROOT / "docs" / "verification.md").read_text(encoding="utf-8")
    assert f"every case is within {script.bound_text()}" in page


def test_the_bound_check_sees_a_case_above_it():
    # the claim's check itself: a stored case pushed just above the bound is found, and the page's
    # sentence then says so
    script = _script()
    numbers = json.loads(json.dumps(script.stored()))
    case = next(iter(numbers["cases"].values()))
    case["automatic"]["im_change"] = -1.01 * script.BOUND
    name, change = script.largest(numbers, script.automatic_change)
    assert change > script.BOUND and numbers["cases"][name] is case
    assert "every case is above" in script.render_automatic(numbers)


@pytest.mark.slow
def test_the_script_reproduces_the_stored_numbers():
    # the whole study again (≈ 30–40 s warm, the 11 crossings at 1 + 1 + 1 + 8 + 1 steps, 4 of them at 6 more)
    recomputed_equals_stored(_script(), "convergence-numbers")


def recomputed_equals_stored(script, where: str, hint: str = HINT, abs_tol: float = 1e-15) -> None:
    """A docs script's numbers computed again equal its stored ones, but the date and run time (also
    used by test_paper_accuracy_numbers.py)."""
    from tests.docs.test_numbers import _close as close

    stored, now = script.stored(), script.compute()
    for key in ("date", "wall_s"):
        stored.pop(key), now.pop(key)
    close(now, stored, where, hint, abs_tol)
