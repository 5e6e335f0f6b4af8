"""A service process for the transport tests: a ``wait`` action server (and nothing else).

python -m tests.integration.transport.action_server_proc --connect EP --namespace NS
"""

from __future__ import annotations

import argparse
import asyncio
import signal
import sys

from aiobt.core.clock import SystemClock
from aiobt.msgs import Wait
from aiobt.transport import BusSettings, GoalHandle, add_bus_arguments, open_bus


async def serve(settings: BusSettings) -> None:
    clock = SystemClock()

    async def execute(
        goal: Wait.Goal, handle: GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]
    ) -> Wait.Result:
        start = clock.now()
        while (left := goal.time - (clock.now() - start)) > 0:
            handle.publish_feedback(Wait.Feedback(time_left=left))
            await clock.sleep(min(0.05, left))
        return Wait.Result(total_elapsed_time=clock.now() - start)

    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    async with open_bus(settings) as bus:
        bus.action_server("wait", Wait, execute)
        print("ready", flush=True)
        await stop.wait()


def main() -> int:
    parser = argparse.ArgumentParser()
    add_bus_arguments(parser)
    asyncio.run(serve(BusSettings.from_args(parser.parse_args())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
