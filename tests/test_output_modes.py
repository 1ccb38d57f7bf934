"""Outputs are readable as the user's umask says: a file written atomically (temporary file +
rename) gets mode 0o666 & ~umask and a created folder 0o777 & ~umask, as `open` and `mkdir` give
them (POSIX), not the 0o600 of `tempfile.mkstemp`."""
from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"

STUDY = {
    "name": "modes", "seed": 1, "batch_size": 2,
    "base": {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 2}, "vehicle": {"model": "two-axle"},
             "road": {"class": "none"}, "crossing": {"speed_kmh": 90}},
    "axes": {"crossing.speed_kmh": [80, 90, 100]},
}

#: one process writes the outputs under each umask in turn (argv: umasks in octal, comma-separated; the
#: base folder, a sub-folder per umask; the study; the scenario): the umask is read by the OS at each
#: ``open``/``mkdir``, so one process serves them all, and the three tests share its start-up
SCRIPT = """
import json, os, sys
from vbikit.cli import main
from vbikit.study import parse_study, run_study
from vbikit.traffic import parse_records, write_records
umasks, base, study, scenario = sys.argv[1].split(","), sys.argv[2], sys.argv[3], sys.argv[4]
for umask in umasks:
    os.umask(int(umask, 8))
    out = os.path.join(base, umask)
    run_study(parse_study(json.loads(study)), os.path.join(out, "study", "s.nc"), workers=1, keep_parts=True)
    write_records(parse_records("time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\\n"
                                "0,1,+x,80,50 90,4.2\\n"), os.path.join(out, "records", "r.csv"))
    sys.argv = ["vbikit", "run", scenario, "--out-dir", os.path.join(out, "run")]
    try:
        main()
    except SystemExit as stop:
        if stop.code not in (0, None):
            raise
"""

UMASKS = [0o022, 0o077, 0o002]


@pytest.fixture(scope="module")
def outputs(tmp_path_factory) -> tuple[Path, subprocess.CompletedProcess]:
    """The base folder (a sub-folder per umask, named by ``oct(umask)``) and the writing process."""
    base = tmp_path_factory.mktemp("modes")
    res = subprocess.run([sys.executable, "-c", SCRIPT, ",".join(oct(u) for u in UMASKS), str(base), json.dumps(STUDY),
                          str(SCENARIO)], capture_output=True, text=True, timeout=600)
    return base, res


@pytest.mark.skipif(os.name != "posix", reason="POSIX permission bits")
@pytest.mark.parametrize("umask", UMASKS)
def test_outputs_follow_the_umask(outputs, umask):
    base, res = outputs
    assert res.returncode == 0, res.stderr
    tmp_path = base / oct(umask)
    files = {
        "run CSV": tmp_path / "run" / f"{SCENARIO.stem}.csv",
        "run JSON": tmp_path / "run" / f"{SCENARIO.stem}.json",
        "run PNG": tmp_path / "run" / f"{SCENARIO.stem}.png",
        "study NetCDF": tmp_path / "study" / "s.nc",
        "study part": tmp_path / "study" / "s.nc.parts" / "batch-000000.npz",
        "study part checksums": tmp_path / "study" / "s.nc.parts" / "SHA256SUMS",
        "study spec": tmp_path / "study" / "s.nc.parts" / "study.json",
        "records CSV": tmp_path / "records" / "r.csv",
    }
    folders = [tmp_path / "run", tmp_path / "study", tmp_path / "study" / "s.nc.parts", tmp_path / "records"]
    want_file, want_dir = 0o666 & ~umask, 0o777 & ~umask  # 0o644 / 0o755 for umask 022, 0o600 / 0o700 for 077
    modes = {name: oct(stat.S_IMODE(path.stat().st_mode)) for name, path in files.items()}
    assert modes == {name: oct(want_file) for name in files}
    assert {str(p): oct(stat.S_IMODE(p.stat().st_mode)) for p in folders} == {str(p): oct(want_dir) for p in folders}
    leftovers = [p for p in tmp_path.rglob("*") if p.name.endswith(".tmp") or p.name.endswith(".lock")]
    assert leftovers == []
