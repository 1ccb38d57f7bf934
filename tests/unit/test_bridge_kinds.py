"""[bridge] kinds: one spec class per kind, chosen by ``model``, each with only its own keys and
its own ``build``; a key of another kind is refused naming the key, the kind's allowed keys and
the kind that takes it; every kind and every preset builds from a minimal TOML."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import BRIDGE_PRESETS, EulerBernoulliBeam, ModalBridge, SlabOnGirderBridge
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.bridge.modefile import modes_from_file, write_modes
from vbikit.scenario.build import build_bridge
from vbikit.scenario.bridge_spec import BeamSpec, ContinuousBeamSpec, ModesFileSpec, PresetBridgeSpec, SlabOnGirderSpec
from vbikit.scenario.schema import ScenarioError, parse_bridge, scenario_from_toml

REST = '[vehicle]\nmodel = "hs20-44"\n[crossing]\nspeed_kmh = 72\n'
BEAM = 'span = 10.0\nEI = 5e9\nmass_per_length = 5000.0\n'
CONTINUOUS = 'model = "continuous-beam"\nspans = [5.0, 5.0]\nEI = 5e9\nmass_per_length = 5000.0\nelements_per_span = 4\n'
SLAB = 'model = "slab-on-girder"\nn_modes = 2\n[bridge.deck]\nspan = 8.0\nn_girders = 3\nn_elements = 10\n'
MODES = 'model = "modes-file"\nmodes_file = "m.vbikit-modes"\n'

#: minimal [bridge] of each kind and the spec class that takes it
KINDS = {
    "beam (model omitted)": (BEAM, BeamSpec),
    "beam": ('model = "beam"\n' + BEAM, BeamSpec),
    "continuous-beam": (CONTINUOUS, ContinuousBeamSpec),
    "slab-on-girder": (SLAB, SlabOnGirderSpec),
    "modes-file": (MODES, ModesFileSpec),
}


def scenario(bridge: str, tmp_path=None):
    return scenario_from_toml("[bridge]\n" + bridge + "\n" + REST, tmp_path or ".")


def refusal(bridge: str) -> str:
    with pytest.raises(ScenarioError) as err:
        scenario(bridge)
    return str(err.value)


def _with(table: str, line: str) -> str:
    """``line`` added to the [bridge] table itself (before any [bridge.deck] sub-table)."""
    head, sep, deck = table.partition("[bridge.deck]")
    return head + line + "\n" + sep + deck


@pytest.mark.parametrize("table, key, line, other", [
    ('model = "beam"\n' + BEAM, "spans", "spans = [5.0, 5.0]", 'model = "continuous-beam"'),
    ('model = "beam"\n' + BEAM, "elements_per_span", "elements_per_span = 8", 'model = "continuous-beam"'),
    ('model = "beam"\n' + BEAM, "modes_file", 'modes_file = "m.vbikit-modes"', 'model = "modes-file"'),
    ('model = "beam"\n' + BEAM, "damage", "damage = []", 'model = "continuous-beam"'),
    (CONTINUOUS, "span", "span = 10.0", 'model = "beam"'),
    (CONTINUOUS, "modes_file", 'modes_file = "m.vbikit-modes"', 'model = "modes-file"'),
    (SLAB, "EI", "EI = 5e9", 'model = "beam"'),
    (SLAB, "neutral_axis_depth", "neutral_axis_depth = 0.5", 'model = "beam"'),
    (SLAB, "spans", "spans = [4.0, 4.0]", 'model = "continuous-beam"'),
    (MODES, "span", "span = 10.0", 'model = "beam"'),
    (MODES, "support_stiffness", "support_stiffness = 1e9", 'model = "continuous-beam"'),
    ('model = "paper-bridge-2"\n', "modes_file", 'modes_file = "m.vbikit-modes"', 'model = "modes-file"'),
    ('model = "paper-bridge-2-beam"\n', "neutral_axis_depth", "neutral_axis_depth = 0.5", 'model = "beam"'),
    ('model = "paper-bridge-2-beam"\n', "EI", "EI = 5e9", 'model = "beam"'),
])
def test_a_kind_refuses_a_key_of_another_kind(table, key, line, other):
    msg = refusal(_with(table, line))
    assert f"bridge.{key}: unknown key" in msg, msg
    allowed = msg.split("allowed keys: ")[1].split(" (")[0].split(", ")
    assert key not in allowed and "model" in allowed and "n_modes" in allowed, msg
    assert f"{key} is a key of {other}" in msg and "model = \"preset\"" not in msg, msg


@pytest.mark.parametrize("key, line", [("span", "span = 10.0"), ("spans", "spans = [5.0, 5.0]")])
def test_a_deck_key_on_a_slab_on_girder_preset_names_its_deck_table(key, line):
    """A slab-on-girder preset takes its deck's geometry in [bridge.deck]: the refusal says so (a new user
    wrote span = 30 beside model = "paper-bridge-2" and was sent to model = "beam")."""
    msg = refusal(_with('model = "paper-bridge-2"\n', line))
    assert f"bridge.{key}: unknown key" in msg and f"[bridge.deck] table (bridge.deck.{key})" in msg, msg
    assert "is a key of" not in msg, msg


def test_a_modes_file_key_on_another_kind_says_which_kind_takes_it():
    msg = refusal('model = "paper-bridge-2-beam"\nmodes_file = "m.vbikit-modes"\n')
    assert "bridge.modes_file: unknown key" in msg and 'model = "modes-file"' in msg and "a preset fixes" in msg, msg


@pytest.mark.parametrize("extra, key", [("[bridge.deck]\nn_girders = 3\n", "bridge.deck"),
                                        ("[[bridge.damage]]\nposition = 1.0\nlength = 1.0\nseverity = 0.1\n", "bridge.damage")])
def test_a_beam_preset_refuses_the_deck_presets_overrides(extra, key):
    """One class for every preset; the overrides it allows follow the preset's kind."""
    msg = refusal('model = "paper-bridge-2-beam"\n' + extra)
    assert f"{key}: " in msg and "slab-on-girder" in msg and "'paper-bridge-2-beam'" in msg, msg
    assert scenario('model = "paper-bridge-2"\nn_modes = 2\n' + extra.replace("severity = 0.1", "severity = 0.1\ngirder = 2"))


def test_the_allowed_keys_of_a_beam_preset_leave_out_the_deck_overrides():
    msg = refusal('model = "paper-bridge-2-beam"\nspan = 3.0\n')
    assert "allowed keys: model, damping_ratio, n_modes (" in msg, msg
    msg = refusal('model = "paper-bridge-2"\nspan = 3.0\n')
    assert "allowed keys: model, damage, damping_ratio, n_modes, deck (" in msg, msg


def test_an_unknown_model_lists_every_kind_and_preset():
    msg = refusal('model = "girder-deck"\n')
    assert "bridge.model: unknown bridge model 'girder-deck'; allowed: beam, continuous-beam, slab-on-girder, modes-file, " in msg
    assert all(name in msg for name in BRIDGE_PRESETS)


@pytest.fixture
def modes_dir(tmp_path):
    write_modes(SlabOnGirderBridge(span=8.0, n_girders=3, n_elements=10, n_modes=3), tmp_path / "m.vbikit-modes")
    return tmp_path


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_kind_builds_from_a_minimal_toml(kind, modes_dir):
    table, cls = KINDS[kind]
    s = scenario(table, modes_dir)
    spec = s.bridge
    assert type(spec) is cls
    assert spec.model == kind.split(" ")[0] and spec.damping_ratio == 0.02 and spec.damage is not None
    assert (spec.deck is not None) == (cls is SlabOnGirderSpec)
    bridge = build_bridge(spec, modes_dir)
    assert isinstance(bridge, ModalBridge)
    expected = {
        BeamSpec: lambda: EulerBernoulliBeam(10.0, 5e9, 5000.0),
        ContinuousBeamSpec: lambda: ContinuousBeam(spans=(5.0, 5.0), EI=5e9, mass_per_length=5000.0, elements_per_span=4),
        SlabOnGirderSpec: lambda: SlabOnGirderBridge(span=8.0, n_girders=3, n_elements=10, n_modes=2),
        ModesFileSpec: lambda: modes_from_file(modes_dir / "m.vbikit-modes"),
    }[cls]()
    np.testing.assert_array_equal(bridge.omega, expected.omega)
    np.testing.assert_array_equal(bridge.mode_shapes([3.3], [0.5]), expected.mode_shapes([3.3], [0.5]))


@pytest.mark.parametrize("name", list(BRIDGE_PRESETS))
def test_every_preset_builds_from_a_minimal_toml(name):
    spec = scenario(f'model = "{name}"\nn_modes = 2\n').bridge
    assert type(spec) is PresetBridgeSpec and spec.model == name and spec.deck is None and spec.n_modes == 2
    bridge = spec.build()
    np.testing.assert_array_equal(bridge.omega, BRIDGE_PRESETS[name].build(n_modes=2, damping_ratio=0.02).omega)


def test_parse_bridge_alone_names_the_scenario_key():
    assert type(parse_bridge({"model": "cypress-bayou", "n_modes": 3})) is PresetBridgeSpec
    with pytest.raises(ScenarioError, match=r"^bridge\.deck\.span_x|bridge\.deck: unknown \[bridge\.deck\] key\(s\) 'span_x'"):
        parse_bridge({"model": "cypress-bayou", "deck": {"span_x": 1.0}})
    with pytest.raises(ScenarioError, match=r"^bridge\.n_modes: "):
        parse_bridge({"model": "cypress-bayou", "n_modes": 0})
