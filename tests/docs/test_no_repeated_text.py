"""The documentation pages hold no stutter: a run of words written twice in a row, as an edit that
pasted a clause again leaves it (docs/cli.md's exit codes once read "…: its usage typer itself
refuses, such as `--workers 0` or a missing `--out`: its usage …")."""
from __future__ import annotations

from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
PAGES = sorted(DOCS.rglob("*.md")) + [DOCS.parent / "README.md"]
#: the shortest run of words counted as a stutter when it directly repeats itself
RUN = 8


def stutters(text: str, run: int = RUN, longest: int = 80) -> list[str]:
    """The first words of every run of ``run`` … ``longest`` words immediately followed by the same
    words (a stretch where word j equals word j + p for p consecutive j, p the run's length)."""
    words = text.split()
    found = []
    for p in range(run, longest + 1):
        same = 0
        for j in range(len(words) - p):
            same = same + 1 if words[j] == words[j + p] else 0
            if same == p:
                found.append(" ".join(words[j - p + 1:j - p + 1 + min(p, 12)]))
    return found


def test_the_check_finds_a_pasted_clause():
    text = "An option typer itself refuses, such as `--workers 0` or a missing `--out`: its usage " * 2
    assert stutters("before " + text + "after")
    assert not stutters("a b c d e f g h i j k l m n o p")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(DOCS.parent)))
def test_no_page_repeats_a_run_of_words(page):
    assert stutters(page.read_text(encoding="utf-8")) == []
