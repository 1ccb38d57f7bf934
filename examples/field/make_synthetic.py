"""Regenerate the synthetic field test in this folder (known truth, see docs/field.md).

    python examples/field/make_synthetic.py          # writes FIELD.toml, profiles, records here
    vbikit field examples/field/FIELD.toml --calibrate

Truth: Cypress Bayou deck with every stiffness × 1.10 and 2.5 % damping (FIELD.toml describes
the nominal model: × 1.00, 2 %); dump truck at 64.4 km/h with multipoint tires over a 38.1 mm
wood bump at the span entry; records at 200 Hz on the recorder's clock (trigger 1.237 / 1.548 s),
white noise 10 µm / 0.01 m/s² / 0.5 µε, accelerometer offset +0.03 m/s² and drift
+0.004 m/s² per second.
"""
from pathlib import Path

from vbikit.field.synthetic import write_synthetic_case

if __name__ == "__main__":
    truth = write_synthetic_case(Path(__file__).resolve().parent)
    print(truth)
