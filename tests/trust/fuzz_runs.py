"""Generated valid-but-extreme inputs of ``vbikit lifetime``, ``vbikit driveby`` and ``vbikit rail``
that are RUN (not only validated), and the oracle of their outputs: at exit 0 the JSON summaries
hold no NaN or Infinity and the NetCDF datasets no non-finite number except where the dataset
documents one (its ``long_name`` says what NaN means, or the variable is in ``MAY_BE_NAN``: ragged
padding and "not applicable" entries present on the unmodified inputs too); a refusal must be one
clean ``error:`` line with exit code 2.  Used by ``test_fuzz_runs.py``."""
from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import numpy as np
from fuzz_commands import BASES, RECORDS, _set
from hypothesis import strategies as st

#: tiny inputs: one or two cases, a few days, a narrow speed range
SMALL: dict[str, dict[str, Any]] = {
    "lifetime": {"traffic": {"trucks_per_day": 60.0}},
    "driveby": {"sweep": {"speed": [8.0], "damage_position": [11.25], "damage_length": 2.5, "damage_severity": [0.0, 0.3]}},
    "rail": {"speeds": {"min": 150.0, "max": 200.0, "step": 25.0}},
}

#: (key path, extreme values inside the documented range), per command
EXTREMES: dict[str, list[tuple[tuple, list]]] = {
    "rail": [(("bridge", "span"), [8.0, 60.0]), (("bridge", "damping"), [0.0, 0.19]), (("bridge", "EI"), [5e8, 5e12]),
             (("bridge", "mass_per_length"), [800.0, 2e5]), (("speeds", "min"), [5.0]), (("speeds", "max"), [420.0]),
             (("speeds", "step"), [0.5, 100.0]), (("run", "points"), [1, 25]), (("trains", "presets"), [["hslm-a10"]]),
             (("bridge", "n_modes"), [1])],
    "driveby": [(("crossing", "speed"), [0.5, 40.0]), (("sweep", "speed"), [[0.5], [40.0]]), (("vehicle", "mass"), [1.0, 5e4]),
                (("vehicle", "frequency_hz"), [0.5, 40.0]), (("sensors", 0, "noise_rms"), [0.0, 100.0]),
                (("sweep", "damage_severity"), [[0.0, 0.99]]), (("sampling", "rate"), [50.0, 2000.0]),
                (("vehicle", "damping_ratio"), [0.0, 0.5]), (("sweep", "damage_length"), [0.01, 20.0])],
    "lifetime": [(("amplification",), [0.01, 5.0]), (("traffic", "trucks_per_day"), [5.0, 400.0]),
                 (("return_periods",), [[1.5, 1e4]]), (("fatigue", "damage_so_far"), [0.0, 0.999]),
                 (("fatigue", "details", 0, "section_modulus"), [1e-4, 10.0]), (("fatigue", "histogram_bin"), [1.0, 1e8]),
                 (("ci",), [0.5, 0.999]), (("fatigue", "dynamic_sample"), [0.0, 0.3])],
}

#: variables whose NaN (or ±inf) is a documented "does not apply" on ordinary inputs too
MAY_BE_NAN: dict[str, set[str]] = {
    "rail": {"peak_acceleration_grid", "peak_speed_grid", "peak_speed_refined", "peak_grid_error", "peak_refinement_bound",
             "peak_last_change", "peak_speed_step", "resonance_speed", "excitation_wavelength",
             "bogie_axle_spacing", "bogie_resonance_speed"},  # bogie_*: NaN for a train without (or with fewer) bogie spacings
    "driveby": {"multipass_frequency_hz", "multipass_q25_hz", "multipass_q75_hz", "multipass_mean_hz", "multipass_std_hz",
                "mode_shape_mac", "curvature_change", "curvature_change_x"},
    "lifetime": {"fit_pot_total_shape", "fit_pot_static_shape", "code_allowance", "dynamic_damage_ratio",
                 "remaining_life"},  # remaining_life: inf when the damage per year is 0 (never reached)
}


@st.composite
def extreme_inputs(draw, kind: str) -> tuple[dict, dict[str, str]]:
    """(file as a dict, further files) of a small valid run of ``kind`` with one to three keys at
    an extreme of their range."""
    data = copy.deepcopy(BASES[kind])
    for section, values in SMALL[kind].items():
        data[section] = {**data.get(section, {}), **values} if isinstance(values, dict) else values
    if kind == "driveby":
        data["sweep"] = dict(SMALL["driveby"]["sweep"])
    for path, values in draw(st.lists(st.sampled_from(EXTREMES[kind]), min_size=1, max_size=3, unique_by=lambda e: e[0])):
        _set(data, path, draw(st.sampled_from(values)))
    files: dict[str, str] = {}
    if kind == "lifetime":
        files["records.csv"] = "\n".join(RECORDS) + "\n"
    if kind == "rail":
        load = draw(st.sampled_from([170.0, 0.5, 3000.0]))  # kN a axle
        files["train.csv"] = "position_m,load_kN\n" + "".join(f"{x},{load}\n" for x in (0, 3, 14, 17))
    return data, files


def _no_constants(name: str) -> None:
    raise ValueError(f"{name} in a JSON output")


def non_finite(out_dir: Path, kind: str) -> list[str]:
    """Every non-finite number in the run's JSON and NetCDF outputs that the dataset does not
    document (module docstring); [] when clean."""
    import xarray as xr

    found = []
    for path in sorted(out_dir.glob("*.json")):
        try:
            json.loads(path.read_text(), parse_constant=_no_constants)
        except ValueError as err:
            found.append(f"{path.name}: {err}")
    for path in sorted(out_dir.glob("*.nc")):
        with xr.open_dataset(path) as ds:
            for name, var in ds.variables.items():
                if var.dtype.kind not in "fc":
                    continue
                values = np.asarray(var.values)
                bad = ~np.isfinite(values)
                if not bad.any():
                    continue
                if not _documented(ds, name, kind):
                    kinds = "infinite" if np.isinf(values).any() else "NaN"
                    found.append(f"{path.name}:{name}: {int(bad.sum())} {kinds}")
    return found


def _documented(ds, name: str, kind: str) -> bool:
    """Whether the dataset says what a non-finite value of ``name`` means: its long_name names NaN
    or inf, it carries a non-empty ``missing_because``, or it is
    one of ``MAY_BE_NAN``."""
    var = ds[name]
    text = str(var.attrs.get("long_name", ""))
    because = var.attrs.get("missing_because")
    return "NaN" in text or "inf" in text.replace("information", "") or bool(because) or name in MAY_BE_NAN[kind]
