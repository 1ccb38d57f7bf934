"""Field verification: calibrating a bridge model to measured responses.

A synthetic field test with known truth (the Cypress Bayou deck made 10 % stiffer with 2.5 %
damping, crossed by the dump truck at 64.4 km/h over a 38.1 mm bump, recorded at 200 Hz with
noise, an accelerometer offset and drift) is compared with the nominal model and calibrated:
the least-squares fit recovers the stiffness factor and the damping ratio.
"""
import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from vbikit.field import calibrate, compare_case, load_field_toml
from vbikit.field.synthetic import write_synthetic_case

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

with tempfile.TemporaryDirectory() as tmp:
    truth = write_synthetic_case(tmp, free_vibration=2.0, cases=("case1",))
    spec = load_field_toml(Path(tmp) / "FIELD.toml")
    nominal = compare_case(spec, spec.cases[0], ["multipoint"])
    cal = calibrate(spec, [nominal], tire="multipoint", max_nfev=20)
    fitted = compare_case(spec, spec.cases[0], ["multipoint"], stiffness_factor=cal.stiffness_factor,
                          damping_ratio=cal.damping_ratio)

channel = next(ch for ch in spec.cases[0].channels if ch.quantity == "displacement")
fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
ax.plot(nominal.time, 1e3 * nominal.measured[channel.name], color="0.7", lw=3, label="measured (synthetic)")
for cmp, label, style in ((nominal, "nominal model", "--"), (fitted, "calibrated model", "-")):
    ax.plot(cmp.time, 1e3 * cmp.simulated["multipoint"][channel.name], style, lw=1, label=label)
ax.set(xlabel="time [s]", ylabel=f"{channel.name} [mm]",
       title=f"stiffness factor {cal.stiffness_factor:.3f} (truth {truth.stiffness_factor}), "
             f"damping {cal.damping_ratio:.4f} (truth {truth.damping_ratio})")
ax.legend(fontsize=8)
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "field_calibration.png", dpi=110)
print(f"stiffness factor {cal.stiffness_factor:.4f}, damping ratio {cal.damping_ratio:.4f}")
