"""The design-code allowances of `vbikit run` by what is on the span.

CSA S6 (S6-14 / S6:19 clause 3.8.4.5.3, dynamic load allowance): 0.40 when only one axle of the
CL-W truck is on the span, 0.30 for two axles, 0.25 for three or more — the axles that can be on
the span at once, not the truck's axles (second source: LL Analyzer's truckGroupDla, 40 / 30 / 25 %
by the axles selected on the spans, docs/bridges.md).  Worked by hand below from the axle positions:
HS20-44 axles at 0, 4.267, 8.534 m; the "axles" truck [4, 14] m at 0, 4, 18 m.

A railway vehicle gets no highway allowances: EN 1991-2:2003 6.4.5.2 Eq. 6.4 Φ2 = 1.44/(√L_Φ − 0.2)
+ 0.82 (1.00 … 1.67) and Eq. 6.5 Φ3 = 2.16/(√L_Φ − 0.2) + 0.73 (1.00 … 2.00), L_Φ the span of a
simply supported girder (Table 6.2): for L = 15 m Φ2 = 1.44/3.67298 + 0.82 = 1.21205,
Φ3 = 2.16/3.67298 + 0.73 = 1.31807."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.analysis.codes import axles_on_span, csa_s6
from vbikit.cli import app

runner = CliRunner()

BEAM = """
[bridge]
model = "beam"
span = {span}
EI = {EI}
mass_per_length = 6000.0
n_modes = 2
{vehicles}
[crossing]
speed_kmh = {speed}
"""


def _run(tmp_path: Path, text: str, *args: str):
    path = tmp_path / "s.toml"
    path.write_text(text)
    return runner.invoke(app, ["run", str(path), *args])


def _json(tmp_path: Path, text: str) -> dict:
    res = _run(tmp_path, text, "--json")
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


# ------------------------------------------------------------------------- axles on the span
def test_axles_on_span_by_hand():
    hs20 = [0.0, 4.267, 8.534]
    # a 2 m span holds one HS20-44 axle, 5 m two (4.267 m apart), 9 m all three (8.534 m < 9 m)
    assert [axles_on_span(hs20, L) for L in (2.0, 5.0, 9.0)] == [1, 2, 3]
    # two axles exactly a span apart: the rear one is on the far support, not on the span with the front one
    assert axles_on_span(hs20, 4.267) == 1 and axles_on_span(hs20, 4.3) == 2
    # the 3-axle truck with a 14 m gap: 0, 4, 18 m -> at most two of them within 12 m (CSA S6: 0.30, not 0.25)
    assert axles_on_span([0.0, 4.0, 18.0], 12.0) == 2 and csa_s6(axles_on_span([0.0, 4.0, 18.0], 12.0)) == 0.30
    # the two wheels of an axle (same offset) and vehicles side by side at one offset are one axle
    assert axles_on_span([0.0, 0.0, 0.0004, 3.0, 3.0], 10.0) == 2
    # several configurations (rows, e.g. instants of two vehicles meeting): the most of any row
    assert axles_on_span([[0.0, 20.0, 25.0], [0.0, 5.0, 6.0]], 8.0) == 3
    with pytest.raises(ValueError, match="span"):
        axles_on_span(hs20, 0.0)


@pytest.mark.parametrize("span, n, dla", [(2.0, 1, 0.40), (6.0, 2, 0.30), (10.0, 3, 0.25)])
def test_hs20_csa_by_axles_on_the_span(tmp_path, span, n, dla):
    # the old count (every axle of the truck: 3 -> 0.25) failed the 2 m and 6 m spans
    s = _json(tmp_path, BEAM.format(span=span, EI=2e8 * span**2, speed=30,
                                    vehicles='[vehicle]\nmodel = "hs20-44"'))
    c = s["design_code_allowances"]
    assert c["n_axles"] == n and c["csa_s6"] == dla
    assert c["aashto_lrfd"] == 0.33


def test_axle_truck_with_gap_longer_than_span(tmp_path):
    # axles at 0, 4, 18 m on a 12 m span: two at most together -> CSA S6 0.30 (the old code: 3 axles, 0.25)
    veh = '[vehicle]\nmodel = "axles"\naxle_loads = [50e3, 100e3, 100e3]\naxle_spacings = [4.0, 14.0]'
    c = _json(tmp_path, BEAM.format(span=12.0, EI=5e9, speed=40, vehicles=veh))["design_code_allowances"]
    assert c["n_axles"] == 2 and c["csa_s6"] == 0.30


def test_two_vehicles_count_as_placed(tmp_path):
    # two moving forces on the same path, the second entering 0.5 s later at 36 km/h = 10 m/s: 5 m
    # apart on a 12 m span -> two axles on the span at once (CSA S6 0.30); each vehicle alone has one
    # axle offset (0), which the old count (distinct offsets) took for one axle (0.40)
    veh = "\n".join(f'[[vehicles]]\nmodel = "moving-force"\nforce = 1e5\nentry_time = {t}' for t in (0.0, 0.5))
    c = _json(tmp_path, BEAM.format(span=12.0, EI=5e9, speed=36, vehicles=veh))["design_code_allowances"]
    assert c["n_axles"] == 2 and c["csa_s6"] == 0.30


def test_text_explains_the_count(tmp_path):
    res = _run(tmp_path, BEAM.format(span=2.0, EI=8e8, speed=30, vehicles='[vehicle]\nmodel = "hs20-44"'))
    assert res.exit_code == 0, res.output
    assert "CSA S6 0.400" in res.output
    assert "CSA S6 by 1 axle, the most axles on a span of the loaded length at once" in res.output


# ------------------------------------------------------------------------------- railway
def test_railway_vehicle_gets_en1991_2_factors_not_highway_codes(tmp_path):
    text = BEAM.format(span=15.0, EI=2e10, speed=200, vehicles='[vehicle]\nmodel = "hslm-a1"')
    s = _json(tmp_path, text)
    c = s["design_code_allowances"]
    phi2 = 1.44 / (math.sqrt(15.0) - 0.2) + 0.82  # EN 1991-2 Eq. 6.4
    phi3 = 2.16 / (math.sqrt(15.0) - 0.2) + 0.73  # EN 1991-2 Eq. 6.5
    assert c["railway"] is True
    assert c["en1991_2_phi2"] == pytest.approx(phi2, rel=1e-12) and round(phi2, 4) == 1.2121
    assert c["en1991_2_phi3"] == pytest.approx(phi3, rel=1e-12) and round(phi3, 4) == 1.3181
    assert not {"aashto_lrfd", "aashto_standard", "csa_s6", "ohbdc_1983", "jtg_d60_2015", "n_axles"} & set(c)
    for e in s["moment"]["sections"]:
        assert e["code_allowances"]["railway"] is True and "csa_s6" not in e["code_allowances"]
    res = _run(tmp_path, text)
    assert res.exit_code == 0, res.output
    assert "EN 1991-2 Phi2 1.212  Phi3 1.318" in res.output and "vbikit rail" in res.output
    assert "CSA S6" not in res.output and "AASHTO" not in res.output
