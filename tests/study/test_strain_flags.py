"""A study flags the crossings whose strain is not converged in the modes, as a single run of each flags it
(``strain_not_converged``; a second trial found a study's dataset silent where ``vbikit run`` of the same cell
said its strain IM was 2.3 % off, 2026-12-07).  The static reference does not read the road: the error is
computed once a batch and is the same for every road of it."""
from __future__ import annotations


import vbikit
from vbikit.analysis.checks import STRAIN_MODE_TOLERANCE, find_flag
from vbikit.study import parse_study, run_study

STUDY = {"name": "strain check", "seed": 1, "batch_size": 2,
         "base": {"bridge": {"model": "paper-bridge-1-beam"}, "vehicle": {"model": "hs20-44"},
                  "tire": {"model": "point"}, "road": {"class": "A"}, "crossing": {"speed_kmh": 75}},
         "axes": {"bridge.n_modes": [6, 40], "road.seed": {"samples": 2}}}


def test_a_study_flags_the_crossings_a_single_run_flags(tmp_path):
    study = parse_study(STUDY)
    ds = run_study(study, tmp_path / "s.nc", workers=1)
    flag_codes = str(ds.attrs.get("flag_codes", "")).split(",")
    assert "strain_not_converged" in flag_codes, ds.attrs
    assert "in 2 of 4 crossings" in ds.attrs["warnings"] and "bridge.n_modes = 6" in ds.attrs["warnings"]
    # each cell's single run: 6 modes flagged, by as much as the study says; 40 modes not
    for n_modes, flagged in ((6, True), (40, False)):
        seed = int(ds["road_seed"].values[0])
        s = vbikit.run({**STUDY["base"], "bridge": {"model": "paper-bridge-1-beam", "n_modes": n_modes},
                        "road": {"class": "A", "seed": seed}}, step_check=False).summary
        f = find_flag(s, "strain_not_converged")
        assert (f is not None) == flagged, (n_modes, s["warnings"])
        if flagged:
            assert abs(f["value"]) > STRAIN_MODE_TOLERANCE
            assert f"{f['value']:+.1%}" in ds.attrs["warnings"]
