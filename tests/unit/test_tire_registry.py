"""The tire registry (vbikit.contact.registry): tire models by name, their parameter models, the
[tire] table validated by the chosen model, build and cite through the registry."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from pydantic import Field

from vbikit.contact import (
    TIRE_MODELS,
    DiskTire,
    MultiPointTire,
    PointTire,
    RigidDiskTire,
    TireModel,
    TireParameters,
    register_tire,
    tire_catalogue,
    tire_from_parameters,
    tire_model,
)
from vbikit.scenario import ScenarioError, scenario_from_toml
from vbikit.scenario.build import build_tire
from vbikit.scenario.cite import scenario_references
from vbikit.scenario.schema import TireSpec, key_unit
from vbikit.study.spec import StudyError, parse_study

BUILT_IN = ("point", "multipoint", "disk", "rigid-disk")
#: what the scenario built for each model's defaults before the registry
TODAY = {"point": PointTire(), "multipoint": MultiPointTire(6, 0.254, "ends"),
         "disk": DiskTire(radius=0.5, spacing=0.01, max_gap=0.1), "rigid-disk": RigidDiskTire(radius=0.5, spacing=0.01, max_gap=0.1)}
SCENARIO = """
[bridge]
model = "beam"
span = 10.0
EI = 5e9
mass_per_length = 5000.0
n_modes = 3

[vehicle]
model = "quarter-car"

[crossing]
speed = 20.0
"""


@pytest.fixture
def extra_tire():
    """A tire model registered for one test (removed afterwards)."""

    @dataclass(frozen=True)
    class TwinPointTire(TireModel):
        """Two points a distance ``gap`` apart, each with half the spring."""

        gap: float = 0.2
        name = "twin-point"
        description = "two points, half the spring each"
        references = ("Hambly1991",)  # any entry the test scenario's other models do not cite

        class Parameters(TireParameters):
            gap: float = Field(0.2, gt=0, le=1.0, description="distance between the points [m]")

        def layout(self):
            return np.array([-self.gap / 2, self.gap / 2]), np.full(2, 0.5)

    register_tire(TwinPointTire)
    yield TwinPointTire
    TIRE_MODELS.pop("twin-point", None)


def _tire(text: str) -> TireSpec:
    return scenario_from_toml(SCENARIO + text).tire


def test_built_in_tires_are_registered_in_order():
    assert tuple(TIRE_MODELS)[:4] == BUILT_IN
    assert [tire_model(n) for n in BUILT_IN] == [PointTire, MultiPointTire, DiskTire, RigidDiskTire]


@pytest.mark.parametrize("call", [tire_model, tire_from_parameters])
def test_unknown_name_is_refused_listing_the_allowed_ones(call):
    with pytest.raises(ValueError, match="unknown tire model 'tyre'") as err:
        call("tyre")
    assert f"allowed: {', '.join(BUILT_IN)}" in str(err.value)


@pytest.mark.parametrize("name", BUILT_IN)
def test_every_tire_builds_from_its_defaults_and_from_the_scenario(name):
    cls = TIRE_MODELS[name]
    assert tire_from_parameters(name) == cls.from_parameters(cls.Parameters()) == TODAY[name]
    spec = _tire(f'[tire]\nmodel = "{name}"\n')
    assert build_tire(spec) == TODAY[name]


def test_every_registered_tire_builds_and_lays_points(extra_tire):
    for name, cls in TIRE_MODELS.items():
        tire = build_tire(_tire(f'[tire]\nmodel = "{name}"\n'))
        assert isinstance(tire, cls) and tire.name == name
        offsets, shares = tire.layout()
        assert offsets.size == shares.size >= 1 and shares.sum() == pytest.approx(1.0)


def test_scenario_parameters_reach_the_model():
    assert build_tire(_tire('[tire]\nmodel = "multipoint"\nn_points = 4\ncontact_length = 0.3\nlayout = "cells"\n')) \
        == MultiPointTire(4, 0.3, "cells")
    assert build_tire(_tire('[tire]\nmodel = "rigid-disk"\nradius = 0.6\ndisk_spacing = 0.02\n')) \
        == RigidDiskTire(radius=0.6, spacing=0.02, max_gap=0.12)


def test_unknown_tire_in_a_scenario_is_refused():
    with pytest.raises(ScenarioError, match=r"tire\.model: unknown tire model 'tyre'; allowed: point, multipoint"):
        _tire('[tire]\nmodel = "tyre"\n')
    with pytest.raises(ScenarioError, match=r"vehicles\[1\]\.tire\.model: unknown tire model 'tyre'"):
        scenario_from_toml(SCENARIO.replace('[vehicle]\nmodel = "quarter-car"', '[[vehicles]]\nmodel = "quarter-car"\n'
                                                                               '[vehicles.tire]\nmodel = "tyre"'))


def test_unvalidated_unknown_tire_is_not_built_as_another_model():
    # before the registry an unrecognised name became a rigid disk without a word
    with pytest.raises(ValueError, match="unknown tire model 'uniform'; allowed: point, multipoint, disk, rigid-disk"):
        build_tire(TireSpec.model_construct(model="uniform"))
    with pytest.raises(ValueError, match="unknown tire model 'uniform'"):
        _tire("").model_copy(update={"model": "uniform"})


@pytest.mark.parametrize("model,key", [("disk", "n_points"), ("point", "radius"), ("multipoint", "disk_spacing"),
                                       ("rigid-disk", "layout")])
def test_a_parameter_of_another_tire_is_refused_naming_the_key(model, key):
    value = '"cells"' if key == "layout" else "3"
    with pytest.raises(ScenarioError) as err:
        _tire(f'[tire]\nmodel = "{model}"\n{key} = {value}\n')
    msg = str(err.value)
    assert f"tire.{key}: unknown key for tire model {model!r}; allowed keys: " in msg
    allowed = msg.split("allowed keys: ")[1].split(", ")
    assert allowed == ["model", "loss_of_contact", *TIRE_MODELS[model].Parameters.model_fields]
    with pytest.raises(ValueError, match=f"{key}: unknown key for tire model {model!r}"):
        tire_from_parameters(model, **{key: 3})


def test_parameter_ranges_name_the_key():
    with pytest.raises(ScenarioError, match=r"tire\.n_points: expected an integer in \[1, 100\], got 0"):
        _tire('[tire]\nmodel = "multipoint"\nn_points = 0\n')
    with pytest.raises(ScenarioError, match=r"tire\.radius: expected a number in \(0\.05, 2\] \[m\], got 'big' \(a number is written without quotes\)"):
        _tire('[tire]\nmodel = "disk"\nradius = "big"\n')
    with pytest.raises(ValueError, match=r"tire model 'multipoint': n_points: expected an integer in \[1, 100\], got 0"):
        tire_from_parameters("multipoint", n_points=0)


def test_loss_of_contact_is_common_to_every_tire():
    for name in BUILT_IN:
        assert _tire(f'[tire]\nmodel = "{name}"\nloss_of_contact = false\n').loss_of_contact is False


def test_copy_with_another_model_keeps_only_what_that_model_takes():
    multi = _tire('[tire]\nmodel = "multipoint"\nn_points = 4\ncontact_length = 0.3\nloss_of_contact = false\n')
    point = multi.model_copy(update={"model": "point"})
    assert build_tire(point) == PointTire() and point.loss_of_contact is False
    assert build_tire(multi.model_copy(update={"n_points": 6})) == MultiPointTire(6, 0.3)
    disk = _tire('[tire]\nmodel = "disk"\nradius = 0.6\n')
    assert build_tire(disk.model_copy(update={"model": "rigid-disk"})) == RigidDiskTire(radius=0.6, spacing=0.01, max_gap=0.12)


def test_registration_rules(extra_tire):
    @dataclass(frozen=True)
    class Impostor(extra_tire):
        pass

    with pytest.raises(ValueError, match="'twin-point' is taken by"):
        register_tire(Impostor)

    @dataclass(frozen=True)
    class Nameless(PointTire):
        name = ""

    with pytest.raises(ValueError, match="no scenario name"):
        register_tire(Nameless)

    @dataclass(frozen=True)
    class Unsourced(PointTire):
        name = "unsourced"
        references = ("NoSuchPaper2099",)

    with pytest.raises(ValueError, match="unknown reference key.*'NoSuchPaper2099'"):
        register_tire(Unsourced)
    assert "unsourced" not in TIRE_MODELS


def test_a_registered_tire_is_usable_from_a_scenario(extra_tire):
    spec = _tire('[tire]\nmodel = "twin-point"\ngap = 0.3\n')
    assert build_tire(spec) == extra_tire(gap=0.3)
    with pytest.raises(ScenarioError, match=r"tire\.n_points: unknown key for tire model 'twin-point'; "
                                            r"allowed keys: model, loss_of_contact, gap"):
        _tire('[tire]\nmodel = "twin-point"\nn_points = 2\n')
    assert key_unit("tire.gap") == "m"


def test_cite_takes_the_tire_references_from_the_class(extra_tire):
    def keys(tire: str) -> list[str]:
        return [r.key for r in scenario_references(scenario_from_toml(SCENARIO + tire))]

    multi = keys('[tire]\nmodel = "multipoint"\n')
    assert "AASHTO-LRFD" in multi and multi.index("AASHTO-LRFD") < multi.index("NigamJennings1969")  # tire before integrator
    assert "Yin2010" in keys('[tire]\nmodel = "disk"\n') and "Chang2011" in keys('[tire]\nmodel = "rigid-disk"\n')
    point = keys('[tire]\nmodel = "point"\n')
    assert not {"Yin2010", "Chang2011", "Hambly1991"} & set(point)
    # bridge, vehicle, then the tire's own entries, then integrator and code lines
    at = point.index("Biggs1964") + 1  # the quarter car's
    assert keys('[tire]\nmodel = "twin-point"\n') == [*point[:at], "Hambly1991", *point[at:]]


def test_catalogue_lists_every_model_with_parameters_and_defaults(extra_tire):
    catalogue = dict(tire_catalogue())
    assert list(catalogue) == list(TIRE_MODELS)
    assert catalogue["point"] == "single-point contact"
    assert "n_points (default 6), contact_length (default 0.254 m), layout = ends | cells (default ends)" in catalogue["multipoint"]
    assert "Eq. 6" in catalogue["multipoint"]
    for name in ("disk", "rigid-disk"):
        assert catalogue[name].endswith("radius (default 0.5 m), disk_spacing (default 0.01 m)")
    assert catalogue["twin-point"] == "two points, half the spring each; gap (default 0.2 m)"


def test_study_axes_accept_tire_parameters_only():
    base = {"bridge": {"model": "beam", "span": 10.0, "EI": 5e9, "mass_per_length": 5000.0, "n_modes": 3},
            "vehicle": {"model": "quarter-car"}, "tire": {"model": "disk"}, "crossing": {"speed": 20.0}}
    study = parse_study({"name": "s", "base": base, "axes": {"tire.radius": [0.4, 0.6]}})
    assert [a.key for a in study.axes] == ["tire.radius"]
    with pytest.raises(StudyError, match=r"unknown key 'gauge' in \[tire\]; allowed: model, loss_of_contact, n_points"):
        parse_study({"name": "s", "base": base, "axes": {"tire.gauge": [1, 2]}})
    with pytest.raises(StudyError, match=r"tire\.n_points"):  # a multipoint parameter on a disk
        parse_study({"name": "s", "base": base, "axes": {"tire.n_points": [1, 2]}})
