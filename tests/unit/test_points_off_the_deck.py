"""A response read at a point off the deck is refused, not returned as zeros: the mode shapes are zero off the span,
so ``CrossingResult.displacement(40.0)`` on a 25 m beam and ``to_xarray(points=[(40.0, 0.0)])`` gave all-zero
histories without a word (a new user's trial), while ``vbikit.analysis.point_response`` refused the same point.
One check (``vbikit.solve.result.check_on_deck``) serves them all."""
from __future__ import annotations

import math

import pytest

from vbikit.analysis.response import point_response
from vbikit.bridge import EulerBernoulliBeam
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import hs20_44


@pytest.fixture(scope="module")
def result():
    beam = EulerBernoulliBeam(span=25.0, EI=8.323e9, mass_per_length=2303.0, n_modes=5)
    return simulate(Crossing(beam, hs20_44(), speed=20.0))


@pytest.mark.parametrize("x, y", [(40.0, 0.0), (-5.0, 0.0), (12.5, math.nan), (math.inf, 0.0)])
def test_every_reader_refuses_a_point_off_the_deck(result, x, y):
    message = r"response\.x must be within the span 0 … 25\.0 m and response\.y finite"
    for read in (lambda: result.displacement(x, y), lambda: result.acceleration(x, y), lambda: result.strain(x, y),
                 lambda: result.to_xarray(points=[(x, y)]), lambda: point_response(result, x=x, y=y)):
        with pytest.raises(ValueError, match=message):
            read()


def test_the_ends_and_midspan_are_on_the_deck(result):
    """The span's ends are on it (0 and L, where a simply supported beam's displacement is 0 by its shapes, not
    by the check); midspan deflects downward (z up)."""
    assert result.displacement(0.0, 0.0).max() == pytest.approx(0.0, abs=1e-15)
    assert result.displacement(25.0, 0.0).max() == pytest.approx(0.0, abs=1e-12)
    assert result.displacement(12.5, 0.0).min() < 0.0
    assert float(result.to_xarray(points=[(12.5, 0.0)])["displacement"].min()) < 0.0
