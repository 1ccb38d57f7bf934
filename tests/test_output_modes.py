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

SCRIPT = """
import json, os, sys
os.umask(int(sys.argv[1], 8))
from vbikit.cli import main
from vbikit.study import parse_study, run_study
from vbikit.traffic import parse_records, write_records
out = sys.argv[2]
run_study(parse_study(json.loads(sys.argv[3])), os.path.join(out, "study", "s.nc"), workers=1, keep_parts=True)
write_records(parse_records("time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\\n"
                            "0,1,+x,80,50 90,4.2\\n"), os.path.join(out, "records", "r.csv"))
sys.argv = ["vbikit", "run", sys.argv[4], "--out-dir", os.path.join(out, "run")]
main()
"""


@pytest.mark.skipif(os.name != "posix", reason="POSIX permission bits")
@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_outputs_follow_the_umask(tmp_path, umask):
    res = subprocess.run([sys.executable, "-c", SCRIPT, oct(umask), str(tmp_path), json.dumps(STUDY), str(SCENARIO)],
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
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
