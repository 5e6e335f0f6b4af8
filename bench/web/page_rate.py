"""Updates per second the web view's page gets with the whole stack driving, at speed-ups.

Run: ``.venv/bin/python -m bench.web.page_rate --speeds 1 10 [--seconds 10] [--rate 20]``

For each speed-up, in a fresh stack (router, robot on the office world, planner,
controller, behaviors, navigator as processes on loopback) with the web view in
this process and headless Chromium on the page: a goal ~25 m away is clicked on
the map, and over ``--seconds`` of wall time while the robot drives the bench
counts, in the same window, the pose messages the robot published on the bus
(the baseline: what a forwarding-everything view would push) and, in the page,
the updates and the pose updates it received. Prints both and their ratio, the
view's cap (``--rate``), and the load average.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import time
from collections.abc import Sequence
from typing import Any

from aiobt.msgs import PoseStamped
from aiobt.testing.browser import headless_chromium, measured_rate, missing_browser, page_value
from aiobt.testing.bus import exit_on_sigterm
from aiobt.testing.stack import StackConfig, running_stack
from aiobt.transport import open_bus
from aiobt.web import WebOptions, serve_web

GOAL = (18.5, 18.0)  # the office's north-east room
WAIT = 120.0  # s for the stack and the page (a loaded machine)


async def _until(driver: Any, script: str) -> Any:
    deadline = time.monotonic() + WAIT
    while not (value := await asyncio.to_thread(page_value, driver, script)):
        if time.monotonic() > deadline:
            raise TimeoutError(f"the page never showed {script}")
        await asyncio.sleep(0.2)
    return value


async def one_speed(speed: float, seconds: float, rate: float, driver: Any) -> dict[str, float]:
    with running_stack(StackConfig(speed=speed)) as stack:
        async with open_bus(stack.settings()) as bus:
            await stack.wait_ready(bus, timeout=WAIT)
            async with serve_web(bus, WebOptions(port=0, rate=rate)) as view:
                await asyncio.to_thread(driver.get, view.url)
                await _until(driver, "window.aiobtState.map && window.aiobtState.robot")
                sent = await view.sources.send_goal(*GOAL, 0.0)
                if sent:
                    raise RuntimeError(sent)
                start = await _until(driver, "window.aiobtState.robot")
                await _until(
                    driver,
                    f"(s => Math.hypot(s.robot.x - {start['x']}, s.robot.y - {start['y']}) > 0.3)"
                    "(window.aiobtState)",
                )
                poses = [0]
                counting = bus.subscribe(
                    "pose", PoseStamped, lambda _p: poses.__setitem__(0, poses[0] + 1)
                )
                began = time.monotonic()
                frames, page_poses = await asyncio.to_thread(measured_rate, driver, seconds)
                bus_rate = poses[0] / (time.monotonic() - began)
                counting.close()
    return {"speed": speed, "bus": bus_rate, "frames": frames, "page_poses": page_poses}


async def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[1.0, 10.0])
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rate", type=float, default=20.0, help="the view's cap, updates/s")
    exit_on_sigterm()
    args = parser.parse_args(argv)
    reason = missing_browser()
    if reason is not None:
        raise SystemExit(f"bench.web.page_rate: {reason}")
    print(f"load average before: {os.getloadavg()[0]:.1f}; view cap {args.rate:g} updates/s")
    print("| speed-up | robot poses on the bus /s (baseline) | page updates /s | "
          "page pose updates /s | page poses / bus poses |")  # fmt: skip
    print("|---|---|---|---|---|")
    with headless_chromium() as driver:
        for speed in args.speeds:
            r = await one_speed(speed, args.seconds, args.rate, driver)
            print(
                f"| {speed:g}x | {r['bus']:.1f} | {r['frames']:.1f} | {r['page_poses']:.1f} | "
                f"{r['page_poses'] / r['bus']:.2f} |",
                flush=True,
            )
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    asyncio.run(main())
