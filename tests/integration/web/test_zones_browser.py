"""The collision monitor's zones in the web view, in headless Chromium: the robot (small
world) and the collision monitor as processes, the web view on the test's bus. A box
put in the stop zone ahead of the robot and a command to drive make the monitor act:
the page draws both polygons at the robot, the acting one red and the other in its
action's colour (read back from the canvas's pixels, not only from the page's state)."""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import pytest
from selenium.common.exceptions import TimeoutException
from selenium.webdriver.support.ui import WebDriverWait

from aiobt.msgs import Twist
from aiobt.msgs.sim import Ack, SpawnObstacle
from aiobt.testing.browser import page_value
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace
from aiobt.web import WebOptions, serve_web
from tests.integration.safety.chain import Spawn, monitor_params, start_chain

pytestmark = [pytest.mark.integration, pytest.mark.e2e]
WAIT = 60.0  # s for what the page must show (a loaded machine)
ROBOT_X = -1.8  # chain.START
STOP_ZONE = [[0.6, 0.3], [0.6, -0.3], [0.3, -0.3], [0.3, 0.3]]  # base frame: far edge first
SLOW_ZONE = [[1.2, 0.6], [1.2, -0.6], [0.3, -0.6], [0.3, 0.6]]
Pixel = tuple[int, int, int]
# the canvas's own drawing: the pixels (r, g, b) of the 5 x 5 about map point (x, y)
PIXELS = """
const [x, y] = arguments; const m = window.aiobtState.map;
const c = document.getElementById('map'); if (!m) return [];
const k = c.width / m.width;
const cx = Math.round((x - m.origin[0]) / m.resolution * k);
const cy = Math.round((m.height - (y - m.origin[1]) / m.resolution) * k);
const d = c.getContext('2d').getImageData(cx - 2, cy - 2, 5, 5).data;
const out = []; for (let i = 0; i < d.length; i += 4) out.push([d[i], d[i + 1], d[i + 2]]);
return out;
"""


def red(p: Pixel) -> bool:  # app.js's acting zone, #d50000 (3.5 px wide: solid at its middle)
    return p[0] >= 180 and p[1] <= 40 and p[2] <= 40


def orange(p: Pixel) -> bool:  # a slowdown or stop zone not acting, #ff9100 (1.5 px: blended)
    return p[0] >= 200 and 100 <= p[1] <= 210 and p[2] <= 120 and p[0] - p[1] >= 45


def two_zones(params: dict[str, Any]) -> None:
    params["polygons"] = ["Stop", "Slow"]
    common = {"type": "polygon", "min_points": 4, "visualize": True, "enabled": True}
    params["Stop"] = {**common, "action_type": "stop", "points": str(STOP_ZONE)}
    params["Slow"] = {**common, "action_type": "slowdown", "slowdown_ratio": 0.5,
                      "points": str(SLOW_ZONE)}  # fmt: skip


async def wait_page(driver: Any, what: str, script: str, *args: Any, ok: Any = bool) -> Any:
    """``script``'s value once ``ok(value)`` (re-evaluated until then), off the event loop."""

    def until() -> Any:
        try:
            return WebDriverWait(driver, WAIT, poll_frequency=0.2).until(
                lambda d: (lambda v: ok(v) and v)(d.execute_script(script, *args))
            )
        except TimeoutException:
            zones = page_value(driver, "JSON.stringify(window.aiobtState.zones)")
            seen = driver.execute_script(script, *args)
            raise AssertionError(
                f"the page never showed {what}; it had {seen}; its zones: {zones}"
            ) from None

    return await asyncio.to_thread(until)


def any_pixel(test: Any) -> Any:
    return lambda pixels: any(test(p) for p in pixels)


def edge_middle(zone: dict[str, Any]) -> tuple[float, float]:
    """The middle of the zone's first edge (map frame): its far side, ahead of the robot."""
    (x1, y1), (x2, y2) = zone["points"][0], zone["points"][1]
    return (x1 + x2) / 2, (y1 + y2) / 2


@pytest.mark.timeout(240)
async def test_the_zones_are_drawn_at_the_robot_and_the_acting_one_red(
    browser: Any, spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path
) -> None:
    params = monitor_params(tmp_path, two_zones)
    await start_chain(spawn, bus, bus_settings, speed="1", smoother=None, controller=None,
                      monitor=["--params-file", params])  # fmt: skip
    # in the stop zone: its near face 0.45 m ahead of the robot's centre
    box = SpawnObstacle(id="box", shape="box", x=ROBOT_X + 0.55, y=0.0, size_x=0.2,
                        size_y=0.4, height=0.5)  # fmt: skip
    sim = sim_namespace(bus.namespace)  # the simulation's services
    assert (await bus.call("obstacles/spawn", box, Ack, timeout=10.0, namespace=sim)).ok
    command = bus.publisher("cmd_vel_smoothed", Twist)
    driving = asyncio.create_task(_drive(command))
    try:
        async with serve_web(bus, WebOptions(port=0)) as view:
            await asyncio.to_thread(browser.get, view.url)
            zones = await wait_page(
                browser,
                "two zones, one acting",
                "const z = window.aiobtState.zones;"
                "return z.length === 2 && z.some(q => q.acting) && window.aiobtState.robot && z;",
            )
            by_name = {z["name"]: z for z in zones}
            assert sorted(by_name) == ["Slow", "Stop"]
            assert (by_name["Stop"]["acting"], by_name["Slow"]["acting"]) == (True, False)
            assert by_name["Stop"]["action"] == "stop"
            far = edge_middle(by_name["Stop"])  # 0.6 m ahead of the robot's centre
            assert far == pytest.approx((ROBOT_X + 0.6, 0.0), abs=0.05)
            await wait_page(browser, "the acting zone in red", PIXELS, *far, ok=any_pixel(red))
            slow = edge_middle(by_name["Slow"])
            pixels = await wait_page(
                browser, "the other zone in orange", PIXELS, *slow, ok=any_pixel(orange)
            )
            assert not any(red(p) for p in pixels)  # not drawn as acting
    finally:
        driving.cancel()
        await asyncio.gather(driving, return_exceptions=True)


async def _drive(command: Any) -> None:
    """The smoother's output, forward at 0.3 m/s, ten times a second (wall) until cancelled."""
    while True:
        command.put(Twist.planar(0.3, 0.0))
        await asyncio.sleep(0.1)
