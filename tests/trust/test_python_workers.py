"""The Python entry points check ``workers`` as the command line checks ``--workers`` (one check,
``vbikit._validation.checked_workers``): a trial's ``run_study(…, workers=0)`` ran, and ``workers=-3`` too, where
``--workers 0`` is refused.  Each refuses before anything is written."""
from __future__ import annotations

from pathlib import Path

import pytest

from vbikit.errors import VbikitError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("workers", [0, -3, 2.5, True, 10**6])
def test_every_entry_point_refuses_a_bad_worker_count_before_writing(tmp_path, workers):
    from vbikit.driveby.study import run_driveby
    from vbikit.lifetime import run_lifetime
    from vbikit.rail import run_rail
    from vbikit.study import load_study, run_study

    runs = {"study": lambda out: run_study(load_study(EXAMPLES / "studies" / "modes_sensitivity.toml"), out / "s.nc",
                                           workers=workers),
            "lifetime": lambda out: run_lifetime(EXAMPLES / "lifetime" / "lifetime.toml", out, workers=workers),
            "driveby": lambda out: run_driveby(EXAMPLES / "driveby" / "DRIVEBY.toml", out, workers=workers),
            "rail": lambda out: run_rail(EXAMPLES / "railway" / "hslm_20m.toml", out, workers=workers)}
    for name, run in runs.items():
        out = tmp_path / name
        with pytest.raises(VbikitError, match=r"workers: expected an integer in \[1, \d+\], got"):
            run(out)
        assert not out.exists() or not any(out.iterdir()), name
