"""Fuzz tests of ``vbikit lifetime``, ``vbikit driveby`` and ``vbikit rail`` (generated inputs:
``fuzz_commands.py``), judged through ``vbikit validate`` — the checks each command makes before it
computes: never a traceback, a hang, an input file's content in a message, or an input that must
be refused (NaN, infinity, a boolean or string for a number, 1e300, a tiny positive length or
speed, an unknown key, a damaged CSV input) accepted.  The default run tries 25 inputs a command
(derandomised); the ``slow`` variants 700 a command (2,100 in all), randomly.  With
``VBIKIT_FUZZ_LOG=path`` every outcome is appended to that file (JSON lines) instead of asserted:
that is how the counts in docs/changelog.md were measured.
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import pytest
from fuzz_commands import HANG_SECONDS, command_inputs, fuzz_settings, outcome, write_input
from fuzzing import time_limit
from hypothesis import given
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
LOG = os.environ.get("VBIKIT_FUZZ_LOG")


def check(kind: str, inputs) -> None:
    data, refuse, files = inputs
    with tempfile.TemporaryDirectory() as tmp:
        path = write_input(Path(tmp), kind, data, files)
        with time_limit(HANG_SECONDS):
            result = runner.invoke(app, ["validate", str(path)])
        verdict = outcome(result, refuse)
        text = path.read_text()
    if LOG:
        with open(LOG, "a") as fh:
            fh.write(json.dumps({"kind": kind, "outcome": verdict, "refuse": refuse, "damage": files.get("_damage"),
                                 "output": "" if result is None else result.output[-300:], "input": text[:1500]}) + "\n")
        return
    assert verdict in ("ok", "clean"), f"{kind}: {verdict}\n--- input ---\n{text}\n--- output ---\n" + \
        ("" if result is None else result.output)



KINDS = ("lifetime", "driveby", "rail")


@pytest.mark.parametrize("kind, n", [*((k, 25) for k in KINDS), *(pytest.param(k, 700, marks=pytest.mark.slow) for k in KINDS)])
def test_fuzz_commands(kind, n):
    """25 generated inputs a command (derandomised); under ``slow`` 700 a command (2,100 in all), randomly."""
    @fuzz_settings(n, slow=n > 25)
    @given(command_inputs(kind))
    def run(inputs):
        check(kind, inputs)

    run()
