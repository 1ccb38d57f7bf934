"""`vbikit compile` (and the test run's shared warm-up) also compile the static modal history of a
run's impact factor, the exact static peaks' sweep and the decoupled drive-by recursions
(``compile_history_kernels``, ``compile_driveby_kernels``): their tiny calls have the argument types
of real runs, so a real run afterwards adds no second compiled variant of any of these kernels
(a float passed as an int, or a non-contiguous array, would add one)."""
from __future__ import annotations


from vbikit.analysis.breakpoints import _sweep
from vbikit.analysis import impact
from vbikit.analysis.warmup import compile_history_kernels
from vbikit.bridge import EulerBernoulliBeam
from vbikit.bridge.presets import BRIDGE_PRESETS
from vbikit.driveby import sensor_cart
from vbikit.driveby._decoupled_kernels import diagonal_recursion
from vbikit.driveby.decoupled import simulate_decoupled
from vbikit.driveby.warmup import compile_driveby_kernels
from vbikit.lifetime.influence import HALF_TRACK, Tabulated, effect_line, event_static
from vbikit.solve import Crossing, simulate
from vbikit.solve.kernels.assembly import static_modal_history
from vbikit.solve.kernels.run_in import linear_recursion
from vbikit.traffic.records import VehicleRecord
from vbikit.vehicle import hs20_44


def test_a_beam_run_and_a_lifetime_event_use_the_warmed_variants():
    compile_history_kernels()
    warmed = (set(static_modal_history.signatures), set(_sweep.signatures))
    assert all(warmed)
    beam = EulerBernoulliBeam(span=16.76, EI=1.0e10, mass_per_length=7500.0, n_modes=4)
    impact.static_modal_history(simulate(Crossing(beam, hs20_44(), speed=20.0, approach=1.0, free_vibration=0.0,
                                                  dt=4e-3)))  # as a run's impact factor takes it
    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    line = effect_line(deck, deck.load_effect("moment", x=5.3))
    tab = Tabulated(line, deck, [-HALF_TRACK, HALF_TRACK], 0.02)
    recs = [VehicleRecord(0.123, "-x", 19.3, (100e3, 50e3), (4.0,), lane=1)]
    event_static(recs, [(0,)], [line], deck.span, (0.0, 0.0), tables=[tab], keep_histories=True)
    assert (set(static_modal_history.signatures), set(_sweep.signatures)) == warmed


def test_a_decoupled_pass_uses_the_warmed_variants():
    compile_driveby_kernels()
    warmed = (set(diagonal_recursion.signatures), set(linear_recursion.signatures))  # (the step-by-step fallback's)
    assert all(warmed)
    beam = EulerBernoulliBeam(span=25.0, EI=2.4e10, mass_per_length=4800.0, damping_ratio=0.02, n_modes=4)
    simulate_decoupled(Crossing(beam, sensor_cart(mass=500.0, frequency_hz=2.3, damping_ratio=0.1), speed=12.0,
                                approach=2.0))
    assert (set(diagonal_recursion.signatures), set(linear_recursion.signatures)) == warmed
