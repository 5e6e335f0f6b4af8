"""The whole stack at --speed 10: robot, planner, controller and behaviors as processes;
seeded goals planned and followed one after another all arrive.

The full figure (10 goals) is ``python -m bench.system.plan_follow``; this runs three.
The machine may not reach 10x; the achieved speed-up is printed with the outcomes.
"""

from __future__ import annotations

import asyncio
import time

import pytest

from aiobt.transport import Bus, BusSettings
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import OFFICE
from bench.system.plan_follow import Tracker, plan_and_follow, seeded_goals, stack_commands, wait_up

from .helpers import Spawn

pytestmark = [pytest.mark.integration, pytest.mark.e2e]


@pytest.mark.timeout(300)
async def test_three_seeded_goals_arrive_at_10x(spawn: Spawn, bus: Bus, bus_settings: BusSettings):
    tracker = Tracker(bus)
    commands = stack_commands(bus_settings.connect[0], bus_settings.namespace, "10")
    procs = {name: spawn(args) for name, args in commands.items()}
    missing = await wait_up(bus, list(procs))
    assert not missing, procs[missing[0]].output()
    await asyncio.wait_for(tracker.first_pose.wait(), 30.0)
    goals = seeded_goals(load_map(OFFICE), 3, seed=7)
    sim0, wall0 = tracker.time, time.monotonic()
    outcomes = [await plan_and_follow(bus, tracker, goal, patience=120.0) for goal in goals]
    achieved = (tracker.time - sim0) / (time.monotonic() - wall0)
    print(f"x{achieved:.1f} achieved: {outcomes}")
    assert all(o.arrived for o in outcomes), outcomes
