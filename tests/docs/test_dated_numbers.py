"""A run time quoted in README.md or docs/*.md is either labelled with the date and the machine
it was measured on (``measured YYYY-MM-DD on …machine…`` in the same section) or not quoted at
all: unlike the computed numbers (generated blocks, tests/docs/test_numbers.py), run times cannot
be recomputed by the tests, so their label is what keeps them from passing for today's."""
from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: a duration: "0.8 ms", "≈ 3 s", "10–20 s", "1.0 min" (not "1 s.d.", not units such as "m/s²")
TIMING = re.compile(r"(?<![\w.=/-])(?:≈\s*)?\d+(?:\.\d+)?(?:\s*[–-]\s*\d+(?:\.\d+)?)?\s?(?:ms|s|min|minutes|seconds)\b"
                    r"(?![²/^]|\.d)")
#: the label a section with run times carries
DATED = re.compile(r"measured (?:on )?\d{4}-\d{2}-\d{2}\b[^.]*?\b(?:machine|cores?)\b", re.S | re.I)
#: durations that are physical quantities of a model or a record, not run times: the words before
#: them say so (a time step, a trigger time, a headway, a gap, an airborne time, a free-vibration
#: time, a PSD segment, an alignment bias, a time stamp in an error message)
PHYSICAL = re.compile(r"(\bdt\b|Δt|\bsteps?\b|trigger|Hann|headway|apart|free\b|airborne|contact for|biased|"
                      r"time 0\.|previous|\| 1\.23\d\d s|\(\d+(\.\d+)? ms, \d+\)|dt²|\bat (\d+(\.\d+)?, )*\d+(\.\d+)? ms|"
                      r"cm \(\d+(\.\d+)? ms)")
#: pages generated from the code or a log of past versions (their times are the history's)
SKIP = {"changelog.md", "references.md"}


def _sections(text: str) -> list[str]:
    out, cur = [], []
    for line in text.splitlines():
        if line.startswith("#") and cur:
            out.append("\n".join(cur))
            cur = []
        cur.append(line)
    out.append("\n".join(cur))
    return out


def undated_run_times() -> list[str]:
    bad = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        if path.name in SKIP:
            continue
        for section in _sections(path.read_text(encoding="utf-8")):
            if DATED.search(section):
                continue
            for line in section.splitlines():
                for m in TIMING.finditer(line):
                    if not PHYSICAL.search(line[max(0, m.start() - 60):m.end() + 20]):
                        bad.append(f"{path.relative_to(ROOT)}: …{line[max(0, m.start() - 50):m.end() + 10]}…")
    return bad


def test_every_quoted_run_time_is_dated():
    bad = undated_run_times()
    assert not bad, ("run times without 'measured YYYY-MM-DD on <machine>' in their section (measure them again "
                     "and label them, or leave the number out):\n" + "\n".join(bad))


def test_the_check_finds_an_undated_run_time(tmp_path, monkeypatch):
    # the detector itself: an undated "takes ≈ 3 s" is found, a dated one and a time step are not
    page = tmp_path / "docs"
    page.mkdir()
    (page / "a.md").write_text("# A\n\nA run takes ≈ 3 s.\n\n# B\n\nIt took 4 s (measured 2026-12-02 on the "
                               "2-core machine).\n\n# C\n\nThe step dt = 1 ms.\n", encoding="utf-8")
    (tmp_path / "README.md").write_text("", encoding="utf-8")
    monkeypatch.setattr(sys.modules[__name__], "ROOT", tmp_path)
    assert [b.split(":")[0] for b in undated_run_times()] == ["docs/a.md"]
