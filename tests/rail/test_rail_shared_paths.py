"""A railway sweep's shared files name no folder of the machine it ran on."""
from vbikit.rail.run import run_rail


def test_a_scenario_bridge_is_named_by_its_file_name(tmp_path):
    """``bridge.scenario`` given as an absolute path: rail.nc's ``bridge_model`` says ``… from deck.toml``
    (before 2026-12-06 the whole path), and no attribute, summary or report line holds the folder."""
    (tmp_path / "deck.toml").write_text('name = "beam"\n[bridge]\nmodel = "beam"\nspan = 20.0\nEI = 7.9e10\n'
                                        'mass_per_length = 25000.0\ndamping_ratio = 0.03\n')
    out = tmp_path / "out"
    r = run_rail({"bridge": {"scenario": str(tmp_path / "deck.toml"), "deck": "steel"},
                  "trains": {"presets": ["hslm-a1"]}, "speeds": {"min": 200.0, "max": 220.0, "step": 20.0}},
                 out_dir=out, figures=False)
    assert r.dataset.attrs["bridge_model"].endswith(" from deck.toml")
    texts = [str(v) for v in r.dataset.attrs.values()] + [r.report]
    texts += [p.read_text() for p in out.iterdir() if p.suffix in (".json", ".txt")]
    assert len(texts) > len(r.dataset.attrs) + 1  # (the summary and report files were read)
    assert not [t for t in texts if str(tmp_path) in t]
