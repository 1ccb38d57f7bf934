"""The pages describe the present; history goes to docs/changelog.md.  A few words that only a page
telling history uses (README's benchmark note once read "This table predates the step rule …", and
docs/railway.md "2.4 % before the limits were read") are refused outside the changelog."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [p for p in sorted((ROOT / "docs").rglob("*.md")) if p.name != "changelog.md"] + [ROOT / "README.md"]
#: words of history: what the code did before, not what it does
HISTORY = re.compile(r"\b(predates|previously|formerly|used to be|before the [a-z-]+ (?:was|were) [a-z]+)\b", re.I)


def test_the_pattern_finds_history():
    assert HISTORY.search("This table predates the step rule")
    assert HISTORY.search("2.4 % before the limits were read")
    assert not HISTORY.search("the limits are read where an axle enters")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_page_tells_history(page):
    found = [m.group(0) for m in HISTORY.finditer(page.read_text(encoding="utf-8"))]
    assert found == [], f"{page.relative_to(ROOT)}: {found} (history belongs in docs/changelog.md)"
