"""Following the navigator's tree from outside, on its status stream ``{ns}/bt/...``.

:class:`TreeWatch` keeps the latest tree structure (``bt/tree``, latched) and
every transition of it (``bt/transitions``) as :class:`Event` records: the node's
ID and name, the new status, the sim-time stamp and the wall time of arrival
(``time.monotonic``), so a test can ask "did ComputePathToPose fail within 1.5 s
of the kill?" or "in which order did the recovery actions start?".
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import Callable
from dataclasses import dataclass

from aiobt.msgs import BtTransitions, BtTree
from aiobt.testing.navwatch import wait_until
from aiobt.transport import Bus


@dataclass(frozen=True, slots=True)
class Event:
    run: int
    node_id: str
    name: str
    previous: str
    status: str
    stamp: float
    wall: float


class TreeWatch:
    """Transitions of every tree the navigator runs, named after their nodes."""

    def __init__(self, bus: Bus) -> None:
        self.events: list[Event] = []
        self._names: dict[int, dict[int, tuple[str, str]]] = {}  # run -> uid -> (id, name)
        self._early: list[BtTransitions] = []  # transitions seen before their structure
        self._changed = asyncio.Event()
        self._tree_sub = bus.subscribe("bt/tree", BtTree, self._on_tree, latched=True)
        self._transitions_sub = bus.subscribe("bt/transitions", BtTransitions, self._on_transitions)

    def _on_tree(self, tree: BtTree) -> None:
        self._names[tree.run] = {node.uid: (node.id, node.name) for node in tree.nodes}
        early, self._early = self._early, []
        for batch in early:
            self._on_transitions(batch)

    def _on_transitions(self, batch: BtTransitions) -> None:
        names = self._names.get(batch.run)
        if names is None:
            self._early.append(batch)
            return
        wall = time.monotonic()
        for change in batch.transitions:
            node_id, name = names.get(change.uid, ("?", "?"))
            self.events.append(
                Event(batch.run, node_id, name, change.previous, change.status, change.stamp, wall)
            )
        self._changed.set()

    def find(
        self, node: str, status: str, after: float = 0.0, run: int | None = None
    ) -> Event | None:
        """The first event of ``node`` (ID or name) to ``status`` arriving after wall time
        ``after`` (and in tree instance ``run`` if given)."""
        for event in self.events:
            if (
                node in (event.node_id, event.name)
                and event.status == status
                and event.wall > after
                and run in (None, event.run)
            ):
                return event
        return None

    def activations(self, names: tuple[str, ...], after: float = 0.0) -> list[str]:
        """Which of ``names`` (IDs or names) started after wall time ``after``, in order: one
        entry per activation (a transition out of IDLE)."""
        return [
            event.name
            for event in self.events
            if event.wall > after
            and names_match(event, names)
            and event.previous == "IDLE"
            and event.status != "IDLE"
        ]

    async def wait_for(self, predicate: Callable[[], object], timeout: float) -> bool:  # noqa: ASYNC109
        """True once ``predicate()`` is truthy (checked on every transition batch)."""
        return await wait_until(self._changed, predicate, timeout)

    def close(self) -> None:
        self._transitions_sub.close()
        self._tree_sub.close()


def names_match(event: Event, names: tuple[str, ...]) -> bool:
    return event.name in names or event.node_id in names
