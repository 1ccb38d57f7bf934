"""Drive-by (indirect) bridge monitoring: instrumented vehicles, contact-point response,
identification of bridge frequencies, mode shapes and damage, and labelled datasets.

Modules: ``sensors`` (sensors, sampling, anti-alias filter, noise), ``contact`` (contact-point
response, back-calculated and true), ``identify`` (spectra, frequency identification, roughness
cancellation, mode-shape squares, damage indicators), ``vehicles`` (test vehicles), ``spec``
(the DRIVEBY.toml file), ``study`` (the sweep as a resumable job of the study runner),
``figures`` and ``report``.
"""
from vbikit.driveby.contact import (SingleAxle, contact_acceleration, contact_acceleration_from_measured,
                                    contact_point_response, on_bridge, true_contact_response)
from vbikit.driveby.identify import (Identification, Spectrum, bandpass, frequency_labels, frequency_shift,
                                     identify_frequency, mode_shape_squares, residual_response, shape_change, spectrum)
from vbikit.driveby.sensors import Measurement, Sampling, Sensor, SensorError, measure, sensor_row
from vbikit.driveby.vehicles import DRIVEBY_VEHICLES, driveby_vehicle, sensor_cart, two_axle_car

__all__ = [
    "SingleAxle", "contact_acceleration", "contact_acceleration_from_measured", "contact_point_response", "on_bridge",
    "true_contact_response", "Identification", "Spectrum", "bandpass", "frequency_labels", "frequency_shift",
    "identify_frequency", "mode_shape_squares", "residual_response", "shape_change", "spectrum", "Measurement",
    "Sampling", "Sensor", "SensorError", "measure", "sensor_row", "DRIVEBY_VEHICLES", "driveby_vehicle", "sensor_cart",
    "two_axle_car",
]
