"""The documentation: the site builds strictly, generated pages match the code, and no file in
the repository points outside it."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_generated_pages_match_the_code(docs_script):
    stale = docs_script("generate").stale(write=False)
    assert not stale, f"regenerate with `python docs/scripts/generate.py`: {', '.join(stale)} differ from the code"


def test_site_builds_strictly(strict_site):
    # --strict turns every warning (broken link or anchor, page missing from the nav's files,
    # docstring cross-reference that does not resolve) into a failure; the run builds the site once
    # (the session fixture ``strict_site``, shared with the API-reference tests)
    assert strict_site["returncode"] == 0, strict_site["output"]
    page = Path(strict_site["site"]) / "api" / "solve" / "index.html"
    assert page.is_file()
    assert "CrossingResult" in page.read_text()


def _repo_files() -> list[Path]:
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout.split()
    return [ROOT / f for f in out if (ROOT / f).is_file()]


# the pointers are assembled from parts so that this file does not match itself
_OUTSIDE = re.compile("|".join([r"\.\./" + "shared", "shared/" + "reference", "shared/" + "paper", "/" + "work/",
                                "domain" + "-data", "ecosystem" + "-notes", "beyond" + "-the-paper", "style" + "-anchors"]))
_TEXT = {".py", ".md", ".toml", ".txt", ".yml", ".yaml", ".cfg", ".json", ".bib", ".csv", ".sh", ""}


def test_no_file_points_outside_the_repository():
    hits = []
    for path in _repo_files():
        if path.suffix not in _TEXT or path.stat().st_size > 2_000_000:
            continue
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for n, line in enumerate(text.splitlines(), start=1):
            if _OUTSIDE.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()[:100]}")
    assert not hits, "write the fact into the project's docs with its source instead:\n" + "\n".join(hits)


_LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def test_markdown_links_resolve_inside_the_repository():
    # mkdocs checks the site's pages; this also covers README.md, benchmarks/ and examples/
    bad = []
    for path in _repo_files():
        if path.suffix != ".md":
            continue
        for target in _LINK.findall(path.read_text(encoding="utf-8")):
            if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                continue
            dest = (path.parent / target.split("#")[0]).resolve()
            if not dest.is_relative_to(ROOT) or not dest.exists():
                bad.append(f"{path.relative_to(ROOT)}: {target}")
    assert not bad, "links that leave the repository or do not resolve:\n" + "\n".join(bad)


def test_every_markdown_table_has_its_separator_row():
    # a table whose header is not followed by |---| renders as raw text (it happened on the
    # verification page); generated pages included
    bad = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]:
        lines = path.read_text(encoding="utf-8").splitlines()
        in_code = False
        for i, line in enumerate(lines):
            if line.lstrip().startswith("```"):
                in_code = not in_code
            if in_code or not (line.startswith("|") and line.rstrip().endswith("|")):  # a table row, not prose
                continue
            starts_table = i == 0 or not lines[i - 1].startswith("|")
            if starts_table and not re.match(r"^\|(\s*:?-{3,}:?\s*\|)+\s*$", lines[i + 1] if i + 1 < len(lines) else ""):
                bad.append(f"{path.relative_to(ROOT)}:{i + 1}: {line[:80]}")
    assert not bad, "tables without a separator row after their header:\n" + "\n".join(bad)
