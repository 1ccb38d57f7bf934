"""A traffic stream's base scenario (``vbikit traffic --bridge``): a scenario without vehicles, whose
vehicles come from the records; kept apart from ``vbikit.traffic.study`` (the events, which load the
compiled kernels) so that ``vbikit validate`` checks a base file without loading them."""
from __future__ import annotations

from pathlib import Path

from vbikit.scenario.schema import ScenarioError

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
