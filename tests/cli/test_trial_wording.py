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
