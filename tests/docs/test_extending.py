"""docs/extending.md: every Python block runs as written (in order, one fresh process, in a
temporary folder), so the worked examples of a new output, tire model and integrator cannot go
stale; each block asserts its own independent check."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

PAGE = Path(__file__).resolve().parents[2] / "docs" / "extending.md"


def test_the_page_has_the_three_worked_examples():
    text = PAGE.read_text(encoding="utf-8")
    for title in ("## A new output", "## A new tire model", "## A new integrator"):
        assert title in text, title


def test_every_python_block_runs(tmp_path):
    blocks = re.findall(r"```python\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)
    assert len(blocks) >= 5
    res = subprocess.run([sys.executable, "-c", "\n".join(blocks)], cwd=tmp_path, capture_output=True, text=True,
                         timeout=600)
    assert res.returncode == 0, res.stderr[-4000:]
    # the peaks the page quotes are the ones the example prints today
    printed = re.search(r"peak midspan displacement: point (-?[\d.]+) mm, parabolic patch \(n = 5\) (-?[\d.]+) mm",
                        res.stdout)
    quoted = re.search(r"It prints the two peaks \(−([\d.]+) mm and −([\d.]+) mm", PAGE.read_text(encoding="utf-8"))
    assert printed and quoted, res.stdout[-2000:]
    assert [f"-{q}" for q in quoted.groups()] == list(printed.groups()), (printed.groups(), quoted.groups())
