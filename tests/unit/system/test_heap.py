"""settle(): the objects alive at start-up are left out of later collections."""

from __future__ import annotations

import gc
import weakref
from collections.abc import Iterator

import pytest

from aiobt.system.heap import settle


class Node:
    def __init__(self) -> None:
        self.me: Node | None = None


@pytest.fixture
def unfrozen() -> Iterator[None]:
    gc.unfreeze()
    yield
    gc.unfreeze()  # the test process's heap as it was: collected as usual


@pytest.mark.usefixtures("unfrozen")
def test_settle_freezes_what_lives_and_collects_what_does_not() -> None:
    kept = [Node() for _ in range(10)]
    cycle = Node()
    cycle.me = cycle  # only a collection frees it
    gone = weakref.ref(cycle)
    del cycle
    before = gc.get_freeze_count()
    settle()
    assert gone() is None  # collected first, not frozen with the rest
    assert gc.get_freeze_count() >= before + len(kept)
    seen = {id(o) for o in gc.get_objects()}  # what later collections walk
    assert id(kept) not in seen
    assert not any(id(node) in seen for node in kept)
