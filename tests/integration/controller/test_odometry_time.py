"""The controller on sim time takes its time from the odometry's stamps, not from
``{ns}/clock``: at 1x its 20 Hz loop keeps its rate on their 20 ms grid."""

from __future__ import annotations

import itertools
import statistics

import pytest

from aiobt.msgs import FollowPath, GoalState, Odometry
from aiobt.msgs import TrackingFeedback as TrackingFeedbackMsg
from aiobt.transport import Bus, BusSettings

from .helpers import Spawn, path_through, start

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(120)]


async def test_at_1x_every_cycle_is_timed_by_an_odometry_stamp_and_the_rate_holds(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    odometry: set[float] = set()
    bus.subscribe("odom", Odometry, lambda msg: odometry.add(msg.header.stamp))
    tracking: list[TrackingFeedbackMsg] = []  # one per cycle, stamped with its now()
    bus.subscribe("tracking_feedback", TrackingFeedbackMsg, tracking.append)
    await start(spawn, bus, bus_settings, "controller", speed="1")
    client = bus.action_client("follow_path", FollowPath)
    path = FollowPath.Goal(path=path_through([(0.0, 0.0), (1.2, 0.0)]))
    goal = await client.send_goal(path, server_timeout=10.0)
    result = await goal.result(timeout=60.0)
    assert goal.status is GoalState.SUCCEEDED, result
    stamps = [t.header.stamp for t in tracking]
    assert len(stamps) > 20
    # the clock's stamps come every 10 ms, the odometry's every 20: each cycle's time is
    # one of the odometry's
    assert [s for s in stamps if s not in odometry] == []
    # 20 Hz on the 20 ms grid: cycles 40 and 60 ms apart, 50 on average
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    assert statistics.median(gaps) == pytest.approx(0.05, abs=0.011)
    assert (stamps[-1] - stamps[0]) / len(gaps) == pytest.approx(0.05, rel=0.03)
