"""Road profiles: sampled profiles, random profiles from a PSD (Eq. 7, ISO 8608), measured CSV files."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.road.defects import DEFECT_DEFAULTS, Defect, with_defects
    from vbikit.road.measured import RoadFileError, read_profile_csv
    from vbikit.road.profile import RoadOrigin, RoadProfile
    from vbikit.road.psd import (
        ISO_CLASSES,
        ISO_N0,
        PAPER_CLASSES,
        RoadPSD,
        correlated_profile,
        phase_angles,
        random_profile,
    )
    from vbikit.road.track import TRACK_PSDS, TrackPSD, track_profile

__all__ = [
    "DEFECT_DEFAULTS",
    "Defect",
    "with_defects",
    "ISO_CLASSES",
    "ISO_N0",
    "PAPER_CLASSES",
    "RoadFileError",
    "RoadOrigin",
    "RoadPSD",
    "RoadProfile",
    "TRACK_PSDS",
    "TrackPSD",
    "correlated_profile",
    "phase_angles",
    "random_profile",
    "read_profile_csv",
    "track_profile",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.road.defects": ["DEFECT_DEFAULTS", "Defect", "with_defects"],
    "vbikit.road.measured": ["RoadFileError", "read_profile_csv"],
    "vbikit.road.profile": ["RoadOrigin", "RoadProfile"],
    "vbikit.road.psd": ["ISO_CLASSES", "ISO_N0", "PAPER_CLASSES", "RoadPSD", "correlated_profile", "phase_angles", "random_profile"],
    "vbikit.road.track": ["TRACK_PSDS", "TrackPSD", "track_profile"],
})
