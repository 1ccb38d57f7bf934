"""Random vibration without sampling: mean and standard deviation histories of a crossing's
responses on a Gaussian random road by the pseudo-excitation method (``pem``), and the peak
and impact-factor distributions that follow from them (``peaks``)."""
from __future__ import annotations

from vbikit.random.lines import Lines, band_lines, default_lines
from vbikit.random.pem import NonlinearTireError, PEMResult, Probes, PseudoRoad, pseudo_excitation

__all__ = ["Lines", "band_lines", "default_lines", "NonlinearTireError", "PEMResult", "Probes", "PseudoRoad", "pseudo_excitation"]
