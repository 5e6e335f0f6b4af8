"""The status-change observer API, on top of ``Tree.add_status_listener``.

An observer costs nothing until attached (the tree's listener list is empty)
and one call per status change once attached. Subclass
:class:`StatusObserver` and implement :meth:`StatusObserver.on_transition`,
or collect :class:`Transition` records with :class:`TransitionRecorder`::

    with TransitionRecorder(tree) as recorder:
        await tree.tick_while_running()
    print(recorder.transitions)
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod
from dataclasses import dataclass
from types import TracebackType
from typing import Self

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree


@dataclass(frozen=True, slots=True)
class Transition:
    """One status change: clock time, node uid and path, previous and new status."""

    stamp: float
    uid: int
    path: str
    previous: Status
    status: Status


class StatusObserver(ABC):
    """Base of every logger: attached on construction, detached by :meth:`close`.

    It is also a context manager (``with Logger(tree) as log: ...``).
    ``epoch_us`` and ``clock_start`` pair the tree's clock with wall time at
    attach, so file loggers can write absolute time stamps like BT.CPP.
    """

    def __init__(self, tree: Tree) -> None:
        self.tree = tree
        self.clock_start = tree.clock.now()
        self.epoch_us = time.time_ns() // 1000
        self._detach = tree.add_status_listener(self.on_transition)
        self._attached = True

    @abstractmethod
    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        """One status change of one node (the tree's listener signature)."""

    def offset_us(self, stamp: float) -> int:
        """Microseconds of tree-clock time since this observer was attached."""
        return max(0, round((stamp - self.clock_start) * 1e6))

    def flush(self) -> None:  # noqa: B027 - a default that does nothing, on purpose
        """Write out what is buffered (loggers that buffer override this)."""

    def close(self) -> None:
        """Detach from the tree and flush; safe to call twice."""
        if self._attached:
            self._attached = False
            self._detach()
        self.flush()

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()


class TransitionRecorder(StatusObserver):
    """Keeps every transition in memory (tests, debugging, the CLI)."""

    def __init__(self, tree: Tree) -> None:
        self.transitions: list[Transition] = []
        super().__init__(tree)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        self.transitions.append(Transition(stamp, node.uid, node.path, previous, status))
