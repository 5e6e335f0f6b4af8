"""The web view in headless Chromium beside a hardware-like robot (no pose in map) and the
localization service on a real router: the page gets the particle cloud, the estimate
(``{ns}/pose``, ``amcl_pose``) and the simulation's truth (``{ns}/sim/pose``), and draws
the particles and the truth on the map (their colours counted on the canvas)."""

from __future__ import annotations

import asyncio
import math
from pathlib import Path
from typing import Any

import pytest

from aiobt.testing.browser import page_value
from aiobt.transport import Bus, BusSettings
from aiobt.web import WebOptions, serve_web
from tests.integration.localization.stack import START, Spawn, set_initial_pose, start_stack

from .test_browser import wait_page

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(240)]
PARTICLE, TRUTH = (0x79, 0x55, 0x48), (0x00, 0xBC, 0xD4)  # localization.js's colours


def pixels_of(colour: tuple[int, int, int]) -> str:
    """A page script: how many canvas pixels have exactly ``colour``."""
    r, g, b = colour
    return (
        "(c => { const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
        f" let n = 0; for (let i = 0; i < d.length; i += 4) n += d[i] === {r} &&"
        f" d[i + 1] === {g} && d[i + 2] === {b}; return n; }})(document.getElementById('map'))"
    )


async def test_page_draws_the_particle_cloud_and_the_truth_beside_the_estimate(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, browser: Any, tmp_path: Path
) -> None:
    await start_stack(spawn, bus, bus_settings, speed=2)
    async with serve_web(bus, WebOptions(port=0)) as view:
        await asyncio.to_thread(browser.get, view.url)
        await wait_page(browser, "window.aiobtState.map", "the map")
        truth = await wait_page(browser, "window.aiobtState.truth", "the truth")
        assert math.dist((truth["x"], truth["y"]), START[:2]) < 0.05  # where the sim put it
        assert page_value(browser, "window.aiobtState.robot") is None  # no estimate yet
        await set_initial_pose(bus, *START)  # the localization starts: estimate and cloud
        particles = await wait_page(
            browser, "window.aiobtState.particles.length && window.aiobtState.particles",
            "the particle cloud",
        )  # fmt: skip
        assert 10 <= len(particles) <= 250  # thinned by the service for viewers
        spread = sorted(math.dist((x, y), START[:2]) for x, y, _ in particles)
        assert spread[len(spread) // 2] < 1.0, spread  # around the initial pose
        robot = await wait_page(browser, "window.aiobtState.robot", "the estimate")
        assert math.dist((robot["x"], robot["y"]), START[:2]) < 0.5
        estimate = await wait_page(browser, "window.aiobtState.amclPose", "amcl_pose")
        assert len(estimate["covariance"]) == 4
        assert estimate["covariance"][0] > 0.0  # the cloud's spread in x
        drawn = await wait_page(
            browser, "(d => d.particles && d.truth && d)(window.aiobtState.drawn)", "both drawn"
        )
        assert drawn["particles"] == len(page_value(browser, "window.aiobtState.particles"))
        assert page_value(browser, pixels_of(PARTICLE)) > 2 * len(particles)
        assert page_value(browser, pixels_of(TRUTH)) > 20
        error = await wait_page(browser, "window.aiobtState.truthError", "the error readout")
        assert error.startswith("estimate off the truth by "), error
        assert float(error.split(" by ")[1].split(" cm")[0]) < 50.0, error
        toggle = browser.find_element("id", "show-particles")
        await asyncio.to_thread(toggle.click)  # particles off: none drawn, the truth stays
        await wait_page(browser, pixels_of(PARTICLE).replace("return n;", "return n === 0;"),
                        "no particle drawn")  # fmt: skip
        assert page_value(browser, pixels_of(TRUTH)) > 20
        await asyncio.to_thread(toggle.click)
        shot = tmp_path / "localization_view.png"
        assert await asyncio.to_thread(browser.save_screenshot, str(shot))
        print(f"{len(particles)} particles drawn, {error}; screenshot {shot}")
