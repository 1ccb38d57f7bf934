"""The folder form of a traffic stream's outputs (``vbikit traffic --out-dir DIR``), as a lifetime, drive-by or
railway run writes its folder: the dataset ``traffic.nc``, the report ``traffic-report.txt`` (what the command
prints), ``traffic-summary.json`` (``summary``) and the figure ``traffic-im.png`` (``vbikit.plot.traffic.plot_stream``).
``vbikit traffic --out FILE.nc`` writes the dataset only."""
from __future__ import annotations

import json
from typing import Any

#: the files ``vbikit traffic --out-dir`` writes (checked before the run, ``vbikit._files.output_names``), and the
#: folder of its finished batches (``vbikit.study.storage.parts_dir`` of the dataset)
DATASET_FILE, REPORT_FILE, SUMMARY_FILE, FIGURE_FILE = ("traffic.nc", "traffic-report.txt", "traffic-summary.json",
                                                        "traffic-im.png")
WORK_FOLDER = DATASET_FILE + ".parts"

#: the half-step check of the governing events kept in the summary (the dataset's attributes of that name)
_HALF_STEP = ("governing_static_half_step_im_change", "governing_dynamic_half_step_im_change", "half_step_tolerance")
#: and every stored impact factor's change there (the dataset's JSON attributes; the report prints the largest)
_HALF_STEP_CHANGES = ("governing_static_half_step_changes", "governing_dynamic_half_step_changes")


def summary(ds: Any, dataset: str = DATASET_FILE) -> dict[str, Any]:
    """The stream's results as plain data for ``traffic-summary.json`` (``dataset``: the name of the dataset file it
    summarises, ``traffic.nc`` in a folder, ``--out``'s name otherwise): the statistics at the first response point
    (``vbikit.traffic.study.stream_statistics``: event counts, the impact-factor distribution with the 95 %
    confidence intervals, the governing events with their deflections and dynamic amplification), their half-step
    check, where the stream starts (``start_words``), the flag codes, the ``warnings`` (a list of messages) and
    ``flags`` (their records: code, message, output, subject, value, threshold), as every summary gives them, and ``units``: each number's unit (``summary_unit``).  NaN stays NaN here; the writer gives
    null (``vbikit._files.json_text``)."""
    from vbikit.analysis.population_start import start_words
    from vbikit.traffic.study import stream_statistics

    attrs = dict(ds.attrs)
    stats = stream_statistics(ds)
    # the governing events the run stored (its half-step check is of them)
    # (not their deflections: stream_statistics reads those from the variables at the same events, signed, z up, also
    # for a dataset written when the attribute held the magnitude)
    stats |= {k: attrs[k] for k in stats if k.startswith("governing_") and k in attrs and not k.endswith("_deflection")}
    # the flags as records and their messages as a list, as every summary gives them (a dataset written before the
    # records were stored: its "; "-joined messages as one)
    from vbikit.analysis.checks import dataset_flag_codes, dataset_flags

    codes = dataset_flag_codes(attrs)
    records, warnings = dataset_flags(attrs)
    changes = {k: json.loads(attrs[k]) for k in _HALF_STEP_CHANGES if attrs.get(k)}  # (every stored IM's change)
    out = {"dataset": dataset, "vbikit_version": str(attrs.get("vbikit_version", "")), **stats,
           **{k: attrs[k] for k in _HALF_STEP if k in attrs}, **changes,
           "start": start_words(attrs), "flag_codes": codes, "warnings": warnings, "flags": records}
    return out | {"units": {k: unit for k in out if (unit := summary_unit(k))}}


def summary_unit(key: str) -> str:
    """The unit of a number of ``summary`` (SI, as the dataset; "" for words and lists of words)."""
    if key.endswith("_deflection"):
        return "m"
    # (an event index, from 0, and a count are dimensionless in CF too, as the dataset's counts)
    if key.startswith(("n_", "im_", "governing_")) or key.endswith(("_event", "_counts", "_fraction", "_tolerance",
                                                                    "_change")):
        return "1"
    return ""
