"""The tables of docs/reproduction.md ("The claims, one by one", claims 1 and 3, and the IM
ranges of "What is (and is not) modelled") from the datasets of a run of the paper's programme.

    vbikit study paper-all --out-dir out --workers 2
    vbikit study paper-all --out-dir out --workers 2 --beam
    python docs/scripts/reproduction_tables.py out        # prints the markdown to paste, with the run's date

The programme takes minutes to hours (8640 crossings per bridge model), so the tests do not run
it: the page says the date and machine of the run its tables come from.
"""
from __future__ import annotations

import sys
from pathlib import Path

STUDIES = {"fig5": "Fig. 5, Bridge 1, HS20-44", "fig6": "Fig. 6, Bridge 2, HS20-44",
           "fig7": "Fig. 7, Bridge 3, HS20-44", "fig8": "Fig. 8, Bridge 2, two-axle"}


def _open(out: Path, fig: str, beam: bool):
    import xarray as xr

    path = out / f"paper-{fig}{'-beam' if beam else ''}.nc"
    if not path.is_file():
        return None
    with xr.open_dataset(path) as ds:  # closed again: the netCDF library refuses a second open of a held file
        return ds.load()


def claim1(out: Path) -> str:
    """IM(n = 1) − IM(n = 6): mean over the samples, range over the speeds, per class; the share of
    paired crossings with IM(1) > IM(6) (beam values in brackets where they differ)."""
    rows = ["| study | B | C | D | paired: IM(1) > IM(6) |", "|---|---|---|---|---|"]
    for fig, label in STUDIES.items():
        cells = []
        for beam in (False, True):
            ds = _open(out, fig, beam)
            if ds is None:
                cells.append(None)
                continue
            d = ds.impact_factor.sel(tire_n_points=1) - ds.impact_factor.sel(tire_n_points=6)
            m = d.mean("sample")
            cells.append([f"{float(m.sel(road_class=c).min()):+.3f} … {float(m.sel(road_class=c).max()):+.3f}"
                          for c in ("B", "C", "D")] + [f"{float((d > 0).mean()) * 100:.0f} %"])
        g, b = cells
        shown = [x + (f" [beam {y}]" if b is not None and y != x else "") for x, y in zip(g, b or g)]
        rows.append(f"| {label} | " + " | ".join(shown) + " |")
    return "\n".join(rows)


def claim3(out: Path) -> str:
    """max |IM(n) − IM(9)| over classes and speeds, for n = 3 … 5 and n = 6 … 8."""
    rows = ["| study | n = 3 … 5 | n = 6 … 8 |", "|---|---|---|"]
    for fig, label in STUDIES.items():
        cells = []
        for beam in (False, True):
            ds = _open(out, fig, beam)
            if ds is None:
                cells.append(None)
                continue
            m = ds.impact_factor.mean("sample")
            ref = m.sel(tire_n_points=9)
            cells.append([f"{float(abs(m.sel(tire_n_points=list(ns)) - ref).max()):.2g}" for ns in ((3, 4, 5), (6, 7, 8))])
        g, b = cells
        shown = [x + (f" [{y}]" if b is not None and y != x else "") for x, y in zip(g, b or g)]
        rows.append(f"| {label} | " + " | ".join(shown) + " |")
    return "\n".join(rows)


def im_ranges(out: Path) -> str:
    """Range of the mean IM (over the samples) per bridge, 3D programme."""
    parts = []
    for bridge, figs in (("Bridge 1", ("fig5",)), ("Bridge 2", ("fig6", "fig10", "fig11")), ("Bridge 3", ("fig7",))):
        means = [_open(out, f, False).impact_factor.mean("sample") for f in figs]
        parts.append(f"{bridge} {min(float(m.min()) for m in means):.2f}–{max(float(m.max()) for m in means):.2f}")
    return "Girder 4 mean IM: " + ", ".join(parts)


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
    ds = _open(out, "fig6", False)
    print(f"<!-- from {out}: vbikit {ds.attrs.get('vbikit_version')} -->\n")
    print(im_ranges(out), "\n")
    print(claim1(out), "\n")
    print(claim3(out))
