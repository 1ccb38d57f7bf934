"""Figures of a drive-by dataset: a spectrogram of a sensor record, identified against true
frequency by speed, and the damage indicator against severity (matplotlib imported inside)."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def spectrogram_figure(ds, case: int = 0, sensor: int = 0):
    """Spectrogram (``scipy.signal.spectrogram``, Hann segments of 1 s) of one case's sensor record,
    with the true bridge frequency marked."""
    import matplotlib.pyplot as plt
    from scipy.signal import spectrogram


    fs = float(ds.attrs["sampling_rate"])
    x = np.asarray(ds["sensor_history"].values[case, sensor], float)
    x = x[np.isfinite(x)]
    nper = min(x.size, max(16, int(fs)))
    f, t, s = spectrogram(x - x.mean(), fs, window="hann", nperseg=nper, noverlap=nper * 7 // 8, nfft=4 * nper)
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    keep = f <= min(25.0, fs / 2)
    ax.pcolormesh(t + float(ds["time_start"][case]), f[keep], 10 * np.log10(s[keep] + 1e-30), shading="auto")
    ax.axhline(float(ds["bridge_frequency_hz"][case]), color="w", ls="--", lw=1, label="bridge f₁ (true)")
    for name in ("record_start", "record_end"):
        ax.axvline(float(ds[name][case]), color="w", lw=0.8, ls=":")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(f"spectrogram of {ds['sensor'].values[sensor]} (case {case}), dB")
    ax.legend(loc="upper right")
    fig.tight_layout()
    return fig


def frequency_figure(ds):
    """Identified and true first frequency against speed (one marker per road class; crosses:
    identifications flagged unreliable)."""
    import matplotlib.pyplot as plt


    fig, ax = plt.subplots(figsize=(6.0, 3.8))
    healthy = np.asarray(ds["damage_severity"].values) == 0
    reliable = np.asarray(ds["identified_frequency_reliable"].values, bool)
    for k, road in enumerate(sorted(set(ds["road_class"].values.tolist()))):
        sel = healthy & (ds["road_class"].values == road)
        if (sel & reliable).any():
            ax.plot(ds["speed"].values[sel & reliable], ds["identified_frequency_hz"].values[sel & reliable], "o",
                    color=f"C{k}", label=f"identified, road {road}")
        if (sel & ~reliable).any():
            ax.plot(ds["speed"].values[sel & ~reliable], ds["identified_frequency_hz"].values[sel & ~reliable], "x",
                    color=f"C{k}", label=f"flagged unreliable, road {road}")
    true = ds["bridge_frequency_hz"].values[healthy]
    if true.size:
        ax.axhline(float(true[0]), color="k", lw=1, label="true f₁ (healthy)")
    ax.set_xlabel("speed [m/s]")
    ax.set_ylabel("first frequency [Hz]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def damage_figure(ds):
    """Identified (reliable passes only; unreliable ones give none) and true relative frequency
    shift against damage severity, and the multi-pass estimate's."""
    import matplotlib.pyplot as plt


    fig, ax = plt.subplots(figsize=(6.0, 3.8))
    sev = ds["damage_severity"].values
    ax.plot(sev, 100 * ds["identified_frequency_shift"].values, "o", label="identified")
    ax.plot(sev, 100 * ds["bridge_frequency_shift"].values, "k_", ms=14, label="true (modal model)")
    res = 100 * ds["resolution_hz"].values / ds["bridge_frequency_hz"].values
    ax.errorbar(sev, 100 * ds["identified_frequency_shift"].values, yerr=res, fmt="none", ecolor="0.6", lw=0.8,
                label="± resolution 1/T")
    ax.plot(sev, 100 * ds["multipass_frequency_shift"].values, "s", mfc="none", label="multi-pass medians")
    ax.set_xlabel("damage severity (EI loss) [-]")
    ax.set_ylabel("first-frequency shift [%]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def write_figures(ds, out_dir: str | Path) -> list[Path]:
    """Write driveby-spectrogram.png, driveby-frequency-vs-speed.png and (with damage cases)
    driveby-damage.png into ``out_dir``."""
    from vbikit._files import save_figure

    out_dir = Path(out_dir)
    written = []
    figs = [("driveby-spectrogram.png", spectrogram_figure(ds)), ("driveby-frequency-vs-speed.png", frequency_figure(ds))]
    if np.any(np.isfinite(ds["identified_frequency_shift"].values) & (ds["damage_severity"].values > 0)):
        figs.append(("driveby-damage.png", damage_figure(ds)))
    for name, fig in figs:
        written.append(save_figure(fig, out_dir / name, dpi=120))
    return written
