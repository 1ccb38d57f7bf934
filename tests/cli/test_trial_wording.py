"""Wording a new user's trial found wrong (2026-12-07): an existing read-only output folder was said to be
impossible to create, and a lifetime estimate of seconds printed as "0.00 h"."""
from __future__ import annotations

import os

import pytest

from vbikit._files import OutputError, output_dir


def test_an_existing_folder_that_is_not_writable_is_said_so(tmp_path, monkeypatch):
    ro = tmp_path / "ro"
    ro.mkdir()
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode: False if os.path.abspath(p) == str(ro) else real(p, mode))
    with pytest.raises(OutputError, match=r"^--out-dir .*ro: the folder is not writable$"):
        output_dir(ro, create=False)
    # a folder still to make inside it: that it cannot be created there
    with pytest.raises(OutputError, match=r"cannot create the folder in .*ro \(not writable\)$"):
        output_dir(ro / "new", create=False)


@pytest.mark.parametrize("hours, words", [(0.011, "40 s (0.011 h)"), (0.2, "12 min (0.2 h)"), (3.5, "3.5 h")])
def test_a_lifetime_estimate_is_said_in_seconds_minutes_or_hours(hours, words):
    from vbikit.lifetime.run import _estimate

    assert _estimate(hours) == words


def test_an_implausible_bridge_marks_its_load_effect_ims_too(tmp_path):
    """EI = 1e7 N m² (a unit mistake): the run says no result is meaningful and marks the headline IM "!"; the
    load-effect table's IMs were printed unmarked (the second trial, 2026-12-07)."""
    from typer.testing import CliRunner

    from vbikit.cli import app

    path = tmp_path / "implausible.toml"
    path.write_text('[bridge]\nmodel = "beam"\nspan = 20.0\nEI = 1e7\nmass_per_length = 25000.0\ndamping_ratio = 0.01\n'
                    'n_modes = 4\n[vehicle]\nmodel = "sprung-mass"\n[crossing]\nspeed_kmh = 60\n[response]\nmoment = [10.0]\n')
    res = CliRunner().invoke(app, ["run", str(path)])
    assert res.exit_code == 0, res.output
    (line,) = [x for x in res.stdout.splitlines() if x.strip().startswith("moment ")]
    assert "!  codes" in line, line
