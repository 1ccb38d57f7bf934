"""Every population dataset stores its flags as records (attribute ``flags``, JSON: code, message, output, subject,
value, threshold), beside the "; "-joined ``warnings`` and the ``flag_codes``, and every summary reads them back
(``dataset_flags``): before 2026-12-08 only a traffic stream's dataset carried records, and a study's summary gave its
warnings as one joined string, which a program cannot split (messages hold "; " themselves)."""
from __future__ import annotations

import numpy as np

from vbikit.analysis.checks import Flag, add_dataset_flags, dataset_flag_attrs, dataset_flags

A = Flag("small_static", "point p2: small static reference; see the report", point="p2", value=np.float64(0.1),
         threshold=0.2)
B = Flag("contact_not_converged", "3 crossings: contact forces not converged", value=np.int64(3))


def test_records_round_trip_with_numpy_numbers_and_messages_holding_semicolons():
    attrs = dataset_flag_attrs([A, B, Flag("strain_not_converged", "strain off at p1")])
    assert attrs["warnings"] == f"{A.message}; {B.message}; strain off at p1"
    assert attrs["flag_codes"] == "small_static,contact_not_converged,strain_not_converged"
    records, warnings = dataset_flags(attrs)
    assert [r["code"] for r in records] == ["small_static", "contact_not_converged", "strain_not_converged"]
    assert warnings == [A.message, B.message, "strain off at p1"]  # (three messages, though one holds "; ")
    assert records[0]["point"] == "p2" and records[0]["value"] == 0.1 and records[1]["value"] == 3
    assert dataset_flag_attrs([]) == {}


def test_flags_added_later_go_after_and_a_message_is_not_repeated():
    attrs = {"title": "t", **dataset_flag_attrs([A])}
    out = add_dataset_flags(attrs, [A, B])
    assert out["title"] == "t" and out["flag_codes"] == "small_static,contact_not_converged"
    assert out["warnings"] == f"{A.message}; {B.message}"
    assert [r["code"] for r in dataset_flags(out)[0]] == ["small_static", "contact_not_converged"]


def test_a_dataset_written_before_the_records_gives_its_joined_warnings_as_one_message():
    assert dataset_flags({"warnings": "a; b", "flag_codes": "small_static"}) == ([], ["a; b"])
    assert dataset_flags({}) == ([], [])


def test_flags_added_to_a_dataset_written_before_the_records_keep_its_messages():
    """A review found them dropped: the new records alone were then read back as every message."""
    old = {"warnings": f"a msg; {A.message}", "flag_codes": "small_static"}
    out = add_dataset_flags(old, [A, B])  # (A is among the old messages: not repeated)
    records, warnings = dataset_flags(out)
    assert warnings == [f"a msg; {A.message}", B.message] and records[0]["code"] is None
    assert out["flag_codes"] == "small_static,contact_not_converged"


def test_a_small_static_share_ignores_a_nan_peak_elsewhere_in_the_crossing():
    from vbikit.analysis.checks import small_static_dataset_flags

    (flag,) = small_static_dataset_flags(["p1", "p2", "p3"], np.array([[1.0, 0.1, np.nan], [1.0, 0.15, 0.5]]))
    assert flag.point == "p2" and flag.value == 0.1

