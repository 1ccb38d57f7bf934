"""vbikit — vehicle–bridge coupled vibration.

Conventions used everywhere (SI units inside: m, kg, s, N, Pa):

* ``x`` runs along the bridge from its entry support (x = 0) to the far support
  (x = span); vehicles drive in the +x direction.
* ``y`` is transverse, measured from the deck centreline, positive to the driver's left.
* ``z`` is up.  A bridge deflecting under load therefore has *negative* displacement;
  vehicle DOFs are absolute displacements from the unstretched springs (gravity included).
* Bottom-fibre strain is positive in tension (sagging gives positive strain).

The library is composed from separate pieces: a :class:`~vbikit.bridge.ModalBridge`,
a :class:`~vbikit.vehicle.Vehicle`, a :class:`~vbikit.contact.TireModel`, a
:class:`~vbikit.road.RoadProfile`, combined in a :class:`~vbikit.solve.Crossing` and solved
by :func:`~vbikit.solve.simulate`; :func:`vbikit.run` runs a whole scenario (a file, TOML text, a
dict, or a crossing with a response plan) and returns its :class:`~vbikit.scenario.report.Report`,
whose ``summary`` is exactly what ``vbikit run --json`` prints.
"""
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("vbikit")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"

from vbikit.bridge import EulerBernoulliBeam, ModalBridge
from vbikit.contact import MultiPointTire, PointTire, TireModel
from vbikit.road import RoadProfile
from vbikit.vehicle import Vehicle

def __getattr__(name: str):
    if name in ("run", "Report"):  # the run pipeline, imported on first use
        from vbikit.scenario import pipeline, report

        return pipeline.run if name == "run" else report.Report
    raise AttributeError(f"module 'vbikit' has no attribute {name!r}")


__all__ = [
    "EulerBernoulliBeam",
    "ModalBridge",
    "MultiPointTire",
    "PointTire",
    "Report",
    "RoadProfile",
    "TireModel",
    "Vehicle",
    "__version__",
    "run",
]
