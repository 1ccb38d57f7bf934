"""Monte Carlo on the engine: the same crossing on many sampled roads (the reference the
pseudo-excitation method is checked against, and the study's ``method = "monte-carlo"``)."""
from __future__ import annotations

from typing import Callable, Sequence, TypeVar

from vbikit.road.profile import RoadProfile
from vbikit.road.psd import correlated_profile, random_profile
from vbikit.random.pem import PseudoRoad
from vbikit.solve.batch import BatchSolver
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.simulate import MAX_LANES

T = TypeVar("T")


def sampled_roads(road: PseudoRoad, seed: int, spacing: float = 0.01,
                  length: float = 1000.0) -> tuple[RoadProfile, RoadProfile | None]:
    """The (left, right) profiles of ``seed`` exactly as a scenario builds them (paper Eq. 7; the
    right line by ``correlated_profile`` when the lines are not identical)."""
    left = random_profile(road.psd, seed, spacing=spacing, length=length)
    if not road.two_lines or road.coherence >= 1.0:
        return left, None
    return left, correlated_profile(left, road.psd, seed, road.coherence, spacing=spacing, length=length)


def monte_carlo(crossing: Crossing, road: PseudoRoad, seeds: Sequence[int], reduce: Callable[[CrossingResult], T],
                spacing: float = 0.01, length: float = 1000.0) -> list[T]:
    """``reduce`` of the crossing on the sampled road of every seed (the engine's batched lanes)."""
    solver = BatchSolver(crossing)
    out: list[T] = []
    for k in range(0, len(seeds), MAX_LANES):  # roads of one kernel call at a time (each ≈ 1 MB)
        out += solver.run_many([sampled_roads(road, s, spacing, length) for s in seeds[k:k + MAX_LANES]], reduce=reduce)
    return out
