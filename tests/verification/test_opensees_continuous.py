"""A two-span continuous slab-on-girder deck against the independent OpenSeesPy grillage of
``test_opensees_crosscheck.py`` with a third line of bearings at the pier.

Bridge 2's cross-section (five Type II girders, no overhang as in the cross-check) over two
16.76 m spans, girders continuous over the pier, diaphragms at both ends and over the pier
(``build_grillage`` places them at the ends and at the middle of the whole length, the pier).
Frequencies within 0.5 % (the cross-check's tolerance for lumped vs consistent girder mass);
static girder moments at the middle of span 1 and over the pier, and the pier reactions, under
HS20-44 axle loads at grid nodes, to 1e-6.

Runs when the optional ``opensees`` extra is installed.
"""
from __future__ import annotations

import numpy as np
import pytest
from test_opensees_crosscheck import build_grillage, ops, static_truck  # noqa: F401 - the ops fixture

from vbikit.bridge import paper_deck

L = 16.76


@pytest.fixture(scope="module")
def two_span(ops, tmp_path_factory):  # noqa: F811
    bridge = paper_deck(2, n_modes=8, overhang=0.0, span=2 * L, spans=(L, L), n_elements=68,
                        diaphragms=(0.0, L, 2 * L), use_cache=False)
    tag, xs, ys = build_grillage(ops, bridge, tmp_path_factory.mktemp("ops") / "ops.log")
    pier = 34
    assert xs[pier] == pytest.approx(L)
    for j in range(ys.size):
        ops.fix(tag[j, pier], 0, 0, 1, 0, 0, 0)
    return ops, bridge, tag, xs, ys, pier


def test_frequencies_of_the_continuous_deck(two_span):
    ops, bridge, tag, xs, ys, pier = two_span
    # shift-invert Lanczos ("-genBandArpack"): the dense "-fullGenLapack" takes 50× longer on this
    # model (about 20 s) and gives the same five eigenvalues to 4e-11 (measured), far inside 0.5 %
    f_ops = np.sqrt(np.array(ops.eigen("-genBandArpack", 5))) / (2 * np.pi)
    assert bridge.frequencies_hz[:5] == pytest.approx(f_ops, rel=0.005)
    assert bridge.frequencies_hz[0] > paper_deck(2, n_modes=1, overhang=0.0, use_cache=False).frequencies_hz[0] * 0.99


def test_static_girder_moments_and_pier_reactions(two_span):
    ops, bridge, tag, xs, ys, pier = two_span
    axles = [(12.5, 35.6e3), (12.5 - 4.27, 142.3e3), (12.5 - 8.54, 142.3e3)]
    pts = static_truck(ops, tag, xs, axles)
    ops.reactions()
    n_el = xs.size - 1
    px, py = np.array([xs[i] for i, _, _ in pts]), np.array([ys[j] for _, j, _ in pts])
    pf = -np.array([P for _, _, P in pts])
    mid = 17
    for g in range(1, 6):
        j = g - 1
        for i in (mid, pier):
            my = ops.eleForce(j * n_el + i + 1)[4]  # sagging moment at the element's first node
            ours = bridge.load_effect("moment", x=float(xs[i]), girder=g).influence(px, py) @ pf
            assert ours == pytest.approx(my, rel=1e-6, abs=1e-6 * abs(pf).sum())
        r = bridge.load_effect("reaction", support=1, girder=g).influence(px, py) @ pf
        assert r == pytest.approx(ops.nodeReaction(tag[j, pier], 3), rel=1e-6, abs=1e-6 * abs(pf).sum())
    # hogging over the pier on the loaded girders
    assert bridge.load_effect("moment", x=L, girder=4).influence(px, py) @ pf < 0
