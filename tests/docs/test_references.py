"""The bibliography says, for every DOI, how it was confirmed or what was searched without
confirming it (docs/references.md prints it; generated from vbikit.references)."""
from __future__ import annotations

from vbikit.references import REFERENCES


def test_every_doi_says_how_it_was_checked():
    missing = [r.key for r in REFERENCES.values() if r.doi and not r.verification]
    assert not missing, f"entries with a DOI but no verification note: {missing}"


def test_checked_and_unconfirmed_agree_with_the_note():
    # an entry counted as checked names the record it was checked against; an unchecked one says
    # that it is unconfirmed and what was searched
    for r in REFERENCES.values():
        if not r.doi:
            continue
        if r.checked:
            assert r.verification.startswith("Checked against"), r.key
        else:
            assert "unconfirmed" in r.verification.lower() and "searched" in r.verification, r.key
            assert "not yet checked" in r.text(), r.key


def test_the_founding_paper_entry_states_what_is_missing():
    paper = REFERENCES["MultiPointTire"]
    assert paper.title == "A Multi-Point Tire Model for Studying Bridge–Vehicle Coupled Vibration"
    assert "Unconfirmed" in paper.verification and "searched" in paper.verification.lower()
