"""What an engineer reads of `vbikit lifetime`'s report: a deflection in mm (the one table of
report units, `vbikit.outputs.REPORT_UNITS`), and the period of the fatigue damage said where it is
printed; its flags in the one format of flag codes and in words."""
from __future__ import annotations

import pytest


@pytest.fixture(scope="module")
def facts(tmp_path_factory):
    """Moving forces at 5 km/h on a smooth road over the Bridge 1 beam, 5 days of 16 trucks: the
    midspan deflection, the midspan moment and one EN 36 detail on it."""
    from vbikit.lifetime.report import summary
    from vbikit.lifetime.run import run_lifetime

    spec = {"name": "report units", "seed": 4, "days": 5, "amplification": 0.05,
            "traffic": {"records": "examples/lifetime/wim.csv", "trucks_per_day": 16, "speed_kmh": 5.0},
            "vehicle_model": "moving-forces", "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
            "tire": {"model": "point"}, "road": {"class": "none"},
            "load_effects": [{"kind": "deflection", "x": 4.58, "name": "w"}, {"kind": "moment", "x": 4.58, "name": "M"}],
            "fatigue": {"details": [{"name": "flange", "effect": "M", "section_modulus": 0.005, "category": "EN 36"}]}}
    out = tmp_path_factory.mktemp("units")
    ds = run_lifetime(spec, out, base_dir=".", workers=1, figures=False)
    return summary(ds) | {"out": out}


def test_a_deflection_is_reported_in_mm(facts):
    """The summary keeps SI (m); the report's row, its return-level table and its governing events
    show mm, the values times 1000 (1 m = 1000 mm); on main the report showed m."""
    from vbikit.lifetime.report import text_report
    from vbikit.outputs import report_unit

    assert report_unit("m") == ("mm", 1e3)
    e = facts["load_effects"]["w"]
    assert e["units"] == "m"
    report = text_report(facts)
    row = next(x for x in report.splitlines() if x.startswith("w "))
    assert row[22:28].strip() == "mm"
    assert float(row[28:42].rstrip("!")) == pytest.approx(e["characteristic_static"] * 1e3, rel=1e-4)  # (! a flag)
    assert "\nw [mm]: return levels" in report
    gov = e["governing"]["static"]
    assert f"static {gov['static'] * 1e3:.4g}, total {gov['total'] * 1e3:.4g};" in report


def test_the_fatigue_table_says_its_period(facts):
    """The damage column is the damage of the simulated days (``fatigue_damage``: "Miner damage over
    the simulated period"), the per-year column that scaled by days_per_year / days: the header line
    says both (on main: "fatigue (design life 100 years)" only)."""
    from vbikit.lifetime.report import text_report

    lines = text_report(facts).splitlines()
    header = next(x for x in lines if x.startswith("fatigue"))
    assert "damage over the 5 simulated days" in header and "per year (365 days)" in header
    assert "design life 100 years" in header
    assert lines[lines.index(header) + 1].split()[:3] == ["detail", "category", "damage"]


def test_the_flags_are_in_words_and_their_codes_in_the_one_format(facts):
    """Five days give intervals wider than the levels and an ADR that cannot be told from 1 (the run's
    findings); every flag names what it puts in doubt in words ("static return levels", "ADR"; on
    main a path "return_levels.static"), and lifetime.nc stores the codes as every dataset does:
    comma-separated, each once (on main a JSON table by effect), per effect in a variable."""
    import json

    import xarray as xr

    from vbikit.analysis.checks import FLAG_CODES, dataset_has_flag

    saved = json.loads((facts["out"] / "summary.json").read_text())["load_effects"]
    records = [f for e in saved.values() for f in e["flags"]]
    assert records and all("." not in f["output"] and "_" not in f["output"] for f in records)
    assert {f["output"] for f in records} <= {"characteristic static value", "characteristic total value",
                                               "static return levels", "total return levels", "ADR",
                                               "governing static event", "governing total event"}
    with xr.open_dataset(facts["out"] / "lifetime.nc") as ds:
        codes = ds.attrs["flag_codes"].split(",")
        assert codes == list(dict.fromkeys(f["code"] for f in records)) and set(codes) <= set(FLAG_CODES)
        assert all(dataset_has_flag(ds.attrs, c) for c in codes)
        per_effect = [str(x) for x in ds["load_effect_flag_codes"].values]
    assert per_effect == [",".join(f["code"] for f in e["flags"]) for e in saved.values()]


def _pot_run(path, sample: float = 0.05, details: bool = True, amplification: float = 0.05, speed_kmh: float = 5.0):
    """Five days of 16 trucks as moving forces over the Bridge 1 beam, its midspan moment (and an EN 36
    detail on it with ``details``: only then is a random sample of ``sample`` of the events simulated)."""
    from vbikit.lifetime.run import run_lifetime

    fatigue = {"dynamic_sample": sample} | ({"details": [{"name": "flange", "effect": "M", "section_modulus": 0.005,
                                                          "category": "EN 36"}]} if details else {})
    spec = {"name": "pot words", "seed": 4, "days": 5, "amplification": amplification,
            "traffic": {"records": "examples/lifetime/wim.csv", "trucks_per_day": 16, "speed_kmh": speed_kmh},
            "vehicle_model": "moving-forces", "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
            "tire": {"model": "point"}, "road": {"class": "none"},
            "load_effects": [{"kind": "moment", "x": 4.58, "name": "M"}], "fatigue": fatigue}
    return run_lifetime(spec, path, base_dir=".", workers=1, figures=False)


def _completeness(ds) -> float:
    """c = (1 + A)·max s·R_st over the events the screening did not simulate, from the dataset's events
    and the A the run ended with (independently of ``vbikit.lifetime.accuracy.completeness_level``)."""
    left = ~ds["event_simulated"].values.astype(bool)
    static = ds["event_static"].values[:, 0] * float(ds["effect_sign"].values[0])
    assert left.any()
    return (1.0 + float(ds.attrs["amplification_bound_used"])) * static[left].max()


def test_a_missing_total_pot_value_says_the_screening_set_its_threshold(tmp_path):
    """With 5 % of the events sampled (a fatigue detail given) the simulated totals are complete only
    above c = (1 + A)·max s·R_st of the events not simulated; the total POT threshold is c, too few
    exceed it, and the dataset and the report say why and what lowers it.  With every event
    simulated (dynamic_sample = 1) the total threshold is the static one and the total POT has its
    value (nothing to say)."""
    import numpy as np

    from vbikit.lifetime.report import summary, text_report

    ds = _pot_run(tmp_path / "sampled")
    assert float(ds.attrs["amplification_bound_used"]) == 0.05  # the file's A held
    assert float(ds["fit_pot_total_threshold"].values[0]) == _completeness(ds) > float(ds["fit_pot_threshold"].values[0])
    words = str(ds["pot_total_not_estimable"].values[0])
    assert int(ds["fit_pot_total_exceedances"].values[0]) < 10 and np.isnan(ds["return_level_pot_total"].values[0]).all()
    assert "a GPD fit needs 10" in words and "complete only above this threshold, (1 + A) = 1.05 times" in words
    assert "a larger [fatigue] dynamic_sample simulates more of them" in words
    assert words.endswith("a smaller amplification A lowers it where the run's check shows that A holds")
    assert str(ds["pot_static_not_estimable"].values[0]) == ""
    assert f"(no POT value: {words})" in text_report(summary(ds))

    every = _pot_run(tmp_path / "every", sample=1.0)
    assert float(every["fit_pot_total_threshold"].values[0]) == float(every["fit_pot_threshold"].values[0])
    assert str(every["pot_total_not_estimable"].values[0]) == ""
    assert np.isfinite(every["return_level_pot_total"].values[0]).all()


def test_without_fatigue_details_and_with_a_raised_bound_the_words_say_so(tmp_path):
    """No fatigue detail: no random sample is drawn, so dynamic_sample changes nothing and the words do
    not offer it; at 80 km/h the moving forces amplify the moment by more than the file's A = 0.01, the
    run's check raises A, and the words give the A used and do not advise a smaller one."""
    ds = _pot_run(tmp_path / "raised", details=False, amplification=0.01, speed_kmh=80.0)
    used = float(ds.attrs["amplification_bound_used"])
    assert used > 0.01 and float(ds.attrs["amplification_bound_given"]) == 0.01
    assert float(ds["fit_pot_total_threshold"].values[0]) == _completeness(ds)
    words = str(ds["pot_total_not_estimable"].values[0])
    assert "without [[fatigue.details]] no random sample of events is simulated" in words
    assert "a larger [fatigue] dynamic_sample" not in words and "a smaller amplification" not in words
    assert f"(1 + A) = {1 + used:.3g} times" in words
    assert f"A is {used:.3g} because the run's check raised it from the file's amplification 0.01" in words


def test_the_screening_words_are_added_only_when_the_screening_set_the_total_threshold():
    """The three cases of the total POT fit's reason (unit level: a run of at least 5 days always
    leaves the static fit its exceedances, so the second case cannot be built from a run): the
    screening's completeness level above the static threshold with the static fit made → its words;
    the static fit missing too (too few days, not the screening) → the reason as it is; the level
    at or below the static threshold (the static threshold is the total's) → as it is."""
    from vbikit.lifetime.accuracy import total_pot_why

    why = "3 exceedances above the threshold, fewer than 5"
    added = total_pot_why(why, 1425.0, 977.0, True, 0.05, 0.05, False)
    assert added.startswith(why + "; the simulated totals are complete only above this threshold, (1 + A) = 1.05 times")
    assert total_pot_why(why, 1425.0, 977.0, False, 0.05, 0.05, False) == why
    assert total_pot_why(why, 977.0, 977.0, True, 0.05, 0.05, False) == why
    assert total_pot_why(why, 900.0, 977.0, True, 0.05, 0.05, False) == why


def test_a_one_signed_line_reports_nothing_the_other_way(facts):
    """On a simply supported span a downward load gives a sagging moment and a downward deflection
    everywhere (statics), so the run's largest static value the other way is 0 (every event starts
    and ends with the bridge empty) to round-off of the line's tables, the reported way's (read from
    the daily maxima) is the largest event peak, and no direction is flagged; a swapped pair of extremes would put the
    peak on the other side."""
    import numpy as np
    import xarray as xr

    for name in ("M", "w"):
        d = facts["load_effects"][name]["direction"]
        assert d["source"] == "auto" and d["opposite_area"] == 0.0
        assert abs(d["largest_opposite"]) <= 1e-9 * abs(d["largest"])
        assert abs(d["largest"]) > 0 and d["largest"] * d["sign"] > 0
        with xr.open_dataset(facts["out"] / "lifetime.nc") as ds:
            events = ds["event_static"].sel(load_effect=name).values
        assert d["largest"] == pytest.approx(d["sign"] * np.max(d["sign"] * events), rel=1e-12)
        codes = [f["code"] for f in facts["load_effects"][name].get("flags", [])]
        assert "opposite_direction_unreported" not in codes


def test_the_im_columns_say_what_population_they_are_over(facts):
    """The table's IM mean and IM q95 are over the random sample (every lane and vehicle), not per lane nor
    the governing event's: a note under the table says so with the sample's size, and each effect's sample
    (``n_im_sample``) is its sampled events with a finite IM — counted here from lifetime.nc's events (before
    2026-12-06 the columns said neither, and an event without an IM was not counted anywhere)."""
    import copy

    import numpy as np
    import xarray as xr

    from vbikit.lifetime.report import text_report

    with xr.open_dataset(facts["out"] / "lifetime.nc") as ds:
        sample = ds["event_in_sample"].values.astype(bool)
        im = ds["event_total"].values[sample] / ds["event_static"].values[sample] - 1.0
        names = [str(n) for n in ds["load_effect"].values]
    n = int(sample.sum())
    assert n == facts["run"]["n_sample_events"] and n >= 2
    for j, name in enumerate(names):
        assert facts["load_effects"][name]["n_im_sample"] == int(np.isfinite(im[:, j]).sum()) == n
    lines = text_report(facts).splitlines()
    note = (f"  (IM mean, IM q95: mean and 95th percentile of the impact factors R_dyn/R_st − 1 of the random sample's "
            f"{n} events, all lanes and vehicles together — not per lane, nor the IM of the largest static event)")
    assert note in lines
    assert lines.index(note) == next(i for i, x in enumerate(lines) if x.startswith("M ")) + 1  # right under the table
    assert f"  w: IM of the random sample ({n} events): mean " in "\n".join(lines)
    # one sampled event without an IM for w (no usable static reference): the note and w's line say so
    fewer = copy.deepcopy(facts)
    fewer["load_effects"]["w"]["n_im_sample"] = n - 1
    report = text_report(fewer)
    assert note[:-1] + "; events without an IM left out: w 1)" in report.splitlines()
    assert f"  w: IM of the random sample ({n - 1} of its {n} events with an IM): mean " in report
    assert f"  M: IM of the random sample ({n} events): mean " in report


def test_the_dataset_names_the_records_file_without_the_users_folders():
    """lifetime.nc's ``records`` attribute (``prepare``'s, the one the dataset stores): ``traffic.records`` as
    the lifetime file gives it, an absolute path by its name only (``wim.csv``; a shared dataset does not
    carry the user's folders) — the rule of the traffic stream's (before 2026-12-06 the name only, a
    relative path too)."""
    from pathlib import Path

    from vbikit.lifetime.run import prepare

    spec = {"name": "records name", "seed": 4, "days": 5, "amplification": 0.05,
            "traffic": {"records": "examples/lifetime/wim.csv", "trucks_per_day": 16, "speed_kmh": 5.0},
            "vehicle_model": "moving-forces", "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
            "tire": {"model": "point"}, "road": {"class": "none"},
            "load_effects": [{"kind": "deflection", "x": 4.58, "name": "w"}]}
    assert prepare(spec, ".", workers=1).info["records"] == "examples/lifetime/wim.csv"
    spec["traffic"]["records"] = str(Path("examples/lifetime/wim.csv").resolve())
    assert prepare(spec, "/", workers=1).info["records"] == "wim.csv"


def test_an_older_dataset_counts_its_im_sample_from_its_events(facts):
    """lifetime.nc written before ``n_im_sample`` was stored (2026-12-06): the summary counts it from the
    dataset's events (R_dyn / R_st − 1 of the sampled events, finite), so the report does not claim the whole
    sample for an effect that had an event without an IM (it said "(237 events)" for every effect)."""
    import numpy as np
    import xarray as xr

    from vbikit.lifetime.report import summary, text_report

    with xr.open_dataset(facts["out"] / "lifetime.nc") as stored:
        ds = stored.load().drop_vars("n_im_sample")
    sample = np.flatnonzero(ds["event_in_sample"].values)
    n = sample.size
    j = [str(x) for x in ds["load_effect"].values].index("w")
    static = ds["event_static"].values.copy()
    static[sample[0], j] = 0.0  # that sampled event has no usable static reference for w: no IM
    ds["event_static"] = (ds["event_static"].dims, static, ds["event_static"].attrs)
    older = summary(ds)
    assert older["load_effects"]["w"]["n_im_sample"] == n - 1 and older["load_effects"]["M"]["n_im_sample"] == n
    report = text_report(older)
    assert f"  w: IM of the random sample ({n - 1} of its {n} events with an IM): mean " in report
    assert "; events without an IM left out: w 1)" in report


def test_an_event_without_an_im_is_no_small_static_reference():
    """Four sampled events, two effects: effect 0 has IMs 0.1, NaN (a static peak of 0: R_dyn / 0), 0.3, 0.2 and
    small static references at events 1 and 3; effect 1 all finite, none small.  By hand: n_im_sample 3 and 4;
    n_small_static_sample 1 (event 3; event 1 has no IM to rest on anything) and 0 (before 2026-12-06: 2 —
    the event without an IM counted as a small static reference as well as left out of the IM sample)."""
    import numpy as np

    from vbikit.lifetime.results import im_sample_counts

    im = np.array([[0.1, 0.05], [np.nan, 0.1], [0.3, 0.2], [0.2, 0.0]])
    small = np.array([[False, False], [True, False], [False, False], [True, False]])
    assert im_sample_counts(im, small) == {"n_im_sample": [3, 4], "n_small_static_sample": [1, 0]}


def test_a_gumbel_fits_shape_is_not_quoted_in_the_negative_shape_flag():
    """A Gumbel fit's block-maxima shape is 0 by definition: the flag quoted "block maxima ξ = 0.00" beside the POT
    shape that raised it (a new user's trial, 2026-12-07); it now names the fitted shapes only."""
    from vbikit.lifetime.report import _fit_flags

    e = {"fits": {"static": {"shape_strongly_negative": True, "block_maxima_shape": 0.0, "pot_shape": -1.54}},
         "return_levels": []}
    (gumbel,) = _fit_flags("M", e, "static", -0.3, gumbel=True)
    assert "POT ξ = -1.54" in gumbel.message and "block maxima ξ" not in gumbel.message
    (gev,) = _fit_flags("M", {**e, "fits": {"static": {**e["fits"]["static"], "block_maxima_shape": -0.45}}},
                        "static", -0.3)
    assert "block maxima ξ = -0.45" in gev.message and gev.value == -1.54


def test_another_runs_work_names_the_output_folder(tmp_path, monkeypatch):
    """Another lifetime file's run in the same --out-dir was refused with "static.nc (in the output folder's work
    folder) exists and is not this study's finished dataset; delete it or choose another --out (or --out-dir)": an
    internal file, "study", and an option vbikit lifetime does not have. It now names the output folder and says
    what to do."""
    import pytest

    import vbikit.study.run as study_run
    from vbikit.lifetime.run import _run
    from vbikit.lifetime.spec import LifetimeError
    from vbikit.study.spec import StudyError

    def refuse(*args, **kwargs):
        raise StudyError(f"{tmp_path / 'work' / 'static.nc'} exists and is not this study's finished dataset; delete it "
                         "or write to another path")

    monkeypatch.setattr(study_run, "run_study", refuse)
    with pytest.raises(LifetimeError) as err:
        _run(None, tmp_path / "work" / "static.nc", 1, None, None, "static pass")
    assert str(err.value).startswith(f"{tmp_path} holds work this run cannot use")
    assert f"delete {tmp_path / 'work'} or write to another output folder" in str(err.value)  # (the folder to delete)
    assert "--out" not in str(err.value) and "study" not in str(err.value)


def test_a_headline_value_a_flag_puts_in_doubt_is_marked(finished_cut_down):
    """The cut-down example's report (its finished run, ``finished_cut_down``): a ``!`` follows a characteristic
    static value exactly when a flag of that load effect is about the characteristic static value or the static
    return levels, an ADR exactly when one is about the ADR (the flags' ``output`` words, written out here), and the
    legend is printed when any value is marked."""
    from vbikit.lifetime.report import summary, text_report

    facts = summary(finished_cut_down.ds)
    report = text_report(facts).splitlines()
    header = next(i for i, line in enumerate(report) if line.startswith("load effect"))
    any_mark = False
    for name, e in facts["load_effects"].items():
        row = next(line for line in report[header:] if line.startswith(name + " "))
        outputs = {f.get("output") for f in e.get("flags", ())}
        static = bool(outputs & {"characteristic static value", "static return levels"})
        adr = "ADR" in outputs
        assert (row[41] == "!") == static, (row, outputs)  # (name 22, unit 6, the value 13, its mark)
        assert (row[63] == "!") == adr, (row, outputs)  # (the total 13 and its mark, the ADR 7, its mark)
        any_mark |= static or adr or row[55] == "!"
    assert any(line.startswith("  (! beside a value:") for line in report) == any_mark
