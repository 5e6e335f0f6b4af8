"""Fallback and AsyncFallback: tick children in order until one succeeds."""

from __future__ import annotations

from aiobt.core.status import FAILURE, SUCCESS
from aiobt.nodes.control.ordered import OrderedComposite


class Fallback(OrderedComposite):
    """``<Fallback>`` (OR): tick children in order.

    - a child RUNNING: RUNNING, and the same child is ticked next time;
    - a child SUCCESS: reset all children, SUCCESS;
    - every child FAILURE (or SKIPPED): reset, FAILURE (SKIPPED if all skipped).
    """

    __slots__ = ()
    NEXT = FAILURE
    STOP = SUCCESS


class AsyncFallback(Fallback):
    """``<AsyncFallback>``: a Fallback that returns RUNNING (and asks for a
    wake-up) after each child that failed in the tick it started."""

    __slots__ = ()
    YIELDS = True
