"""Sequence and AsyncSequence: tick children in order until one fails."""

from __future__ import annotations

from aiobt.core.status import FAILURE, SUCCESS
from aiobt.nodes.control.ordered import OrderedComposite


class Sequence(OrderedComposite):
    """``<Sequence>`` (AND): tick children in order.

    - a child RUNNING: RUNNING, and the same child is ticked next time;
    - a child FAILURE: reset all children, start over next time, FAILURE;
    - every child SUCCESS (or SKIPPED): reset, SUCCESS (SKIPPED if all skipped).
    """

    __slots__ = ()
    NEXT = SUCCESS
    STOP = FAILURE


class AsyncSequence(Sequence):
    """``<AsyncSequence>``: a Sequence that returns RUNNING (and asks for a
    wake-up) after each child that finished in the tick it started, so long
    chains of instant children stay interruptible."""

    __slots__ = ()
    YIELDS = True
