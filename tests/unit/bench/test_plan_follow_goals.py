"""The system bench's seeded goals: free, spaced, the same for the same seed."""

from __future__ import annotations

import math

from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import OFFICE
from bench.system.plan_follow import CLEARANCE, seeded_goals


def test_goals_are_free_spaced_and_seeded() -> None:
    world = load_map(OFFICE)
    goals = seeded_goals(world, 10, seed=1, spacing=3.0)
    assert len(goals) == 10
    assert goals == seeded_goals(world, 10, seed=1, spacing=3.0)
    assert goals != seeded_goals(world, 10, seed=2, spacing=3.0)
    previous = world.start[:2]
    for x, y, yaw in goals:
        assert world.contains(x, y, CLEARANCE)
        assert not world.disc_blocked(x, y, CLEARANCE)
        assert math.hypot(x - previous[0], y - previous[1]) >= 3.0
        assert -math.pi <= yaw <= math.pi
        previous = (x, y)
