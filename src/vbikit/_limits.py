"""Limits of a vehicle's motion that every input surface shares (one truth): ``vbikit.solve.Crossing``, the scenario schema
(``vbikit.scenario.schema``), the vehicle records of ``vbikit traffic`` and ``vbikit lifetime``
(``vbikit.traffic.records``) and ``--lanes``.  No imports: the records reader and the command line
read them without loading the scenario schema (about 0.65 s of imports)."""
from __future__ import annotations

#: largest vehicle speed a scenario accepts [m/s] (1080 km/h; speeds above 150 km/h are warned about)
MAX_SPEED = 300.0
#: smallest speed [m/s] (3.6 m/h: below it a crossing lasts days, and the time arithmetic underflows)
MIN_SPEED = 1e-3
#: largest |lateral_offset| of a vehicle centreline [m] (decks of known width refuse wheels off the deck)
MAX_LATERAL_OFFSET = 50.0
#: longest run-in of the vehicles before a run [m] (``crossing.run_in``): ten times the 100 m after which a
#: truck's start has settled (docs/traffic.md, "Start from rest and the approach")
MAX_RUN_IN = 1000.0
