"""vbikit — vehicle–bridge coupled vibration.

Conventions used everywhere (SI units inside: m, kg, s, N, Pa):

* ``x`` runs along the bridge from its entry support (x = 0) to the far support
  (x = span); vehicles drive in the +x direction.
* ``y`` is transverse, measured from the deck centreline, positive to the driver's left.
* ``z`` is up.  A bridge deflecting under load therefore has *negative* displacement;
  vehicle DOFs are absolute displacements from the unstretched springs (gravity included).
* Bottom-fibre strain is positive in tension (sagging gives positive strain).

The library is composed from separate pieces: a [`ModalBridge`][vbikit.bridge.ModalBridge],
a [`Vehicle`][vbikit.vehicle.Vehicle], a [`TireModel`][vbikit.contact.TireModel], a
[`RoadProfile`][vbikit.road.RoadProfile], combined in a [`Crossing`][vbikit.solve.Crossing] and solved
by [`simulate`][vbikit.solve.simulate.simulate]; [`vbikit.run`][vbikit.scenario.run] runs a whole scenario (a file, TOML text, a
dict, or a crossing with a response plan) and returns its [`Report`][vbikit.scenario.Report],
whose ``summary`` is exactly what ``vbikit run --json`` prints.
"""
from vbikit._version import __version__

from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.bridge import EulerBernoulliBeam, ModalBridge
    from vbikit.contact import MultiPointTire, PointTire, TireModel
    from vbikit.errors import VbikitError
    from vbikit.road import RoadProfile
    from vbikit.scenario.pipeline import run, run_random
    from vbikit.scenario.report import Report
    from vbikit.vehicle import Vehicle

__all__ = [
    "EulerBernoulliBeam",
    "ModalBridge",
    "MultiPointTire",
    "PointTire",
    "Report",
    "RoadProfile",
    "TireModel",
    "VbikitError",
    "Vehicle",
    "__version__",
    "run",
    "run_random",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.bridge": ["EulerBernoulliBeam", "ModalBridge"],
    "vbikit.contact": ["MultiPointTire", "PointTire", "TireModel"],
    "vbikit.errors": ["VbikitError"],
    "vbikit.road": ["RoadProfile"],
    "vbikit.scenario.pipeline": ["run", "run_random"],
    "vbikit.scenario.report": ["Report"],
    "vbikit.vehicle": ["Vehicle"],
})
