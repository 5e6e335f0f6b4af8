"""``aiobt web`` and ``aiobt up``'s web view as processes: the page, its websocket fed from
the bus (a real router), goals from the page onto ``{ns}/goal_pose``, and bad input named."""

from __future__ import annotations

import asyncio
import json
import signal
import socket
from collections.abc import AsyncIterator, Callable, Sequence
from pathlib import Path
from typing import Any

import aiohttp
import numpy as np
import pytest

from aiobt.msgs import Msg, OccupancyGrid, PoseStamped
from aiobt.msgs.bt import BtSnapshot
from aiobt.testing.bus import ServiceProcess, free_endpoint, free_port, wait_port
from aiobt.transport import Bus
from tests.integration.system.helpers import SystemProcess, kill_mentioning, processes_mentioning

pytestmark = [pytest.mark.integration, pytest.mark.timeout(180)]
WAIT = 60.0  # s for a process to listen, a message to arrive (a loaded machine)
Spawn = Callable[[Sequence[str]], ServiceProcess]


async def listening(proc: ServiceProcess, port: int) -> None:
    assert await asyncio.to_thread(wait_port, port, WAIT), proc.output()


async def updates(ws: aiohttp.ClientWebSocketResponse) -> AsyncIterator[dict[str, Any]]:
    while True:
        message = await ws.receive(timeout=WAIT)
        assert message.type == aiohttp.WSMsgType.TEXT, message
        yield json.loads(message.data)


async def first(ws: aiohttp.ClientWebSocketResponse, stream: str, check: Any = None) -> Any:
    """The first value of ``stream`` (for which ``check`` holds) the page is sent."""
    async with asyncio.timeout(WAIT):
        async for update in updates(ws):
            if stream in update and (check is None or check(update[stream])):
                return update[stream]
    raise AssertionError("unreachable")


async def keep_publishing(bus: Bus, message: Msg, topic: str = "pose") -> None:
    """``message`` at 20 Hz, as a robot would its pose (a put before the view subscribed is
    lost)."""
    publisher = bus.publisher(topic, type(message))
    while True:
        publisher.put(message)
        await asyncio.sleep(0.05)


async def test_aiobt_web_serves_the_page_fed_from_the_bus_and_takes_goals(
    bus: Bus, router_endpoint: str, spawn: Spawn
):
    port = free_port()
    args = ["--connect", router_endpoint, "--namespace", bus.namespace, "--port", str(port)]
    proc = spawn(["-m", "aiobt.cli.main", "web", *args])
    cells = np.zeros((40, 60), np.int8)
    cells[20, 30] = 100
    bus.latched_publisher("map", OccupancyGrid).put(OccupancyGrid.from_array(cells, 0.05))
    goals: asyncio.Queue[PoseStamped] = asyncio.Queue()
    bus.subscribe("goal_pose", PoseStamped, goals.put_nowait)
    await listening(proc, port)
    assert proc.wait_for_output(f"web view on http://127.0.0.1:{port}/", WAIT)
    publishing = asyncio.create_task(keep_publishing(bus, PoseStamped.from_xy_yaw(1.25, 0.5)))
    try:
        async with aiohttp.ClientSession(f"http://127.0.0.1:{port}") as http:
            async with http.get("/") as response:
                assert response.status == 200
                assert '<canvas id="map"' in await response.text()
            async with http.get("/app.js") as response:
                assert response.status == 200
                assert "window.aiobtState" in await response.text()
            async with http.ws_connect("/ws") as ws:
                grid = await first(ws, "map")
                assert (grid["width"], grid["height"], grid["resolution"]) == (60, 40, 0.05)
                assert await first(ws, "pose", lambda p: p["x"] == 1.25)
                await ws.send_str(json.dumps({"goal": {"x": 2.0, "y": 1.0, "yaw": 0.0}}))
                refused = await first(ws, "goal_reply")
                assert not refused["ok"]
                assert "no navigator" in refused["error"]  # nothing to take it: not sent
                bus.declare_token("nodes/navigator")  # a navigator is up from now on
                await ws.send_str(json.dumps({"goal": {"x": 2.0, "y": 1.0, "yaw": 0.5}}))
                assert (await first(ws, "goal_reply"))["ok"]
                goal = await asyncio.wait_for(goals.get(), WAIT)
                assert (goal.x, goal.y, round(goal.yaw, 6)) == (2.0, 1.0, 0.5)
                # the map marks the navigator's goal (bt/snapshot), whatever goal_pose said
                driven = PoseStamped.from_xy_yaw(-1.0, 0.5)
                shot = BtSnapshot(run=0, state="navigating", goals=[driven], nodes=[])
                snapshots = asyncio.create_task(keep_publishing(bus, shot, "bt/snapshot"))
                try:
                    nav = await first(ws, "nav", lambda n: n["goals"])
                finally:
                    snapshots.cancel()
                assert [(g["x"], g["y"]) for g in nav["goals"]] == [(-1.0, 0.5)]
                await ws.send_str('{"goal": {"x": "far"}}')
                bad = await first(ws, "goal_reply")
                assert not bad["ok"]
                assert "y" in bad["error"] or "must be numbers" in bad["error"]
    finally:
        publishing.cancel()
    assert proc.stop() == 0


async def test_a_port_in_use_is_named_and_exits_2(router_endpoint: str, spawn: Spawn):
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        proc = spawn(["-m", "aiobt.cli.main", "web", "--connect", router_endpoint,
                      "--port", str(port)])  # fmt: skip
        code = await asyncio.to_thread(proc.popen.wait, WAIT)
    assert code == 2
    assert f"aiobt web: web view: cannot listen on 127.0.0.1:{port}" in proc.output()


def test_up_runs_the_web_view_and_still_stops_in_under_3_s(tmp_path: Path):
    endpoint, port = free_endpoint(), free_port()
    config = tmp_path / "system.yaml"
    config.write_text(f"world: small\nspeed: 2\nrouter: {{listen: '{endpoint}'}}\n")
    try:
        with SystemProcess(["up", "--config", str(config), "--web-port", str(port)]) as up:
            line = up.wait_line("web view on ")
            assert f"http://127.0.0.1:{port}/" in line
            asyncio.run(_page_has_the_map(port))
            up.wait_line("     up * ")
            code, seconds = up.stop(signal.SIGTERM)
        assert code == 0
        assert seconds < 3.0
        assert processes_mentioning(endpoint) == []
    finally:
        kill_mentioning(endpoint)


async def _page_has_the_map(port: int) -> None:
    async with (
        aiohttp.ClientSession() as http,
        http.ws_connect(f"http://127.0.0.1:{port}/ws") as ws,
    ):
        grid = await first(ws, "map")
        assert grid["width"] > 0
