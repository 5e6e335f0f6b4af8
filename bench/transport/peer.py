"""The far side of the transport benchmark: raw Zenoh and aiobt endpoints in one process.

python -m bench.transport.peer --connect tcp/127.0.0.1:PORT --namespace bench
"""

from __future__ import annotations

import asyncio
import sys

import zenoh

from aiobt.msgs import ClearCostmapResponse, ClearEntireCostmap, PoseStamped, Wait
from aiobt.testing.bus import service_main
from aiobt.transport import Bus, GoalHandle


def raw_endpoints(session: zenoh.Session, ns: str, loop: asyncio.AbstractEventLoop) -> list[object]:
    """Baselines: a queryable answering at once (in Zenoh's thread, or via the event
    loop like aiobt), and a put echo in Zenoh's thread."""
    pong = session.declare_publisher(f"{ns}/raw_pong")

    def answer(query: zenoh.Query) -> None:
        with query:
            query.reply(query.key_expr, b"{}")

    def answer_in_loop(query: zenoh.Query) -> None:
        loop.call_soon_threadsafe(answer, query)

    def echo(sample: zenoh.Sample) -> None:
        pong.put(sample.payload)

    def echo_in_loop(sample: zenoh.Sample) -> None:
        loop.call_soon_threadsafe(pong.put, sample.payload.to_bytes())

    return [
        pong,
        session.declare_queryable(f"{ns}/raw_get", answer),
        session.declare_queryable(f"{ns}/raw_get_loop", answer_in_loop),
        session.declare_subscriber(f"{ns}/raw_ping", echo),
        session.declare_subscriber(f"{ns}/raw_ping_loop", echo_in_loop),
    ]


async def trivial(
    goal: Wait.Goal, handle: GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]
) -> Wait.Result:
    return Wait.Result(total_elapsed_time=goal.time)


def declare(bus: Bus) -> list[object]:
    """The raw baselines and aiobt's endpoints (all undeclared when the bus closes)."""
    raw = raw_endpoints(bus.session, bus.namespace, asyncio.get_running_loop())
    pong = bus.publisher("pong", PoseStamped)
    bus.subscribe("ping", PoseStamped, callback=pong.put)
    bus.action_server("trivial", Wait, trivial)
    bus.serve(
        "echo",
        ClearEntireCostmap.Request,
        ClearCostmapResponse,
        lambda request: ClearCostmapResponse(),
    )
    return raw


if __name__ == "__main__":
    sys.exit(service_main(declare))
