"""The zenoh command line (which sends raw bytes) switches a selector on a real router."""

from __future__ import annotations

import asyncio
import contextlib
import shutil
import sys
from pathlib import Path

import pytest

from aiobt.core.status import Status
from aiobt.msgs import String
from aiobt.nav import NavContext
from aiobt.nav.shared_topics import SharedTopic, shared_topics
from aiobt.transport import Bus
from tests.unit.nav.state_support import nav_tree, wait_received

pytestmark = [pytest.mark.integration, pytest.mark.timeout(120)]
PLANNER = (
    '<PlannerSelector topic_name="planner_selector" default_planner="GridBased" '
    'selected_planner="{planner}"/>'
)


def zenoh_cli() -> str:
    """The ``zenoh`` script next to this interpreter (the venv's), else the one on PATH."""
    beside = Path(sys.executable).with_name("zenoh")
    found = str(beside) if beside.exists() else shutil.which("zenoh")
    if found is None:
        pytest.fail("the zenoh command line (PyPI zenoh-cli, a dev dependency) is not installed")
    return found


async def zenoh_put(router: str, key: str, value: str) -> None:
    """``zenoh --mode client --connect ROUTER put -k KEY -v VALUE``, killed by PID if it hangs."""
    proc = await asyncio.create_subprocess_exec(
        zenoh_cli(),
        "--mode",
        "client",
        "--connect",
        router,
        "--cfg",
        "scouting/multicast/enabled:false",
        "put",
        "-k",
        key,
        "-v",
        value,
        stdout=asyncio.subprocess.PIPE,
        stderr=asyncio.subprocess.STDOUT,
    )
    try:
        output, _ = await asyncio.wait_for(proc.communicate(), 60)
    finally:
        if proc.returncode is None:
            with contextlib.suppress(ProcessLookupError):
                proc.kill()
            await proc.wait()
    assert proc.returncode == 0, output.decode(errors="replace")


async def put_and_wait(bus: Bus, router: str, topic: SharedTopic[String], value: str) -> None:
    before = topic.received
    await zenoh_put(router, topic.key, value)
    await wait_received(topic, before, 30.0)


async def test_zenoh_put_switches_the_planner_selector(bus: Bus, router_endpoint: str) -> None:
    tree = nav_tree(bus, PLANNER)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert tree.root_blackboard["planner"] == "GridBased"
    topic = shared_topics(NavContext(bus=bus), "test").topic(
        "planner_selector", String, latched=True
    )
    await put_and_wait(bus, router_endpoint, topic, "SmacPlanner")
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert tree.root_blackboard["planner"] == "SmacPlanner"
    await put_and_wait(bus, router_endpoint, topic, '{"data": "ThetaStar"}')
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert tree.root_blackboard["planner"] == "ThetaStar"
