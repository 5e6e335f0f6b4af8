"""No navigation service subscribes to or calls anything in the simulation's namespace
``{ns}/sim/`` (its truth ``sim/pose``, ``sim/target``; its services ``sim/srv/...``).

The whole stack runs (every service of the catalog: the default ones, the safety chain,
the route, following and docking servers; localization giving ``{ns}/pose``, the robot
no pose in map). A publisher declared on ``{ns}/sim/**`` and never put on matches any
subscription that would receive something there (``{ns}/sim/pose``, ``{ns}/sim/**``,
``{ns}/**``): it must match none. A queryable on ``{ns}/sim/**``, declared before any
service starts, is reached by every query for a key there (the robot's queryables are
not complete, so a query goes to each queryable that matches): it must see none. The
controls, from another session as a navigation service would have one: its
subscription is matched and its call is seen."""

from __future__ import annotations

import asyncio
import contextlib

import pytest
import zenoh

from aiobt.msgs import Empty, PoseStamped
from aiobt.msgs.sim import ObstacleList
from aiobt.testing.stack import SERVICES, NavStack, StackConfig
from aiobt.transport import Bus, open_bus
from aiobt.transport.keys import SIM_POSE, sim_namespace
from aiobt.transport.publishers import Publisher, declare_publisher

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(300)]

OPTIONAL = ("route", "following", "docking")  # off in `aiobt up` unless enabled
CONFIG = StackConfig(
    world="office",
    speed=1.0,
    safety_chain=True,
    services=(*SERVICES, *OPTIONAL),
    extra={
        "route": ["--graph-filepath", "office", "--sim-time"],
        "following": ["--sim-time"],
        "docking": ["--dock-database", "office", "--sim-time"],
    },
)


class SimWatch:
    """Who subscribes to or queries anything under ``{ns}/sim/``, seen from ``bus`` (its
    declarations go with the bus's session)."""

    def __init__(self, bus: Bus) -> None:
        self.key = f"{sim_namespace(bus.namespace)}/**"
        self.queries: list[str] = []
        self.readers: Publisher[PoseStamped] = declare_publisher(
            bus.session, bus.bridge, self.key, PoseStamped, reliable=False
        )
        self._queryable = bus.session.declare_queryable(self.key, self._on_query)

    def _on_query(self, query: zenoh.Query) -> None:
        self.queries.append(str(query.key_expr))  # not answered: the caller gets its server's

    async def called(self, within: float) -> bool:
        """Whether a query came within ``within`` s (the queryable's thread appends it)."""
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(within):
                while not self.queries:  # noqa: ASYNC110 - zenoh calls back from its thread
                    await asyncio.sleep(0.01)
        return bool(self.queries)


async def test_no_navigation_service_subscribes_to_or_calls_the_simulation(
    router_endpoint: str,
) -> None:
    with contextlib.closing(NavStack(router_endpoint, CONFIG)) as stack:
        async with open_bus(stack.settings()) as bus:
            watch = SimWatch(bus)  # before any service starts: no call is missed
            for service in CONFIG.services:
                stack.start(service)
            await stack.wait_ready(bus, timeout=180.0)
            estimate = bus.subscribe("pose", PoseStamped, queue_size=1)
            await estimate.wait_latest(60.0)  # localization is in the loop
            estimate.close()
            subscribed = await watch.readers.wait_for_subscribers(3.0)
            assert (subscribed, watch.queries) == (False, []), (
                f"a process subscribes to ({subscribed}) or calls ({watch.queries}) "
                f"{watch.key}:\n{stack.logs()}"
            )
            async with open_bus(stack.settings()) as reader:  # the controls
                reader.subscribe(SIM_POSE, PoseStamped)
                assert await watch.readers.wait_for_subscribers(10.0)
                sim = sim_namespace(reader.namespace)
                await reader.call("obstacles/list", Empty(), ObstacleList, 10.0, namespace=sim)
                assert await watch.called(5.0)
                assert set(watch.queries) == {f"{sim}/srv/obstacles/list"}, watch.queries
