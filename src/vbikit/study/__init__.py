"""Parameter studies: a base scenario swept over axes, run in batches, stored as xarray/NetCDF,
resumable and parallel (local processes or Dask).  See ``docs/studies.md``."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.study.run import assemble, run_study, shutdown_workers
    from vbikit.study.spec import (
        Study,
        StudyError,
        derive_seed,
        load_study,
        parse_study,
        study_from_toml,
    )

__all__ = ["Study", "StudyError", "assemble", "derive_seed", "load_study", "parse_study", "run_study",
           "shutdown_workers", "study_from_toml"]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.study.run": ["assemble", "run_study", "shutdown_workers"],
    "vbikit.study.spec": ["Study", "StudyError", "derive_seed", "load_study", "parse_study", "study_from_toml"],
})
