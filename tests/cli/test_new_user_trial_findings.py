"""What a new user's trial of the shipped examples found (2026-12-06, main at 226cc2d), each test
failing on the code before its fix:

1. ``vbikit run SCENARIO --random`` printed ``peak displacement -2.3691 ± 0.1981 mm`` with no word
   of what ± means (a standard deviation over the road's realisations, not a confidence interval)
   and closed with ``wavenumber lines: 254, grid check 0.69%; 2.5 s`` — a bare time and a check
   without its meaning.
2. ``vbikit compare-tires examples/paper/fig9_tire_models.toml`` in a fresh install printed the disk
   tire's ``time [s]`` as 63.96 against 0.08–2.66 for the others: numba's first compilation of the
   full contact kernel, unsaid, read as the disk tire's cost.
3. ``vbikit study paper-all --out-dir out`` after ``vbikit study paper-fig6 --out-dir out`` printed
   ``1440 crossings -> out/paper-fig6.nc (0.0 s)``: the finished dataset read back, as if run in no
   time (the study runner says so only in an INFO log).
4. ``vbikit lifetime examples/lifetime/lifetime.toml`` opened with ``WARNING vbikit.lifetime.run: an
   event's dynamic amplification 0.742 exceeds …`` — a Python logger's name and level where every
   other warning of the CLI reads ``warning: …``.
5. ``vbikit lifetime`` and ``vbikit driveby`` write ``summary.json`` / ``driveby-summary.json``
   (docs/lifetime.md, docs/driveby.md) which neither their ``--out-dir`` help nor docs/cli.md's
   table named.
6. ``vbikit run examples/verification/yang_yau_sprung_mass.toml`` printed ``max |acceleration|
   0.4026 m/s²`` beside the example's own "sprung-mass peak acceleration ≈ 0.15 m/s²": the line is
   the deck's acceleration at the response point (the sprung mass's peak is 0.156 m/s²), unsaid.
7. ``vbikit study paper-fig10`` while the shared machine ran out of memory: a worker was killed and
   the command ended with a 50-line traceback (``BrokenProcessPool``), exit code 1 — which
   docs/cli.md reserves for a bug in vbikit.
"""
from __future__ import annotations

from types import SimpleNamespace

from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()


def _random_summary() -> dict:
    """A PEM summary with the keys the text report reads (the demo's numbers, rounded)."""
    return {
        "name": "demo", "method": "pseudo-excitation", "warnings": [], "effects": [],
        "points": [{"x": 8.38, "y": 0.0, "displacement_peak_mean": -2.369e-3, "displacement_peak_std": 0.198e-3,
                    "static_peak": -1.969e-3, "impact_factor_mean": 0.203, "impact_factor_std": 0.101,
                    "impact_factor_quantiles": {"0.5": 0.196, "0.9": 0.337, "0.95": 0.381},
                    "displacement_std_max": 0.314e-3, "acceleration_std_max": 0.586, "strain_std_max": 8.6e-6}],
        "wheel_force_std_max": {}, "vehicle_acceleration_std_max": {}, "lift_off_probability": 0.0052,
        "n_lines": 254, "grid_change": 0.0069, "seconds": 2.5, "quality": "…",
    }


def test_random_report_says_what_plus_minus_and_the_closing_numbers_are(tmp_path, monkeypatch):
    import vbikit.scenario.pipeline as pipeline

    monkeypatch.setattr(pipeline, "run_random", lambda scenario, limits=None: SimpleNamespace(summary=_random_summary()))
    scenario = tmp_path / "s.toml"
    scenario.write_text("[bridge]\n", encoding="utf-8")  # (not read: the run is replaced)
    out = runner.invoke(app, ["run", str(scenario), "--random"])
    assert out.exit_code == 0, out.output
    text = out.stdout
    assert "mean ± standard deviation over the road's realisations" in text
    assert text.index("standard deviation") < text.index("peak displacement")  # said before the first ±
    assert "grid check 0.69% (σ on every second line against every line); run time 2.5 s" in text


def test_compare_tires_marks_a_time_that_includes_a_first_compilation(tmp_path, monkeypatch):
    """The run that compiles a kernel (faked: the disk tire's announces one) gets ``*`` after its time
    and a footnote saying why; the kernel's name is kept in compare-tires.json."""
    import json

    import vbikit.plot
    import vbikit.scenario.pipeline
    from vbikit.solve import compile_notice

    summary = {"warnings": [], "flags": [], "max_dynamic_displacement": -3.4e-3, "impact_factor": 0.21,
               "max_dynamic_strain": 9e-5, "strain_impact_factor": 0.2, "max_abs_acceleration": 2.5,
               "min_wheel_force": {"axle1_left": 1e3}, "contact_loss": {"axle1_left": {"lost": False}},
               "response_x": 5.0, "response_y": 0.0, "points": [{"name": "p1"}], "max_static_displacement": -2.8e-3,
               "dt": 1e-3, "step_check": {"dt": 5e-4, "largest_change": 1e-5, "acceleration_change": 1e-3}}

    def fake_run(plan, *args, **kwargs):  # (the runs are checked for real, then "run")
        if plan.scenario.tire.model == "disk":
            monkeypatch.setattr(compile_notice, "_ANNOUNCED", compile_notice._ANNOUNCED | {"fake_kernel"})
        return SimpleNamespace(summary=summary, response=None)

    monkeypatch.setattr(vbikit.scenario.pipeline, "run_planned", fake_run)
    monkeypatch.setattr(vbikit.plot, "plot_tire_comparison", lambda responses, path, name: path)
    monkeypatch.setattr(compile_notice, "_ANNOUNCED", set())
    scenario = tmp_path / "s.toml"
    scenario.write_text(BEAM_SCENARIO, encoding="utf-8")
    out = runner.invoke(app, ["compare-tires", str(scenario), "--out-dir", str(tmp_path / "out")])
    assert out.exit_code == 0, out.output
    rows = {line.split()[0]: line for line in out.stdout.splitlines() if line.startswith("  ") and "[" not in line}
    assert rows["disk"].rstrip().endswith(" *") and not rows["point"].rstrip().endswith("*")
    assert "includes numba's first compilation of a kernel" in out.stdout
    table = json.loads((tmp_path / "out" / "compare-tires.json").read_text())
    assert table["disk"]["compiled_kernels"] == ["fake_kernel"] and table["point"]["compiled_kernels"] == []
    # it says what it wrote, one `wrote PATH` line a file, as every command that writes files (standard error with --json)
    wrote = [line for line in out.stdout.splitlines() if line.startswith("wrote ")]
    assert wrote == [f"wrote {tmp_path / 'out' / 'compare-tires.png'}", f"wrote {tmp_path / 'out' / 'compare-tires.json'}"]
    js = runner.invoke(app, ["compare-tires", str(scenario), "--out-dir", str(tmp_path / "out"), "--json"])
    assert js.exit_code == 0 and json.loads(js.stdout)["point"]["impact_factor"] == 0.21
    assert [line for line in js.stderr.splitlines() if line.startswith("wrote ")] == wrote


BEAM_SCENARIO = """
[bridge]
model = "beam"
span = 25.0
EI = 8.323e9
mass_per_length = 2303.0
[vehicle]
model = "moving-force"
force = 1e5
[crossing]
speed_kmh = 60
"""


def test_a_study_already_finished_in_its_output_says_so(tmp_path, monkeypatch, capsys):
    import vbikit.study.run
    from vbikit.cli.guard import STATE
    from vbikit.cli.study import run_job

    monkeypatch.setitem(STATE, "json", False)  # (no --json: as a command's own start sets it; a test before may have run one)
    monkeypatch.setattr(vbikit.study.run, "run_study", lambda study, out, **kwargs: "dataset")
    study = SimpleNamespace(name="paper-fig6", size=1440)
    fresh, finished = tmp_path / "fresh.nc", tmp_path / "finished.nc"
    finished.write_bytes(b"")  # (what is in it is the runner's business: replaced here)
    assert run_job(study, fresh, 1, None, False) == "dataset"
    assert "1440 crossings -> " in capsys.readouterr().out
    assert run_job(study, finished, 1, None, False) == "dataset"
    text = capsys.readouterr().out
    assert "already holds this finished run" in text and "nothing run" in text and " -> " not in text


def test_a_library_warning_reads_as_the_cli_s_own(tmp_path):
    """At the default verbosity a logged warning prints as ``warning: …`` (the CLI's own form), without
    the logger's name; ``-v`` keeps the name (for a developer); the compile notice (INFO) is unchanged."""
    import logging

    from vbikit.cli import _PlainWarnings

    fmt = _PlainWarnings("%(levelname)s %(name)s: %(message)s")
    record = logging.LogRecord("vbikit.lifetime.run", logging.WARNING, __file__, 1,
                               "an event's dynamic increment (IM) %.3f exceeds the screening bound", (0.742,), None)
    assert fmt.format(record) == "warning: an event's dynamic increment (IM) 0.742 exceeds the screening bound"
    info = logging.LogRecord("vbikit.solve.compile", logging.INFO, __file__, 1, "compiling the kernel lean", (), None)
    assert fmt.format(info) == "INFO vbikit.solve.compile: compiling the kernel lean"

    # through the command line: the handler the CLI installs uses it at the default level, not with -v
    runner.invoke(app, ["presets"])
    assert all(isinstance(h.formatter, _PlainWarnings) for h in logging.getLogger().handlers)
    runner.invoke(app, ["-v", "presets"])
    assert not any(isinstance(h.formatter, _PlainWarnings) for h in logging.getLogger().handlers)


#: the files each batch command writes into --out-dir, as its page says (docs/lifetime.md,
#: docs/driveby.md, docs/railway.md)
WRITES = {"lifetime": ("lifetime.nc", "report.txt", "summary.json"),
          "driveby": ("driveby.nc", "driveby-report.txt", "driveby-summary.json"),
          "rail": ("rail.nc", "rail-report.txt", "rail-summary.json")}


def test_out_dir_help_and_cli_page_name_every_file_written():
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "cli.md").read_text(encoding="utf-8")
    for command, names in WRITES.items():
        res = runner.invoke(app, [command, "--help"], env={"COLUMNS": "400"})
        assert res.exit_code == 0, res.output
        lines = res.output.splitlines()
        start = next(i for i, line in enumerate(lines) if line.lstrip().startswith("--out-dir"))
        end = next(i for i in range(start + 1, len(lines)) if lines[i].lstrip().startswith("--"))
        help_line = " ".join(line.strip() for line in lines[start:end]).replace("- ", "-")  # (wrapped at hyphens)
        (row,) = [line for line in page.splitlines() if line.startswith(f"| `vbikit {command} ")]
        for name in names:
            assert name in help_line, (command, name, help_line)
            assert f"`{name}`" in row or f"`DIR/{name}`" in row, (command, name, row)


def test_the_report_says_whose_acceleration_it_prints(tmp_path):
    scenario = tmp_path / "beam.toml"
    scenario.write_text(BEAM_SCENARIO, encoding="utf-8")
    out = runner.invoke(app, ["run", str(scenario)])
    assert out.exit_code == 0, out.output
    (line,) = [line for line in out.stdout.splitlines() if "max |acceleration|" in line]
    # a moving force rings the beam's highest modes: its peak acceleration moves by 2.6 % at half the step, flagged
    # (step_not_converged) and marked "!" beside its unit
    assert line.rstrip().endswith("m/s²! (the deck's, at the response point)"), line
    assert "max_abs_acceleration is not converged in the time step" in out.output


def test_a_worker_killed_by_the_system_is_an_error_line_not_a_traceback(capsys):
    from concurrent.futures.process import BrokenProcessPool

    import pytest
    import typer

    from vbikit.cli.guard import STATE, guard

    def killed():
        raise BrokenProcessPool("A process in the process pool was terminated abruptly")

    with pytest.raises(typer.Exit) as exit_:
        guard(killed)
    assert exit_.value.exit_code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: a worker process ended abruptly") and "out of memory" in err
    assert "fewer --workers" in err and "resumes" in err and "Traceback" not in err
    with pytest.raises(ValueError):  # any other exception stays a bug's traceback
        guard(lambda: (_ for _ in ()).throw(ValueError("a bug")))
    STATE["debug"] = True
    try:
        with pytest.raises(BrokenProcessPool):  # --debug: the traceback
            guard(killed)
    finally:
        STATE["debug"] = False
