"""ReactiveSequence: re-check every child from the first on each tick."""

from __future__ import annotations

from aiobt.core.status import FAILURE, SUCCESS
from aiobt.nodes.control.ordered import ReactiveComposite


class ReactiveSequence(ReactiveComposite):
    """``<ReactiveSequence>``: tick all children from the first, every tick.

    - a child RUNNING: every other child is reset (a RUNNING one is halted),
      RUNNING; so conditions before a running action are re-checked each tick;
    - a child FAILURE: reset all, FAILURE;
    - all SUCCESS (or SKIPPED): reset all, SUCCESS (SKIPPED if all skipped).
    """

    __slots__ = ()
    NEXT = SUCCESS
    STOP = FAILURE
