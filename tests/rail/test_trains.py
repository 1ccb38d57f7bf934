"""Trains: HSLM-A against EN 1991-2:2003 Table 6.3 and the axle lists of SincBridgeDynamics.jl, the ICE 3
preset against its source's geometry and masses, CSV tables."""
import numpy as np
import pytest

from vbikit.vehicle.trains import HSLM_A_TABLE, TRAIN_PRESETS, TrainError, get_train, hslm_a, hslm_b, ice3, parse_train_table

#: EN 1991-2:2003 (+ AC) Table 6.3 (N intermediate coaches, D [m], d [m], P [kN]), written out here
TABLE_E1 = {1: (18, 18, 2.0, 170), 2: (17, 19, 3.5, 200), 3: (16, 20, 2.0, 180), 4: (15, 21, 3.0, 190),
            5: (14, 22, 2.0, 170), 6: (13, 23, 2.0, 180), 7: (13, 24, 2.0, 190), 8: (12, 25, 2.5, 190),
            9: (11, 26, 2.0, 210), 10: (11, 27, 2.0, 210)}
#: second source: SincBridgeDynamics.jl (antonioaro), src/TRAIN_MODELS.jl — number of axles and the
#: last axle's position [m] of its A_1 … A_10 lists
JULIA_COUNT_LAST = {1: (50, 397.525), 2: (48, 398.525), 3: (46, 397.525), 4: (44, 394.525), 5: (42, 389.525),
                    6: (40, 382.525), 7: (40, 397.525), 8: (38, 387.525), 9: (36, 375.525), 10: (36, 388.525)}
#: the first twelve axles of its A_2 (d = 3.5 m, unequal to the power-car bogie's 3 m) and A_8 (d = 2.5 m)
JULIA_A2_HEAD = [0.0, 3.0, 14.0, 17.0, 20.525, 24.025, 36.0125, 39.5125, 55.0125, 58.5125, 74.0125, 77.5125]
JULIA_A8_TAIL = [342.5125, 345.0125, 364.5, 367.0, 370.525, 373.525, 384.525, 387.525]


@pytest.mark.parametrize("k", range(1, 11))
def test_hslm_a_against_table_e1_and_julia(k):
    n, D, d, P = TABLE_E1[k]
    assert HSLM_A_TABLE[k] == (n, D, d, P)
    t = get_train(f"hslm-a{k}")
    assert t.name == f"HSLM-A{k}"
    count, last = JULIA_COUNT_LAST[k]
    assert t.n_axles == count == 2 * n + 14
    assert t.length == pytest.approx(last, abs=1e-9)
    np.testing.assert_allclose(t.axle_loads, P * 1e3)
    assert t.coach_length == D


def test_hslm_a_axle_lists_match_julia_where_d_differs():
    np.testing.assert_allclose(hslm_a(2).axle_positions[:12], JULIA_A2_HEAD, atol=1e-9)
    np.testing.assert_allclose(hslm_a(8).axle_positions[-8:], JULIA_A8_TAIL, atol=1e-9)


def test_presets_registry_names():
    assert [f"hslm-a{k}" for k in range(1, 11)] == [n for n in TRAIN_PRESETS if n.startswith("hslm-a")]
    with pytest.raises(TrainError, match="hslm-a1"):
        get_train("hslm-a11")


def test_ice3_from_goicolea_geometry_and_masses():
    t = ice3()
    assert t.n_axles == 32
    # 200.32 m over the noses (Goicolea 2014) less 2 × (4.76 − 1.25) m from each nose to its first axle
    assert t.length == pytest.approx(200.32 - 2 * (4.76 - 1.25), abs=1e-9)
    # axle load g ((M_c/2 + M_t)/2 + M_w): 9.81 × ((23900 + 3500)/2 + 1800) = 152 055 N; cars 4, 5: 135 868.5 N
    np.testing.assert_allclose(t.axle_loads[:4], 152055.0)
    np.testing.assert_allclose(t.axle_loads[12:20], 135868.5)
    np.testing.assert_allclose(t.axle_positions[:6], [0.0, 2.5, 17.375, 19.875, 24.775, 27.275])
    assert len(t.cars) == 8


def test_hslm_b_and_its_limits():
    t = hslm_b(12, 2.75)
    assert t.n_axles == 12 and t.length == pytest.approx(11 * 2.75)
    np.testing.assert_allclose(t.axle_loads, 170e3)
    with pytest.raises(TrainError, match="spacing"):
        hslm_b(10, 0.1)


def test_table_file_parsing_and_errors():
    t = parse_train_table("position_m,load_kN\n# a comment\n5.0, 100\n7.5, 120\n\n20, 90\n", "mine")
    np.testing.assert_allclose(t.axle_positions, [0.0, 2.5, 15.0])
    np.testing.assert_allclose(t.axle_loads, [100e3, 120e3, 90e3])
    with pytest.raises(TrainError, match="line 3: axle positions must increase"):
        parse_train_table("0,100\n5,100\n4,100\n", "bad")
    with pytest.raises(TrainError, match="line 2: load must be within"):
        parse_train_table("0,100\n5,-3\n", "bad")
    with pytest.raises(TrainError, match="line 2: position .m. and load .kN. must be numbers"):
        parse_train_table("0,100\n5,abc\n", "bad")


@pytest.mark.parametrize("header", ["", "position_m,load_kN\n", "position [m], load [kN]\n", "Position (m),Load (kN)\n",
                                    "position,load\n", "# a comment\nPOSITION_M , LOAD_KN\n"])
def test_table_headers_that_name_the_documented_columns(header):
    """docs/railway.md: one axle a line 'position [m], load [kN]', an optional header line naming
    them; empty cells after the two (a spreadsheet's export) are ignored."""
    t = parse_train_table(header + "10.0,150\n12.5,160,\n30,170,,\n", "t", "my.csv")
    np.testing.assert_allclose(t.axle_positions, [0.0, 2.5, 20.0])  # shifted to start at 0, by hand
    np.testing.assert_allclose(t.axle_loads, [150e3, 160e3, 170e3])


#: text that is no train table, or not a physical one, and the message (each names the file and line)
NOT_A_TRAIN = [
    # accepted before: any first line was skipped as a header (the issue: 'foo,bar' then '1,2' read as one axle)
    ("foo,bar\n1,2\n", "my.csv, line 1: not a train table: its header's column 1 is not 'position'"),
    ("position,weight\n0,100\n", "my.csv, line 1: not a train table: its header's column 2 is not 'load'"),
    ("a,b\nc,d\n0,100\n", "my.csv, line 1: not a train table"),
    ("position_m,load_kN\nposition_m,load_kN\n0,100\n", "my.csv, line 2: position [m] and load [kN] must be numbers"),
    ("0,abc\n3,100\n", "my.csv, line 1: position [m] and load [kN] must be numbers"),
    ("position_mm,load_kN\n0,100\n", "column 1 (position) another unit than m"),
    ("position [m],load [t]\n0,100\n", "column 2 (load) another unit than kN"),
    ("axle,position,load\n1,0,100\n", "my.csv, line 1: expected two columns 'position [m], load [kN]', got 3"),
    ("0,100,2\n3,100,2\n", "my.csv, line 1: expected two columns"),
    ("0,100\n5000.5,100\n", "my.csv, line 2: this axle is more than 5000 m behind the first"),
    # refused before too
    ("position_m,load_kN\n", "my.csv: no axles"),
    ("# only a comment\n\n", "my.csv: no axles"),
    ("7\n", "my.csv, line 1: expected two columns"),
    ("0,100\n3,0\n", "my.csv, line 2: load must be within 0 … 10000 kN"),
    ("0,-100\n", "my.csv, line 1: load must be within 0 … 10000 kN"),
    ("0,20000\n", "my.csv, line 1: load must be within 0 … 10000 kN"),
    ("0,100\nnan,100\n", "my.csv, line 2: position and load must be finite"),
    ("0,inf\n", "my.csv, line 1: position and load must be finite"),
    ("0,100\n3,100\n3,100\n", "my.csv, line 3: axle positions must increase"),
    ("0,100\n3,100\n2,100\n", "my.csv, line 3: axle positions must increase"),
]


@pytest.mark.parametrize("text, message", NOT_A_TRAIN)
def test_a_table_that_is_no_train_is_refused_naming_file_and_line(text, message):
    with pytest.raises(TrainError) as err:
        parse_train_table(text, "t", "my.csv")
    assert message in str(err.value)


@pytest.mark.parametrize("text, marker", [
    ("foo-7391,bar-8462\n1,2\n", ("foo", "bar", "7391", "8462")),
    ("position,weight-5173\n0,100\n", ("weight", "5173")),
    ("0,100\n3,98765.25\n", ("98765",)),
    ("0,100\n4321.5,100\n1234.5,100\n", ("4321", "1234")),
    ("0,100\n6789.5,100\n", ("6789",)),
    ("0,100,marker-2468\n", ("marker", "2468")),
])
def test_no_text_of_the_table_in_its_message(text, marker):
    """A message names the file, the line and the expected columns, never what the file holds."""
    with pytest.raises(TrainError) as err:
        parse_train_table(text, "t", "my.csv")
    assert "my.csv, line" in str(err.value)
    assert not [m for m in marker if m in str(err.value)], str(err.value)


def test_a_scenario_names_a_train_as_its_vehicle():
    """`[vehicle] model = "hslm-a4"`: the train's axles as moving forces (one wheel per axle, its
    load fixed, no DOFs) at the Table E.1 load P = 190 kN."""
    from vbikit.scenario import build, parse_scenario

    built = build(parse_scenario({"bridge": {"model": "beam", "span": 20.0, "EI": 1e10, "mass_per_length": 15e3},
                                  "vehicle": {"model": "hslm-a4"}, "crossing": {"speed_kmh": 200}}))
    v = built.crossing.vehicle
    assert v.n_dof == 0 and len(v.wheels) == 2 * 15 + 14
    np.testing.assert_allclose([w.fixed_load for w in v.wheels], 190e3)
    np.testing.assert_allclose([w.offset for w in v.wheels], hslm_a(4).axle_positions)


def test_a_train_is_warned_of_only_beyond_train_speeds():
    """Trains run at 5–420 km/h (EN 1991-2 6.4.6 sweeps to 1.2 × the line's 350 km/h), road
    vehicles at 5–150 km/h: 250 km/h is usual for HSLM-A1, 500 km/h is not, and 250 km/h is not
    for a truck (vbikit.analysis.checks)."""
    from vbikit.analysis.checks import input_flags
    from vbikit.scenario import build, parse_scenario

    def warnings(model: str, kmh: float) -> list[str]:
        built = build(parse_scenario({"bridge": {"model": "beam", "span": 20.0, "EI": 1e10, "mass_per_length": 15e3},
                                      "vehicle": {"model": model}, "crossing": {"speed_kmh": kmh}}))
        return [f.message for f in input_flags(built.crossing, 1e-3) if f.code == "speed_range"]

    assert warnings("hslm-a1", 250) == []
    assert "5–420 km/h" in warnings("hslm-a1", 500)[0]
    assert "5–150 km/h" in warnings("hs20-44", 250)[0]
