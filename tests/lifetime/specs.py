"""The small lifetime specification the lifetime tests share: a bootstrap stream of two-axle trucks
over a 10 m beam (EI 2e9 N m², 5000 kg/m, 3 modes), point tires, the midspan moment "M"."""
from __future__ import annotations

SPAN = 10.0


def beam_spec(name: str, seed: int, days: int, return_periods: str, records: str, trucks_per_day: int,
              extra: str = "") -> str:
    """The TOML text of the shared lifetime run (module docstring) with its name, seed, days,
    ``return_periods`` (TOML list text), the ``records`` file, ``trucks_per_day`` and ``extra`` tables."""
    return f'''name = "{name}"
seed = {seed}
days = {days}
block = "day"
distribution = "gumbel"
return_periods = {return_periods}
characteristic_period = 1000
[traffic]
records = "{records}"
mode = "bootstrap"
trucks_per_day = {trucks_per_day}
[bridge]
model = "beam"
span = {SPAN}
EI = 2e9
mass_per_length = 5000.0
n_modes = 3
[tire]
model = "point"
[crossing]
approach = 5
[[load_effects]]
kind = "moment"
x = {SPAN / 2}
name = "M"
{extra}'''
