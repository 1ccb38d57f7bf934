"""``vbikit._kept.Kept``: made once per key, the least recently used key dropped first; ``kept_for``: an
object's own stores."""
import pytest

from vbikit._kept import Kept


def test_a_value_is_made_once_and_the_least_recently_used_goes_first():
    made = []

    def maker(key):
        def make():
            made.append(key)
            return key * 10
        return make

    kept = Kept(2)
    assert kept.get(1, maker(1)) == 10 and kept.get(2, maker(2)) == 20
    assert kept.get(1, maker(1)) == 10  # kept: not made again, and now the most recent
    kept.get(3, maker(3))  # 2 is the least recently used: it goes
    assert made == [1, 2, 3] and len(kept) == 2
    assert 2 not in kept and 1 in kept and 3 in kept
    assert kept.peek(2) is None and kept.peek(1) == 10
    assert [k for k, _ in kept.items()] == [1, 3]
    kept.get(2, maker(2))  # made again; 1 (peek does not refresh it) goes
    assert made == [1, 2, 3, 2] and [k for k, _ in kept.items()] == [3, 2]


def test_a_failed_make_keeps_nothing_and_the_size_is_checked():
    kept = Kept(1)
    with pytest.raises(RuntimeError):
        kept.get("a", lambda: (_ for _ in ()).throw(RuntimeError("no")))
    assert len(kept) == 0
    with pytest.raises(ValueError, match="size: at least 1, got 0"):
        Kept(0)


class Owner:
    """Stands for an immutable model object (a bridge)."""


def test_an_owners_stores_are_its_own_go_with_it_and_are_not_pickled():
    """The stores live on the owner: another owner or name has its own; a pickle or a deep copy
    carries them empty; and the owner is collected with them even when a kept value refers back to
    it (a deck's load effect holds the deck: with the stores in a module-level table, the deck and
    everything kept for it stayed alive for good)."""
    import copy
    import gc
    import pickle
    import weakref

    from vbikit._kept import kept_for

    a, b = Owner(), Owner()
    assert kept_for(a, "x", 2).get(1, lambda: "a1") == "a1"
    assert kept_for(a, "x", 2).get(1, lambda: "other") == "a1"  # the same store again
    assert kept_for(b, "x", 2).get(1, lambda: "b1") == "b1"  # another owner: its own store
    assert kept_for(a, "y", 2).get(1, lambda: "ay") == "ay"  # another name: its own store
    for twin in (pickle.loads(pickle.dumps(a)), copy.deepcopy(a)):
        assert kept_for(twin, "x", 2).get(1, lambda: "made again") == "made again"  # empty stores
        assert kept_for(twin, "x", 2).size == 2
    assert len(pickle.dumps(a)) < 300  # (no values in the pickle)
    kept_for(a, "x", 2).get(2, lambda: [a])  # a value that refers back to its owner: a cycle
    gone = weakref.ref(a)
    del a
    gc.collect()
    assert gone() is None


def test_a_deck_with_load_effects_is_freed():
    """The case the module-level table leaked: a slab-on-girder deck whose load effect was asked for
    (the effect's influence holds the deck) is collected once dropped."""
    import gc
    import weakref

    from vbikit.bridge import SlabOnGirderBridge

    def made_and_dropped() -> weakref.ref:
        deck = SlabOnGirderBridge(span=9.0, n_girders=3, n_modes=3, n_elements=6, use_cache=False)
        deck.load_effect("moment", 4.5, girder=1)
        return weakref.ref(deck)

    refs = [made_and_dropped() for _ in range(2)]
    gc.collect()
    assert [r() for r in refs] == [None, None]


def test_an_owner_without_a_dict_gets_its_values_made_every_time():
    """An owner with no ``__dict__`` to carry stores (``__slots__``; an influence function of a type
    like that): nothing is kept for it, and asking is no error."""
    from vbikit._kept import kept_for

    class Slotted:
        __slots__ = ("value",)

    made, owner = [], Slotted()
    for _ in range(2):
        assert kept_for(owner, "x", 2).get(1, lambda: made.append(1) or "v") == "v"
    assert made == [1, 1]


def test_threads_sharing_a_store_keep_one_value_a_key():
    """Threads asking one store for the same keys at once all get the value kept (the first made),
    and the store stays within its size (its bookkeeping under a lock)."""
    import threading
    import time

    kept: Kept = Kept(3)
    got: list = []

    def ask(n: int) -> None:
        for k in range(6):
            got.append((k, kept.get(k % 4, lambda: (time.sleep(0.001), object())[1])))

    threads = [threading.Thread(target=ask, args=(n,)) for n in range(4)]
    [t.start() for t in threads]
    [t.join() for t in threads]
    assert len(kept) == 3 and len(got) == 24
    last = {k % 4: v for k, v in got[-4:]}
    for key, value in kept.items():
        assert value is kept.peek(key)
    assert all(kept.peek(k) is v for k, v in last.items() if k in kept)


def test_a_bound_method_owner_gets_no_shared_store():
    """A bound method's ``__dict__`` is its function's: stores there would be shared by every instance
    (one bridge's values served for another's method). Nothing is kept for it."""
    from vbikit._kept import kept_for

    class Influence:
        def __init__(self, k):
            self.k = k

        def __call__(self, x):
            return self.k * x

        def at(self, x):
            return self.k * x

    a, b = Influence(1.0), Influence(2.0)
    assert kept_for(a.at, "v", 2).get("key", lambda: "a's") == "a's"
    assert kept_for(b.at, "v", 2).get("key", lambda: "b's") == "b's"
