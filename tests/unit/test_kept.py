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
    import gc
    import pickle

    from vbikit._kept import _PER_OWNER, kept_for

    a, b = Owner(), Owner()
    assert kept_for(a, "x", 2).get(1, lambda: "a1") == "a1"
    assert kept_for(a, "x", 2).get(1, lambda: "other") == "a1"  # the same store again
    assert kept_for(b, "x", 2).get(1, lambda: "b1") == "b1"  # another owner: its own store
    assert kept_for(a, "y", 2).get(1, lambda: "ay") == "ay"  # another name: its own store
    assert vars(pickle.loads(pickle.dumps(a))) == {}  # nothing on the object itself
    n = len(_PER_OWNER)
    del a
    gc.collect()
    assert len(_PER_OWNER) == n - 2  # both of a's stores went with it


def test_an_owner_without_weak_references_gets_its_values_made_every_time():
    """A numpy ufunc (an influence function given as ``np.sin``) cannot be referenced weakly: nothing
    is kept for it (its id could be another object's later), and asking is no error."""
    import numpy as np

    from vbikit._kept import _PER_OWNER, kept_for

    n, made = len(_PER_OWNER), []
    for _ in range(2):
        assert kept_for(np.sin, "x", 2).get(1, lambda: made.append(1) or "v") == "v"
    assert made == [1, 1] and len(_PER_OWNER) == n
