"""The navigation stack as processes for end-to-end scenarios.

- ``stack``: router + robot (office world, seeded, at ``AIOBT_E2E_SPEED``, default 4x)
  + planner + controller + behaviors + navigator, on sim time, shared by the tests of
  a module (CI budget); each test starts with the robot at the world's start, no
  obstacles and no goal on any navigator (the ``world`` fixture).
- ``own_stack``: the same, for one test only (scenarios that kill a service).
- ``bus``: a client of the stack's router in its namespace; ``track`` (the robot's
  pose), ``goals`` (every server's goal states and last result codes), ``tree`` (the
  navigator's tree transitions) and ``world`` (obstacles, resets, navigation goals).
- The velocity smoother and the collision monitor run between the controller/behaviors
  (on ``cmd_vel_nav``) and the base, as ``aiobt up`` runs them by default;
  ``AIOBT_E2E_SAFETY_CHAIN=0`` leaves them out.
- ``AIOBT_E2E_FULL=1`` runs the must-hold scenarios at their issues' full size (ten
  seeded route goals, ten seeded dock poses, every branch's copy of
  odometry_calibration, the across-hosts through-poses and blocked corridor), as the
  issues' figures are measured; without it CI runs a seeded four of each, main's
  calibration tree and the across-hosts goal to a pose, for its time budget.
- ``AIOBT_E2E_KIDNAP=0`` leaves out the kidnapped-robot scenario (``test_kidnap.py``,
  issue 33), run by default.

Readiness is liveliness tokens ({ns}/nodes/<service>) and the navigator's action
servers, never a fixed sleep; every wait is bounded; processes are killed by PID;
the services' output is printed when a test fails.
"""

from __future__ import annotations

import os
from collections.abc import AsyncIterator, Iterator

import pytest

from aiobt.testing.navwatch import RobotTrack, ServerGoals
from aiobt.testing.stack import NavStack, StackConfig, running_stack
from aiobt.testing.treewatch import TreeWatch
from aiobt.transport import Bus, open_bus
from tests.integration.conftest import pytest_runtest_makereport

from .world import ACTIONS, NAVIGATORS, World

__all__ = ["pytest_runtest_makereport"]

SPEED = float(os.environ.get("AIOBT_E2E_SPEED", "4"))
SAFETY_CHAIN = os.environ.get("AIOBT_E2E_SAFETY_CHAIN", "1") != "0"  # smoother + monitor in
FULL = os.environ.get("AIOBT_E2E_FULL", "0") == "1"  # the issues' full-size scenarios
READY_TIMEOUT = 90.0  # wall s for five Python services to import and connect on 2 loaded cores


def _config() -> StackConfig:
    return StackConfig(world="office", speed=SPEED, seed=7, safety_chain=SAFETY_CHAIN)


@pytest.fixture(scope="module")
def _module_stack() -> Iterator[NavStack]:
    with running_stack(_config()) as stack:
        yield stack


@pytest.fixture
def own_stack() -> Iterator[NavStack]:
    with running_stack(_config()) as stack:
        yield stack


@pytest.fixture
def stack(request: pytest.FixtureRequest) -> NavStack:
    """The module's stack, or the test's own if it asks for ``own_stack``."""
    if "own_stack" in request.fixturenames:
        own: NavStack = request.getfixturevalue("own_stack")
        return own
    shared: NavStack = request.getfixturevalue("_module_stack")
    return shared


@pytest.fixture
async def bus(stack: NavStack, request: pytest.FixtureRequest) -> AsyncIterator[Bus]:
    async with open_bus(stack.settings()) as opened:
        try:
            await stack.wait_ready(opened, timeout=READY_TIMEOUT)
            for server in NAVIGATORS:
                if not await opened.presence(opened.keys.action(server).base).wait(READY_TIMEOUT):
                    pytest.fail(f"no {server} server:\n{stack.logs()}")
            yield opened
        finally:
            report = getattr(request.node, "rep_call", None)
            if report is not None and report.failed:
                print(stack.logs())


@pytest.fixture
async def track(bus: Bus) -> AsyncIterator[RobotTrack]:
    watcher = RobotTrack(bus)
    try:
        if await watcher.wait_for(lambda _: True, 20.0) is None:
            pytest.fail("no pose from the robot within 20 s")
        yield watcher
    finally:
        watcher.close()


@pytest.fixture
async def goals(bus: Bus) -> AsyncIterator[ServerGoals]:
    watcher = ServerGoals(bus, ACTIONS)
    try:
        yield watcher
    finally:
        watcher.close()


@pytest.fixture
async def world(bus: Bus, track: RobotTrack, goals: ServerGoals, stack: NavStack) -> World:
    """A clean start: no goal on a navigator, no obstacle, robot at the start (the next
    test of the module starts the same way, whatever this one left)."""
    here = World(bus, track)
    try:
        await here.clear()
    except AssertionError as exc:  # a setup error: pytest shows no teardown output for it
        raise AssertionError(f"{exc}\n{stack.logs()}") from None
    return here


@pytest.fixture
async def tree(bus: Bus) -> AsyncIterator[TreeWatch]:
    watcher = TreeWatch(bus)
    try:
        yield watcher
    finally:
        watcher.close()
