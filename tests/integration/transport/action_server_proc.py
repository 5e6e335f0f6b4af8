"""A service process for the transport tests: a ``wait`` action server (and nothing else).

python -m tests.integration.transport.action_server_proc --connect EP --namespace NS
"""

from __future__ import annotations

import sys

from aiobt.core.clock import SystemClock
from aiobt.msgs import Wait
from aiobt.testing.bus import service_main
from aiobt.transport import Bus, GoalHandle


def declare(bus: Bus) -> None:
    clock = SystemClock()

    async def execute(
        goal: Wait.Goal, handle: GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]
    ) -> Wait.Result:
        start = clock.now()
        while (left := goal.time - (clock.now() - start)) > 0:
            handle.publish_feedback(Wait.Feedback(time_left=left))
            await clock.sleep(min(0.05, left))
        return Wait.Result(total_elapsed_time=clock.now() - start)

    bus.action_server("wait", Wait, execute)


if __name__ == "__main__":
    sys.exit(service_main(declare))
