"""The references a scenario's models rely on (``vbikit cite``, ``vbikit run --json``)."""
from __future__ import annotations

from vbikit.references import MODEL_REFERENCES, REFERENCES, Reference
from vbikit.scenario.schema import Scenario
from vbikit.solve.integrators import get_integrator


def scenario_models(scenario: Scenario) -> list[str]:
    """The ``"<section>:<model>"`` names of the models a scenario uses (keys of
    :data:`vbikit.references.MODEL_REFERENCES`)."""
    road = scenario.road
    names = [f"bridge:{scenario.bridge.model}"]
    if scenario.vehicles:  # several vehicles, each with its tire (default the scenario's)
        for v in scenario.vehicles:
            names += [f"vehicle:{v.model}", f"tire:{(v.tire or scenario.tire).model}"]
    else:
        names += [f"vehicle:{scenario.vehicle.model}", f"tire:{scenario.tire.model}"]
    if road.road_class == "psd":
        names.append("road:psd")
    elif road.road_class != "none" and road.profile_file is None:
        names.append("road:iso")
    names.append(f"integrator:{scenario.crossing.integrator}")
    names.append("impact:code-lines")  # every run reports the design-code allowances beside its IM
    return names


def scenario_references(scenario: Scenario) -> list[Reference]:
    """The bibliography entries of the models ``scenario`` uses, in first-use order (the
    integrator's from its registration, :attr:`vbikit.solve.integrators.Integrator.references`)."""
    keys: list[str] = []
    for name in ("*", *scenario_models(scenario)):
        if name.startswith("integrator:"):
            new = get_integrator(scenario.crossing.integrator).references
        else:
            new = MODEL_REFERENCES.get(name, ())
        keys += [k for k in new if k not in keys]
    return [REFERENCES[k] for k in keys]
