"""An input value is quoted in an error message only as far as it tells which one was given (at most
``vbikit._validation.QUOTED_CHARACTERS``, cut with "..."): a 5,000-character value of a key that takes a name
(a bridge model, a railway deck, a drive-by method, a lifetime block) was echoed in full, 2–5 kB of the file in
one line (a new user's trial, 2026-12-07; docs/cli.md: the file's content is never shown)."""
from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from vbikit._validation import QUOTED_CHARACTERS, short_quotes
from vbikit.errors import VbikitError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
LONG = "X" * 5000


def _scenario():
    from vbikit.scenario import scenario_from_toml

    scenario_from_toml(f'[bridge]\nmodel = "{LONG}"\n[vehicle]\nmodel = "quarter-car"\n[crossing]\nspeed_kmh = 60\n')


def _lifetime():
    from vbikit.lifetime.run import prepare

    prepare({"days": 5, "block": LONG, "traffic": {"records": str(EXAMPLES / "lifetime" / "wim.csv")},
             "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
             "load_effects": [{"kind": "moment", "x": 4.0, "name": "M"}]}, ".")


def _rail():
    from vbikit.rail.spec import parse_rail_spec

    data = tomllib.loads((EXAMPLES / "railway" / "hslm_20m.toml").read_text(encoding="utf-8"))
    data["bridge"]["deck"] = LONG
    parse_rail_spec(data)


def _driveby():
    from vbikit.driveby.spec import parse_driveby

    data = tomllib.loads((EXAMPLES / "driveby" / "DRIVEBY.toml").read_text(encoding="utf-8"))
    data["identification"]["method"] = LONG
    parse_driveby(data)


@pytest.mark.parametrize("parse, key", [(_scenario, "bridge.model"), (_lifetime, "block"), (_rail, "deck"),
                                        (_driveby, "method")])
def test_a_long_value_is_quoted_cut(parse, key):
    with pytest.raises(VbikitError) as err:
        parse()
    message = str(err.value)
    assert key in message and "X" * 10 in message  # it says which key, and shows the value's start
    assert "X" * QUOTED_CHARACTERS not in message and "..." in message, len(message)


def test_short_quotes_keeps_short_values_and_cuts_long_ones():
    assert short_quotes("unknown road class 'Q'; allowed: A, B") == "unknown road class 'Q'; allowed: A, B"
    text = short_quotes(f"deck must be one of steel, got '{'y' * 60}'")
    assert text == "deck must be one of steel, got '" + "y" * (QUOTED_CHARACTERS - 4) + "..."
    # as ``_short`` cuts a repr: 40 characters with the quotes kept, 41 cut to 37 and "..."
    assert short_quotes(f'got "{"z" * 38}"') == f'got "{"z" * 38}"'
    assert short_quotes(f'got "{"z" * 39}"') == 'got "' + "z" * 36 + "..."


def test_a_long_list_after_got_is_cut_to_its_bracket():
    """A validator quoting a list or table it was given (``got [1.0, 1.0, …]``): 3,000 numbers of a drive-by
    file's ``variability.temperature`` made a 15,000-character message (the review of 2026-12-07)."""
    text = short_quotes("temperature: expected two numbers, got [" + ", ".join(["1.0"] * 3000) + "] (x)")
    assert text.endswith("...  (x)".replace("  ", " ")) and len(text) < 120, text
    assert short_quotes("got [1, 2]; got (a)") == "got [1, 2]; got (a)"
