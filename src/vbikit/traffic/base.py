"""A traffic stream's base scenario (``vbikit traffic --bridge``): a scenario without vehicles, whose
vehicles come from the records; kept apart from ``vbikit.traffic.study`` (the events, which load the
compiled kernels) so that ``vbikit validate`` checks a base file without loading them."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from vbikit.scenario.schema import ScenarioError

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.scenario.schema import ResponseSpec

#: scenario sections a traffic base scenario may hold (the vehicles come from the records)
BASE_SECTIONS = ("name", "bridge", "tire", "road", "crossing", "response")


def base_scenario(bridge: str, base_dir: Path | str = ".") -> tuple[dict, str]:
    """The base sections from ``bridge``: a bridge preset name, or a scenario file (its
    ``BASE_SECTIONS``; a [vehicle] or [[vehicles]] there is refused: the records give them)."""
    path = Path(bridge)
    if path.suffix == ".toml" or path.is_file():
        from vbikit._toml import read_toml

        data = read_toml(path, ScenarioError, "scenario file")
        extra = [k for k in data if k not in BASE_SECTIONS]
        if extra:
            raise ScenarioError(f"{path}: a traffic base scenario takes {', '.join(BASE_SECTIONS)}; remove "
                                f"{', '.join(extra)} (the vehicles come from the records)")
        return data, str(path.parent)
    from vbikit.bridge.presets import BRIDGE_PRESETS

    if bridge not in BRIDGE_PRESETS:
        raise ScenarioError(f"--bridge {bridge!r} is neither a scenario file nor a bridge preset; presets: "
                            f"{', '.join(BRIDGE_PRESETS)}")
    return {"bridge": {"model": bridge}}, str(Path(base_dir))


def template_data(base: dict) -> dict:
    """The scenario of a stream's event template from the ``base`` sections: a moving-force stand-in
    for the vehicles (the records give them) at 20 m/s (each event has its vehicles' speeds)."""
    data = dict(base)
    data["vehicle"] = {"model": "moving-force"}
    crossing = {k: v for k, v in base.get("crossing", {}).items() if k not in ("speed", "speed_kmh")}
    data["crossing"] = {**crossing, "speed": 20.0}
    return data


def dropped_section_warnings(response: "ResponseSpec") -> list[str]:
    """A stream's dataset holds one section of each load effect, the first one listed (the
    catalogue's ``moment_*``, ``shear_*``, ``reaction_*`` outputs: ``ResponsePlan.first_effects``);
    one warning per kind of which the base scenario's [response] lists more, naming the sections
    dropped (``vbikit validate`` and ``vbikit traffic`` print them)."""
    out = []
    for kind, where in (("moment", "x = {:g} m"), ("shear", "x = {:g} m"), ("reaction", "support {:d}")):
        given = getattr(response, kind)
        if given is not None and len(given) > 1:
            out.append(f"response.{kind}: a traffic stream's dataset keeps the first section of each load effect "
                       f"only ({kind} at {where.format(given[0])}); dropped: "
                       f"{', '.join(where.format(v) for v in given[1:])}; list the section you want first, or run "
                       "one stream per section")
    return out
