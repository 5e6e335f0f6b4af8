"""A loaded tree: its root, its blackboards, and the ways to tick it.

``tick_exactly_once`` ticks the root once; ``tick_once`` also re-ticks while
the root is RUNNING and a wake-up is pending (BT.CPP's
``tickOnce``); ``tick_while_running`` ticks at a period until the root
finishes, waking early whenever a leaf finishes or a watched value changes.
Pausing, resuming and halting carry a reason, kept in :attr:`Tree.events`.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import Clock
from aiobt.core.node import StatusListener, TreeContext, TreeNode
from aiobt.core.status import FAILURE, IDLE, RUNNING, SUCCESS, Status

log = logging.getLogger("aiobt.core.tree")


class WakeUp:
    """BT.CPP's wake-up signal: a flag consumed by the ticking loop."""

    __slots__ = ("_event", "_pending")

    def __init__(self) -> None:
        self._pending = False
        self._event: asyncio.Event | None = None

    def emit(self) -> None:
        self._pending = True
        if self._event is not None:
            self._event.set()

    def consume(self) -> bool:
        pending, self._pending = self._pending, False
        if self._event is not None:
            self._event.clear()
        return pending

    async def wait(self, clock: Clock, period: float) -> bool:
        """Wait up to ``period`` of clock time; True if woken up."""
        if self.consume():
            return True
        if self._event is None:
            self._event = asyncio.Event()
        waiter = asyncio.ensure_future(self._event.wait())
        # the deadline is fixed now: the sleeper task first runs a few loop turns later
        sleeper = asyncio.ensure_future(_sleep_until(clock, clock.now() + period))
        try:
            await asyncio.wait({waiter, sleeper}, return_when=asyncio.FIRST_COMPLETED)
        finally:
            waiter.cancel()
            sleeper.cancel()
        return self.consume()


async def _sleep_until(clock: Clock, deadline: float) -> None:
    await clock.sleep(deadline - clock.now())


@dataclass(frozen=True, slots=True)
class TreeEvent:
    """A pause, resume or halt, with the clock time and the reason given."""

    stamp: float
    kind: str
    reason: str


class Tree:
    """An instantiated behavior tree."""

    def __init__(
        self,
        root: TreeNode,
        context: TreeContext,
        blackboard: Blackboard,
        *,
        tree_id: str = "",
        source: str = "",
    ) -> None:
        self.root = root
        self.context = context
        self.root_blackboard = blackboard
        self.tree_id = tree_id
        self.source = source
        self.events: list[TreeEvent] = []
        self._wake = WakeUp()
        self._resumed = asyncio.Event()
        self._resumed.set()
        context.wake_up = self._wake.emit
        for node in self.nodes():
            node.on_tree_built()

    @property
    def clock(self) -> Clock:
        return self.context.clock

    @property
    def status(self) -> Status:
        return self.root.status

    def nodes(self) -> Iterator[TreeNode]:
        """Every node, depth first, in the order of their uids."""
        stack = [self.root]
        while stack:
            node = stack.pop()
            yield node
            stack.extend(reversed(node.children_nodes()))

    def find(self, name: str) -> TreeNode:
        """The first node whose name or path is ``name``."""
        for node in self.nodes():
            if name in (node.name, node.path):
                return node
        raise KeyError(f"tree {self.tree_id!r} has no node named {name!r}")

    def add_status_listener(self, listener: StatusListener) -> Callable[[], None]:
        """Call ``listener(stamp, node, previous, status)`` on every change."""
        self.context.listeners.append(listener)
        return lambda: self.context.listeners.remove(listener)

    def watch(self, key: str) -> Callable[[], None]:
        """Wake :meth:`tick_while_running` whenever ``key`` (root blackboard) is written.

        Returns a function that stops watching.
        """
        return self.root_blackboard.watch(key, self._wake.emit)

    def emit_wake_up(self) -> None:
        self._wake.emit()

    async def wait_for_wake_up(self, period: float) -> bool:
        """Wait up to ``period`` of clock time; True if a wake-up came first.

        For runners that tick with :meth:`tick_once` in their own loop (the
        navigator does work between ticks), as :meth:`tick_while_running` waits.
        """
        return await self._wake.wait(self.context.clock, period)

    # -- ticking ------------------------------------------------------------------
    async def _tick_root(self) -> Status:
        status = self.root.tick_sync()
        if self.context.cleanups:  # async leaves halted during the tick
            await self.context.settle()
        return status

    def _finish(self, status: Status) -> Status:
        if status is SUCCESS or status is FAILURE:
            self.root.reset_status()
        return status

    async def tick_exactly_once(self) -> Status:
        """Tick the root once (a wake-up it emits stays pending, as in BT.CPP)."""
        # _tick_root and _finish inlined: one coroutine per tree tick, not two
        root = self.root
        status = root.tick_sync()
        if self.context.cleanups:  # async leaves halted during the tick
            await self.context.settle()
        if status is SUCCESS or status is FAILURE:
            root.reset_status()
        return status

    async def tick_once(self) -> Status:
        """Tick, then tick again while RUNNING and a wake-up is pending.

        As in BT.CPP, a wake-up left pending by an earlier tick_exactly_once
        counts too.
        """
        status = await self._tick_root()
        while status is RUNNING and self._wake.consume():
            status = await self._tick_root()
        return self._finish(status)

    async def tick_while_running(self, period: float = 0.01) -> Status:
        """Tick every ``period`` seconds of clock time until the root finishes."""
        status = IDLE
        while status is IDLE or status is RUNNING:
            await self._resumed.wait()
            status = await self.tick_once()
            if status is RUNNING:
                await self._wake.wait(self.context.clock, period)
        return status

    # -- control ------------------------------------------------------------------
    def _record(self, kind: str, reason: str) -> None:
        self.events.append(TreeEvent(self.context.clock.now(), kind, reason))
        log.info("tree %s %s: %s", self.tree_id or "<tree>", kind, reason or "no reason given")

    def pause(self, reason: str = "") -> None:
        """Stop ticking (running leaves go on) until :meth:`resume`."""
        self._resumed.clear()
        self._record("paused", reason)

    def resume(self, reason: str = "") -> None:
        self._resumed.set()
        self._wake.emit()
        self._record("resumed", reason)

    @property
    def paused(self) -> bool:
        return not self._resumed.is_set()

    async def halt_tree(self, reason: str = "") -> None:
        """Halt the root, then every node (BT.CPP's haltTree)."""
        self._record("halted", reason)
        self.root.halt_sync()
        for node in list(self.nodes()):
            node.halt_sync()
        self.root.reset_status()
        await self.context.settle()
