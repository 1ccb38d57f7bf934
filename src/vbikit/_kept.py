"""``Kept``: values made once per key and kept for the last keys used (bridges, roads and step maps
that runs in one process ask for again)."""
from __future__ import annotations

import threading
import types
import weakref
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterator
from typing import Generic, TypeVar

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class Kept(Generic[K, V]):
    """A bounded store: ``get(key, make)`` returns the value kept under ``key``, made by ``make()``
    the first time; at most ``size`` values stay, the least recently used going first.  Kept values
    are shared by every later caller, so nothing may change them.

    Threads may share a store (``BatchSolver.run_many(threads=…)``): its bookkeeping runs under a
    lock, ``make`` outside it (a value two threads make at once is kept once, the first one
    finished, and both get that one).  A copy or a pickle of a store is an empty store of the same
    size: an object carrying stores (``kept_for``) ships to a worker process without their values."""

    def __init__(self, size: int) -> None:
        if size < 1:
            raise ValueError(f"size: at least 1, got {size}")
        self.size = size
        self._items: OrderedDict[K, V] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: K, make: Callable[[], V]) -> V:
        """The value under ``key``; made by ``make()`` (and kept) when there is none."""
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
        value = make()  # (outside the lock: ``make`` may itself ask this store for other keys)
        with self._lock:
            if key in self._items:  # made meanwhile by another thread: keep the first
                self._items.move_to_end(key)
                return self._items[key]
            self._items[key] = value
            if len(self._items) > self.size:
                self._items.popitem(last=False)
        return value

    def peek(self, key: K) -> V | None:
        """The value under ``key`` if kept, else None (nothing made, the order unchanged)."""
        with self._lock:
            return self._items.get(key)

    def items(self) -> Iterator[tuple[K, V]]:
        """The kept (key, value) pairs, least recently used first."""
        with self._lock:
            return iter(list(self._items.items()))

    def __reduce__(self) -> tuple:
        return (Kept, (self.size,))  # an empty store: the values stay in this process

    def __copy__(self) -> "Kept[K, V]":
        return Kept(self.size)

    def __deepcopy__(self, memo: dict) -> "Kept[K, V]":
        return Kept(self.size)

    def __len__(self) -> int:
        return len(self._items)

    def __contains__(self, key: object) -> bool:
        return key in self._items


#: the attribute under which an owner carries its stores (``kept_for``)
STORES = "_kept_stores"
#: the owners that carry stores, by weak reference (``forget_kept``; a reference keeps none alive)
_OWNERS: "weakref.WeakSet[object]" = weakref.WeakSet()


def kept_for(owner: object, name: str, size: int) -> Kept:
    """The bounded store ``name`` (at most ``size`` values) of the immutable object ``owner`` (a
    bridge, ...), carried by the owner itself (in its ``__dict__``, beside its cached properties): it
    goes when the owner goes, even when its values refer back to the owner (a deck's load effects
    hold the deck: a cycle the garbage collector frees), and a pickle or copy of the owner carries
    empty stores (``Kept.__reduce__``: a worker rebuilds its own).  An owner without a ``__dict__`` of
    its own (``__slots__``; a bound method, whose ``__dict__`` is its function's, shared by every
    instance) gets a new empty store each time: its values are made on every call, not kept."""
    if isinstance(owner, types.MethodType):  # (its ``__dict__`` is its function's, shared by every instance)
        return Kept(size)
    try:
        stores = vars(owner)
    except TypeError:
        return Kept(size)
    per_name = stores.get(STORES)
    if per_name is None:
        per_name = stores.setdefault(STORES, {})  # (setdefault: one dict even if threads race here)
        try:
            _OWNERS.add(owner)
        except TypeError:  # (no weak references: ``forget_kept`` does not reach its stores)
            pass
    store = per_name.get(name)
    if store is None:
        store = per_name.setdefault(name, Kept(size))
    return store


def forget_kept() -> None:
    """Empty every ``kept_for`` store of every living owner (tests that need fresh values)."""
    for owner in list(_OWNERS):
        vars(owner).pop(STORES, None)
