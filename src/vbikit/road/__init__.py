"""Road profiles: sampled profiles, random profiles from a PSD (Eq. 7, ISO 8608), measured CSV files."""
from vbikit.road.defects import DEFECT_DEFAULTS, Defect, with_defects
from vbikit.road.measured import RoadFileError, read_profile_csv
from vbikit.road.profile import RoadProfile
from vbikit.road.psd import (
    ISO_CLASSES,
    ISO_N0,
    PAPER_CLASSES,
    RoadPSD,
    correlated_profile,
    phase_angles,
    random_profile,
)

__all__ = [
    "DEFECT_DEFAULTS",
    "Defect",
    "with_defects",
    "ISO_CLASSES",
    "ISO_N0",
    "PAPER_CLASSES",
    "RoadFileError",
    "RoadPSD",
    "RoadProfile",
    "correlated_profile",
    "phase_angles",
    "random_profile",
    "read_profile_csv",
]
