"""The blackboard: typed entries shared by the nodes of a tree.

Follows BT.CPP v4: every SubTree gets its own blackboard whose parent is the
caller's; a key reaches the parent only through an explicit remapping or, with
``_autoremap``, by the same name unless it is private (``_key``); ``@key``
always means the root blackboard. Each entry remembers its type, a sequence id
that grows with every write, and the time of the last write.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any

from aiobt.core.convert import convert, is_convertible, type_name
from aiobt.core.errors import BlackboardError


@dataclass(slots=True)
class Entry:
    """One blackboard value. ``type`` None means any type is allowed."""

    value: Any = None
    type: Any = None
    sequence_id: int = 0
    stamp: float = 0.0
    has_value: bool = False
    watchers: list[Callable[[], None]] | None = None


def _is_private(key: str) -> bool:
    return key.startswith("_")


_NUMBERS = (int, float)


@dataclass(slots=True, eq=False)
class Blackboard:
    """A scope of entries, optionally child of another scope."""

    parent: Blackboard | None = None
    autoremap: bool = False
    remapping: dict[str, str] = field(default_factory=dict)
    now: Callable[[], float] = time.monotonic
    _storage: dict[str, Entry] = field(default_factory=dict)

    @classmethod
    def create(cls, parent: Blackboard | None = None, *, autoremap: bool = False) -> Blackboard:
        now = parent.now if parent is not None else time.monotonic
        return cls(parent=parent, autoremap=autoremap, now=now)

    def root(self) -> Blackboard:
        bb = self
        while bb.parent is not None:
            bb = bb.parent
        return bb

    def add_remapping(self, internal: str, external: str) -> None:
        """Make ``internal`` here the same entry as ``external`` in the parent."""
        self.remapping[internal] = external

    # -- lookup ---------------------------------------------------------------
    def entry(self, key: str) -> Entry | None:
        """The entry for ``key``, following remapping, or None."""
        if key.startswith("@"):
            return self.root().entry(key[1:])
        found = self._storage.get(key)
        if found is not None:
            return found
        if self.parent is not None:
            external = self.remapping.get(key)
            if external is not None:
                return self.parent.entry(external)
            if self.autoremap and not _is_private(key):
                return self.parent.entry(key)
        return None

    def create_entry(self, key: str, tp: Any = None) -> Entry:
        """Get or create the entry for ``key``; creation follows remapping."""
        if key.startswith("@"):
            return self.root().create_entry(key[1:], tp)
        found = self._storage.get(key)
        if found is not None:
            return found
        external = self.remapping.get(key)
        if self.parent is not None and external is not None:
            entry = self.parent.create_entry(external, tp)
        elif self.parent is not None and self.autoremap and not _is_private(key):
            entry = self.parent.create_entry(key, tp)
        else:
            entry = Entry(type=tp)
        self._storage[key] = entry
        return entry

    def __contains__(self, key: str) -> bool:
        entry = self.entry(key)
        return entry is not None and entry.has_value

    def get(self, key: str, default: Any = None) -> Any:
        entry = self.entry(key)
        if entry is None or not entry.has_value:
            return default
        return entry.value

    def __getitem__(self, key: str) -> Any:
        entry = self.entry(key)
        if entry is None or not entry.has_value:
            raise BlackboardError(f"blackboard has no entry [{key}]")
        return entry.value

    def __setitem__(self, key: str, value: Any) -> None:
        self.set(key, value)

    # -- writes ---------------------------------------------------------------
    def set(self, key: str, value: Any) -> None:
        """Write ``value``; once an entry has a type, its type does not change.

        Strings are converted to the entry's type; ints may go where floats
        are; anything else of another type is an error naming both types.
        """
        entry = self.entry(key)
        if entry is None:
            entry = self.create_entry(key, None if isinstance(value, str) else type(value))
        elif entry.type is None and entry.has_value is False and not isinstance(value, str):
            entry.type = type(value)
        else:
            value = _coerce(key, entry, value)
        entry.value = value
        entry.has_value = True
        entry.sequence_id += 1
        entry.stamp = self.now()
        if entry.watchers:
            for watcher in entry.watchers:
                watcher()

    def watch(self, key: str, callback: Callable[[], None]) -> Callable[[], None]:
        """Call ``callback()`` after every write of ``key``; returns the undo."""
        entry = self.create_entry(key)
        if entry.watchers is None:
            entry.watchers = []
        entry.watchers.append(callback)
        watchers = entry.watchers
        return lambda: watchers.remove(callback)

    def unset(self, key: str) -> None:
        """Remove ``key`` from this scope (BT.CPP's Blackboard::unset)."""
        if key.startswith("@"):
            self.root().unset(key[1:])
            return
        removed = self._storage.pop(key, None)
        if removed is not None:  # whoever still holds it sees it is gone
            removed.has_value = False

    def keys(self) -> Iterator[str]:
        return iter(self._storage)

    def items(self) -> Iterator[tuple[str, Entry]]:
        return iter(self._storage.items())

    def snapshot(self) -> dict[str, Any]:
        """Plain values of this scope, for display and debugging."""
        return {k: e.value for k, e in self._storage.items() if e.has_value}


def _coerce(key: str, entry: Entry, value: Any) -> Any:
    tp = entry.type
    if tp is None or isinstance(value, tp if isinstance(tp, type) else object):
        return value
    if isinstance(value, str) and is_convertible(tp):
        try:
            return convert(value, tp)
        except (ValueError, TypeError) as exc:
            raise BlackboardError(
                f"blackboard [{key}]: cannot convert {value!r} to {type_name(tp)}: {exc}"
            ) from exc
    if tp is float and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if tp is int and isinstance(value, float) and value.is_integer():
        return int(value)
    raise BlackboardError(
        f"blackboard [{key}]: once declared, the type of an entry does not change; "
        f"it is {type_name(tp)}, the new value is {type_name(type(value))} ({value!r})"
    )
