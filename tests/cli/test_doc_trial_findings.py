"""What a new-user trial of the documentation found (2026-12-06), each test failing on the code and
docs before the fix (main at 25ba07d):

1. ``docs/random.md`` ran ``vbikit run demo.toml --random``, but no ``demo.toml`` ships and the page
   did not say how to get one;
2. ``vbikit validate`` called a measured response CSV's key ``[[case]].file``; a FIELD.toml's key is
   ``responses`` (``file`` is refused as an unknown key);
3. a wheel's contact-loss flag off the bridge printed its deck track as ``x from -0.000``.
"""
from __future__ import annotations

import re
from pathlib import Path

from typer.testing import CliRunner

from vbikit.cli import app
from vbikit.field.io import FIELD_KEYS

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


def test_random_page_scenario_files_exist_or_are_written_first():
    text = (ROOT / "docs" / "random.md").read_text(encoding="utf-8")
    block = re.search(r"```console\n(.*?)```", text, re.S).group(1)
    written: set[str] = set()
    for line in block.splitlines():
        line = line.removeprefix("$ ").split("#")[0]
        if m := re.search(r">\s*(\S+\.toml)\s*$", line):
            written.add(m.group(1))
            continue
        for name in re.findall(r"vbikit run (\S+\.toml)", line):
            assert name in written or (ROOT / name).is_file(), f"docs/random.md runs {name}: neither shipped nor written"


def test_random_page_demo_toml_command_writes_the_demo_scenario(tmp_path):
    # the page's first line, run as written, gives a scenario that validates
    text = (ROOT / "docs" / "random.md").read_text(encoding="utf-8")
    code = re.search(r'python -c "(.*?)" > demo.toml', text).group(1)
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(code, {})
    path = tmp_path / "demo.toml"
    path.write_text(out.getvalue(), encoding="utf-8")
    result = runner.invoke(app, ["validate", str(path)])
    assert result.exit_code == 0, result.output
    assert "ok" in result.output


def test_validate_names_the_field_key_of_a_response_csv():
    result = runner.invoke(app, ["validate", str(ROOT / "examples" / "field" / "case1_responses.csv")])
    assert result.exit_code == 0, result.output
    key = re.search(r"\[\[case\]\]\.(\w+)", result.output).group(1)
    assert key in FIELD_KEYS["case"], f"validate names [[case]].{key}, not a FIELD.toml case key"


def test_contact_loss_off_the_bridge_prints_no_negative_zero(tmp_path):
    # 3. at speed = 75 (m/s, a km/h value in the wrong key) the front wheels leave the road after the
    # bridge; the flag printed the deck track's start as "x from -0.000" (a round-off below zero)
    from vbikit.scenario import demo_scenario_text

    path = tmp_path / "fast.toml"
    path.write_text(demo_scenario_text().replace("speed_kmh = 75", "speed = 75"), encoding="utf-8")
    result = runner.invoke(app, ["run", str(path)])
    assert result.exit_code == 0, result.output
    assert "lost contact with the road only after the bridge (its track on the deck: x from 0.000 to 16.760 m)" \
        in result.output
    assert "-0.000" not in result.output


def test_traffic_road_option_names_itself_with_the_allowed_classes(tmp_path):
    """A new user's trial (2026-12-06): ``vbikit traffic --road Q`` reported the scenario key
    ``road.class``; it is refused as the option it is, before any run, with the classes allowed."""
    stream = Path(__file__).resolve().parents[2] / "examples" / "traffic" / "stream.csv"
    res = CliRunner().invoke(app, ["traffic", str(stream), "--bridge", "paper-bridge-2", "--road", "Q",
                                   "--out", str(tmp_path / "t.nc")])
    assert res.exit_code == 2
    text = res.output + (res.stderr if res.stderr_bytes is not None else "")
    assert "'--road'" in text and "unknown road class 'Q'" in text and "A, B, C, D, E, F, G, H" in text
    assert "psd" not in text.split("allowed:")[1]
    assert not (tmp_path / "t.nc").exists()
