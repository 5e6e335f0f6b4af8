"""An action goal whose router-to-router link is cut while it runs, then heals.

Two routers on loopback, the second joined to the first through the link proxy
(tests/netlab/proxy.py, in this process); the action server on the first, its
client on the second, as the controller (robot host) and the navigator (base host).

What Zenoh does with the goal's query (a long-lived get) across the cut: once the
routers' lease runs out the routes through the link go, the router on the client's
side ends the query (the goal's reply stream closes without a result) and the
server's liveliness token goes; the client fails the goal (``GoalLost``). The
server is told nothing: its query object stays, its replies go nowhere, and its
execute runs on (on a robot: the controller follows its path without the base).
When the link heals, Zenoh sends nothing again: no query is retried. So the goal is
never executed a second time; and the client, seeing the server back, cancels the
goal it gave up for lost, so that it does not run on unwatched.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Iterator
from typing import Any

import pytest

from aiobt.msgs import GoalState, Wait
from aiobt.testing.bus import running_router
from aiobt.transport import Bus, BusSettings, GoalLost, open_bus
from aiobt.transport.endpoints import free_port
from tests.netlab.proxy import LinkProxy

pytestmark = [pytest.mark.integration, pytest.mark.timeout(90)]
LOOPBACK = "127.0.0.1"
WAIT = 20.0  # s: bounded waits for the routers on a loaded machine


@contextlib.contextmanager
def _routers(proxy_port: int, server_port: int) -> Iterator[tuple[str, str]]:
    """The server's router on ``server_port``, the client's joined to it via the proxy."""
    with (
        running_router(f"tcp/{LOOPBACK}:{server_port}") as (_, server_side),
        running_router(
            f"tcp/{LOOPBACK}:{free_port()}", ["--connect", f"tcp/{LOOPBACK}:{proxy_port}"]
        ) as (_, client_side),
    ):
        yield server_side, client_side


@contextlib.asynccontextmanager
async def _link() -> AsyncIterator[tuple[LinkProxy, Bus, Bus]]:
    server_port = free_port()
    proxy = LinkProxy((LOOPBACK, 0), (LOOPBACK, server_port))
    await proxy.start()
    try:
        with _routers(proxy.port, server_port) as (server_side, client_side):
            async with (
                open_bus(BusSettings(connect=(server_side,), connect_timeout=WAIT)) as server,
                open_bus(BusSettings(connect=(client_side,), connect_timeout=WAIT)) as client,
            ):
                yield proxy, server, client
    finally:
        await proxy.close()


async def test_a_goal_cut_off_runs_once_and_is_canceled_when_the_link_heals() -> None:
    started: list[str] = []
    ended: dict[str, str] = {}
    release = asyncio.Event()
    canceled = asyncio.Event()

    async def execute(goal: Any, handle: Any) -> Any:
        started.append(handle.goal_id)
        try:
            await release.wait()
        except asyncio.CancelledError:
            ended[handle.goal_id] = "canceled"
            canceled.set()
            raise
        ended[handle.goal_id] = "done"
        return Wait.Result()

    async with _link() as (proxy, server_bus, client_bus):
        server_bus.action_server(Wait.name, Wait, execute)
        client = client_bus.action_client(Wait.name, Wait)
        assert await client.wait_for_server(WAIT)
        goal = await client.send_goal(Wait.Goal(time=1.0), server_timeout=WAIT)
        assert started == [goal.goal_id]

        proxy.cut()
        with pytest.raises(GoalLost):
            await goal.result(WAIT)  # the routers' lease (1 s) runs out: the goal is lost
        assert not client.server_present
        assert ended == {}  # ... but the server runs it on: nobody told it

        proxy.restore()
        assert await client.wait_for_server(WAIT), "the routers did not reconnect"
        # the client cancels what it gave up for lost
        assert await asyncio.wait_for(canceled.wait(), WAIT)
        assert ended == {goal.goal_id: "canceled"}

        # a goal sent now is executed; the link is FIFO, so a copy of the first sent
        # again would have come before it
        again = await client.send_goal(Wait.Goal(time=1.0), server_timeout=WAIT)
        release.set()
        await again.result(WAIT)
        assert again.status is GoalState.SUCCEEDED
        assert started == [goal.goal_id, again.goal_id]
