"""A browser that does not read while the robot floods the bus gets a few newest updates,
not a backlog (the web view in this process, a real router, a websocket client)."""

from __future__ import annotations

import asyncio
import json
import time

import aiohttp
import pytest

from aiobt.msgs import PoseStamped
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.web import WebOptions, serve_web

pytestmark = [pytest.mark.integration, pytest.mark.timeout(120)]
FLOOD = 3000  # poses, put as fast as the publisher goes
WAIT = 60.0


async def test_a_client_that_does_not_read_gets_the_newest_pose_not_a_backlog(
    bus: Bus, bus_settings: BusSettings
):
    async with (
        open_bus(bus_settings) as robot,
        serve_web(bus, WebOptions(port=0, rate=20.0)) as view,
        aiohttp.ClientSession() as http,
        http.ws_connect(view.url + "ws") as ws,
    ):
        publisher = robot.publisher("pose", PoseStamped, reliable=True)
        assert await publisher.wait_for_subscribers(WAIT)
        began = time.monotonic()
        for step in range(FLOOD):  # the client reads nothing meanwhile
            publisher.put(PoseStamped.from_xy_yaw(step * 0.001, 0.0))
            if step % 100 == 0:
                await asyncio.sleep(0)  # let the view's loop run, as a real robot would
        last = round((FLOOD - 1) * 0.001, 3)
        frames = poses = 0
        async with asyncio.timeout(WAIT):
            while True:
                update = json.loads((await ws.receive()).data)
                frames += 1
                poses += "pose" in update
                if update.get("pose", {}).get("x") == last:
                    break
        seconds = time.monotonic() - began
    print(f"{poses} pose updates in {seconds:.2f} s for {FLOOD} poses")
    # at most one update per flush (20/s) reached the client, each with the newest pose
    assert poses <= seconds * 20.0 + 2, (poses, seconds)
    assert poses < FLOOD / 10
    assert frames >= 1
