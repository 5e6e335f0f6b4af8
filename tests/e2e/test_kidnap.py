"""The kidnapped robot (issue 33): moved 3 m mid-goal by the simulation, localization
not told.

The robot drives east along the corridor towards the south middle room; at x 5 the
simulation carries it 3 m south, through the wall, into the west room. The filter
still places it in the corridor. Either the filter finds it by itself (its random
particles: this module's stack turns recovery on, behind the long-beam gate;
sim_robot.yaml ships it off), or the controller, following its path where the robot
is not, makes no progress and the navigator's recoveries run: with the relocalizing
tree (trees/navigate_to_pose_w_relocalization_and_recovery.xml) one of them
reinitializes global localization and turns once on the spot in 42 steps of 0.15
rad, still for 1 s after each, and the round wraps around if the robot is still
lost (a turn can settle on a look-alike place: the west room is nearly
point-symmetric). Required: the estimate back on the robot (within 0.25 m of the
truth) by the end, a clear result, no bump.

Run by default since it passed ten e2e runs in a row (2026-11-29, c5852d2);
``AIOBT_E2E_KIDNAP=0`` leaves it out.
"""

from __future__ import annotations

import asyncio
import math
import os
from collections.abc import Iterator
from pathlib import Path

import pytest

from aiobt.msgs import GoalState, PoseStamped
from aiobt.msgs.sim import Ack, BumperEvent
from aiobt.testing.navwatch import Sample
from aiobt.testing.stack import NavStack, StackConfig, running_stack
from aiobt.testing.treewatch import TreeWatch
from aiobt.transport import Bus
from aiobt.transport.keys import SIM_POSE

from .conftest import SAFETY_CHAIN, SPEED
from .world import World

KIDNAP = os.environ.get("AIOBT_E2E_KIDNAP", "1") != "0"
pytestmark = [
    pytest.mark.e2e,
    pytest.mark.timeout(420),
    pytest.mark.skipif(not KIDNAP, reason="AIOBT_E2E_KIDNAP=0 leaves it out"),
]

TREES = Path(__file__).resolve().parents[2] / "trees"
TREE = TREES / "navigate_to_pose_w_relocalization_and_recovery.xml"
SOUTH_MIDDLE_ROOM = (10.0, 6.0, 0.0)
KIDNAP_AT_X = 5.0  # m along the corridor (y 9.75)
KIDNAPPED_TO = (5.0, 6.75, 0.0)  # 3 m south: the west room, through the corridor's wall
FOUND = 0.25  # m between estimate and truth: the filter has the robot again
BY_THE_FILTER = 30.0  # sim s: issue 33's bound for the filter alone
# the filter's recovery, as bench.localization.kidnap measures it; sim_robot.yaml ships it off
RECOVERY = ("recovery_alpha_slow=0.05", "recovery_alpha_fast=0.5",
            "recovery_reset_after_injection=false", "recovery_min_long_beams=0.05")  # fmt: skip
RESET_POSE = "reset_pose"  # the simulation's teleport, {ns}/sim/srv/reset_pose


@pytest.fixture(scope="module")
def _module_stack() -> Iterator[NavStack]:
    """The module's stack with the filter's recovery on (issue 33: "with recovery
    enabled"), the rest as every e2e module's."""
    flags = [flag for name in RECOVERY for flag in ("--set", name)]
    config = StackConfig(world="office", speed=SPEED, seed=7, safety_chain=SAFETY_CHAIN,
                         extra={"localization": flags})  # fmt: skip
    with running_stack(config) as stack:
        yield stack


async def carry_off(world: World, x: float, y: float, yaw: float) -> None:
    """The robot moved by the simulation alone, localization not told (World.teleport
    tells it: not that)."""
    pose = PoseStamped.from_xy_yaw(x, y, yaw)
    ack = await world.bus.call(RESET_POSE, pose, Ack, timeout=10.0, namespace=world.sim)
    assert ack.ok, f"sim/srv/{RESET_POSE}: {ack.message}"


RECOVERIES = ("ClearingActions", "Relocalize", "Spin", "Wait", "BackUp")
SAMPLE_EVERY = 5.0  # sim s


async def _sample_errors(bus: Bus, world: World, since: float, into: list[str]) -> None:
    """The estimate's distance from the truth every SAMPLE_EVERY sim s after ``since``."""
    truth = bus.subscribe(SIM_POSE, PoseStamped, queue_size=1)
    try:
        async for here in truth:
            estimate = world.track.latest
            if estimate is not None and here.header.stamp >= since + SAMPLE_EVERY * len(into):
                into.append(f"{math.hypot(estimate.x - here.x, estimate.y - here.y):.2f}")
    finally:
        truth.close()


class Pressed:
    """Every bumper press while it is open."""

    def __init__(self, bus: Bus) -> None:
        self.events: list[BumperEvent] = []
        self._sub = bus.subscribe("bumper", BumperEvent, callback=self._on)

    def _on(self, event: BumperEvent) -> None:
        if event.pressed:
            self.events.append(event)

    def close(self) -> None:
        self._sub.close()


@pytest.fixture
def pressed(bus: Bus) -> Iterator[Pressed]:
    watcher = Pressed(bus)
    try:
        yield watcher
    finally:
        watcher.close()


async def test_a_kidnapped_robot_is_found_again_and_the_goal_ends_clearly(
    world: World, bus: Bus, tree: TreeWatch, pressed: Pressed
) -> None:
    truth = bus.subscribe(SIM_POSE, PoseStamped, queue_size=1)
    running = await world.start(*SOUTH_MIDDLE_ROOM, tree=str(TREE))
    try:
        async with asyncio.timeout(60.0):
            async for pose in truth:
                if pose.x >= KIDNAP_AT_X:
                    break
    except TimeoutError:
        pytest.fail(f"the robot never reached x {KIDNAP_AT_X} in the corridor within 60 s")
    await carry_off(world, *KIDNAPPED_TO)
    try:
        async with asyncio.timeout(10.0):
            async for pose in truth:
                if math.dist((pose.x, pose.y), KIDNAPPED_TO[:2]) < 0.5:
                    break
    except TimeoutError:
        pytest.fail(f"the truth never showed the robot near {KIDNAPPED_TO} within 10 s")
    kidnapped = pose.header.stamp

    def found(sample: Sample) -> bool:  # the estimate on the truth again, after the jump
        here = truth.latest
        return (here is not None and here.header.stamp > kidnapped
                and math.hypot(sample.x - here.x, sample.y - here.y) < FOUND)  # fmt: skip

    back = asyncio.create_task(world.track.wait_for(found, 300.0))
    errors: list[str] = []
    sampling = asyncio.create_task(_sample_errors(bus, world, kidnapped, errors))
    done = await running.end(300.0)
    back.cancel()
    sampling.cancel()
    first_back = back.result() if back.done() and not back.cancelled() else None

    here, estimate = truth.latest, world.track.latest
    assert here is not None
    assert estimate is not None
    off = math.hypot(estimate.x - here.x, estimate.y - here.y)
    relocalized = tree.activations(("ReinitializeGlobalLocalization",))
    after = "never" if first_back is None else f"{first_back.stamp - kidnapped:.1f} sim s"
    summary = (f"{done.state.name} {done.result.error_code} {done.result.error_msg!r}; truth "
               f"({here.x:.2f}, {here.y:.2f}), estimate ({estimate.x:.2f}, {estimate.y:.2f}); "
               f"first back after {after}; relocalized {len(relocalized)}x; "
               f"{done.recoveries} recoveries: {' '.join(tree.activations(RECOVERIES))}; "
               f"error every {SAMPLE_EVERY:.0f} sim s: {' '.join(errors)}")  # fmt: skip
    print(summary)
    assert not pressed.events, f"bumped: {pressed.events}; {summary}"
    assert off < FOUND, f"the estimate is {off:.2f} m off the truth at the end: {summary}"
    by_the_filter = first_back is not None and first_back.stamp - kidnapped <= BY_THE_FILTER
    assert by_the_filter or relocalized, f"found neither by the filter nor the tree: {summary}"
    assert done.state in (GoalState.SUCCEEDED, GoalState.ABORTED), summary
    if done.state is GoalState.SUCCEEDED:
        goal_x, goal_y, _ = SOUTH_MIDDLE_ROOM
        assert math.hypot(here.x - goal_x, here.y - goal_y) < 0.25 + FOUND, summary
    else:  # a clear failure: Nav2's code and why
        assert done.result.error_code, summary
        assert done.result.error_msg, summary
