# Pinned random streams.  These numbers are *not* verification against an independent source: they
# were recorded from vbikit (2026-12-01, numpy 2.x) so that any change of a random stream — the study's
# seed derivation, the phase angles of Eq. 7 or the profile synthesis — makes this test fail and is
# made on purpose (with a changelog entry: results of every study on random roads change with it).
# The profile's statistics are verified independently elsewhere (tests/unit/test_road.py).
from __future__ import annotations

import numpy as np

from vbikit.road import RoadPSD, phase_angles, random_profile
from vbikit.study import derive_seed
from vbikit.study.paper import PAPER_SEED

# derive_seed(study_seed, sample) = numpy SeedSequence([study_seed, sample]).generate_state(1, uint32)[0]
DERIVED_SEEDS = {
    (0, 0): 2968811710, (0, 1): 3964924996, (0, 2): 3141116543, (0, 19): 4088419074,
    (1, 0): 1835504127, (1, 1): 1189033389, (1, 2): 1596810411, (1, 19): 3999303432,
    (2024, 0): 3345857025, (2024, 1): 4013653742, (2024, 2): 247616251, (2024, 19): 4199784150,
}


def test_derive_seed_values_are_pinned():
    assert PAPER_SEED == 2024  # the paper studies' seeds are the (2024, i) rows
    assert {key: derive_seed(*key) for key in DERIVED_SEEDS} == DERIVED_SEEDS


def test_class_c_profile_seed_1_first_samples_are_pinned():
    """ISO 8608 class C at its geometric mean, seed 1, the defaults (Δx = 0.01 m, length 1000 m,
    band 0.01–4 cycle/m): period P = 1310.72 m from x = −P/2."""
    psd = RoadPSD.iso("C")
    n_k, theta = phase_angles(psd, 1)
    assert n_k.size == 5229
    np.testing.assert_array_equal(theta[:3], [3.2158701122134374, 5.971939531762716, 0.9057815605287021])
    road = random_profile(psd, seed=1)
    assert road.x.size == 131072 and road.x[0] == -655.36
    # FFT round-off may differ between numpy builds: 1e-12 relative, far below any change of stream
    np.testing.assert_allclose(road.z[:4], [-0.023595852216782485, -0.023641371760286495, -0.02366055293694303,
                                            -0.023652938442615165], rtol=1e-12, atol=0)
    entry = int(np.searchsorted(road.x, 0.0))
    assert road.x[entry] == 0.0
    np.testing.assert_allclose(road.z[entry:entry + 4], [-0.006178892930267802, -0.006286336740928725,
                                                         -0.0064056880865199835, -0.006537785937960838],
                               rtol=1e-12, atol=0)
