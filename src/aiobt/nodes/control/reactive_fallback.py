"""ReactiveFallback: re-try every child from the first on each tick."""

from __future__ import annotations

from aiobt.core.status import FAILURE, SUCCESS
from aiobt.nodes.control.ordered import ReactiveComposite


class ReactiveFallback(ReactiveComposite):
    """``<ReactiveFallback>``: tick all children from the first, every tick.

    - a child RUNNING: every other child is reset (a RUNNING one is halted),
      RUNNING; so a higher-priority child that starts to succeed preempts;
    - a child SUCCESS: reset all, SUCCESS;
    - all FAILURE (or SKIPPED): reset all, FAILURE (SKIPPED if all skipped).
    """

    __slots__ = ()
    NEXT = FAILURE
    STOP = SUCCESS
