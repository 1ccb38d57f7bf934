"""``Kept``: values made once per key and kept for the last keys used (bridges, roads and step maps
that runs in one process ask for again)."""
from __future__ import annotations

import weakref
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterator
from typing import Generic, TypeVar

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class Kept(Generic[K, V]):
    """A bounded store: ``get(key, make)`` returns the value kept under ``key``, made by ``make()``
    the first time; at most ``size`` values stay, the least recently used going first.  Kept values
    are shared by every later caller, so nothing may change them."""

    def __init__(self, size: int) -> None:
        if size < 1:
            raise ValueError(f"size: at least 1, got {size}")
        self.size = size
        self._items: OrderedDict[K, V] = OrderedDict()

    def get(self, key: K, make: Callable[[], V]) -> V:
        """The value under ``key``; made by ``make()`` (and kept) when there is none."""
        if key in self._items:
            self._items.move_to_end(key)
            return self._items[key]
        value = make()
        self._items[key] = value
        if len(self._items) > self.size:
            self._items.popitem(last=False)
        return value

    def peek(self, key: K) -> V | None:
        """The value under ``key`` if kept, else None (nothing made, the order unchanged)."""
        return self._items.get(key)

    def items(self) -> Iterator[tuple[K, V]]:
        """The kept (key, value) pairs, least recently used first."""
        return iter(list(self._items.items()))

    def __len__(self) -> int:
        return len(self._items)

    def __contains__(self, key: object) -> bool:
        return key in self._items


#: (id(owner), name) -> the owner's store (``kept_for``); an entry goes when its owner is collected
_PER_OWNER: dict[tuple[int, str], Kept] = {}


def kept_for(owner: object, name: str, size: int) -> Kept:
    """The bounded store ``name`` (at most ``size`` values) of the immutable object ``owner`` (a
    bridge, ...): by identity, dropped when ``owner`` is collected, and not on the object, so that
    pickling it (for a worker process) carries none of it.  An owner that cannot be referenced weakly
    (a numpy ufunc given as an influence function, ...) gets a new empty store each time: its values
    are made on every call, not kept (its identity could outlive it)."""
    key = (id(owner), name)
    store = _PER_OWNER.get(key)
    if store is None:
        try:
            weakref.finalize(owner, _PER_OWNER.pop, key, None)
        except TypeError:
            return Kept(size)
        store = _PER_OWNER[key] = Kept(size)
    return store


def forget_kept() -> None:
    """Drop every ``kept_for`` store (tests that need fresh values)."""
    _PER_OWNER.clear()
