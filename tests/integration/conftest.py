"""Fixtures for tests with real Zenoh: a router process, a bus, service processes.

- ``router_endpoint``: "tcp/127.0.0.1:PORT" of a router process (one per module)
- ``bus_settings``: client settings for that router with a namespace unique to the test
- ``bus``: an open :class:`aiobt.transport.Bus` with those settings
- ``spawn``: ``spawn(["-m", "aiobt_services.robot", ...])`` -> ServiceProcess, killed
  by PID at the end of the test (its output is printed if the test fails)
"""

from __future__ import annotations

import contextlib
import uuid
from collections.abc import AsyncIterator, Callable, Generator, Iterator, Sequence

import pytest

from aiobt.testing.bus import ServiceProcess, running_router, spawn_service
from aiobt.transport import Bus, BusSettings, open_bus


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_runtest_makereport(
    item: pytest.Item,
) -> Generator[None, pytest.TestReport, pytest.TestReport]:
    report = yield
    setattr(item, f"rep_{report.when}", report)
    return report


@pytest.fixture(scope="module")
def router_endpoint() -> Iterator[str]:
    with running_router() as (_, endpoint):
        yield endpoint


@pytest.fixture
def bus_settings(router_endpoint: str) -> BusSettings:
    return BusSettings(
        mode="client",
        connect=(router_endpoint,),
        namespace=f"t{uuid.uuid4().hex[:10]}",
        connect_timeout=10.0,
    )


@pytest.fixture
async def bus(bus_settings: BusSettings) -> AsyncIterator[Bus]:
    async with open_bus(bus_settings) as opened:
        yield opened


@pytest.fixture
def spawn(request: pytest.FixtureRequest) -> Iterator[Callable[[Sequence[str]], ServiceProcess]]:
    started: list[ServiceProcess] = []

    def start(args: Sequence[str]) -> ServiceProcess:
        proc = spawn_service(args)
        started.append(proc)
        return proc

    yield start
    failed = getattr(request.node, "rep_call", None)
    with contextlib.ExitStack() as cleanups:  # every process is stopped, even if one fails to
        for proc in started:
            cleanups.callback(proc.cleanup)
        for proc in started:
            proc.stop()
            if failed is not None and failed.failed:
                print(f"--- output of {' '.join(proc.args)} ---\n{proc.output()}")
