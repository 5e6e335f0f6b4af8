"""Repeat: tick the child again after each success."""

from __future__ import annotations

from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.nodes.decorators.retry import RetryUntilSuccessful


class Repeat(RetryUntilSuccessful):
    """``<Repeat num_cycles="N">``: run the child N times (-1: forever).

    SUCCESS after N successes (N=0 succeeds without ticking); FAILURE as soon
    as the child fails. Like RetryUntilSuccessful it yields (RUNNING and a
    wake-up) between cycles that finish within a tick. SKIPPED child: SKIPPED.
    """

    __slots__ = ()
    PORTS = (
        input_port(
            "num_cycles",
            int,
            description="repeat a successful child up to N times; -1 loops forever",
            required=True,
        ),
    )
    LIMIT_PORT = "num_cycles"
    AGAIN = Status.SUCCESS
