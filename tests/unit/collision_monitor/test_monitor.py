"""Nav2's collision_monitor_node_test scenarios, on the pure logic."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt_services.collision_monitor.monitor import INVALID_SOURCE
from aiobt_services.collision_monitor.sources import OdomHistory, shift

from .nav2_setup import (
    ANGULAR_LIMIT,
    LINEAR_LIMIT,
    SIMULATION_TIME_STEP,
    SLOWDOWN_RATIO,
    SOURCE_TIMEOUT,
    STOP_PUB_TIMEOUT,
    TIME_BEFORE_COLLISION,
    give_scan,
    monitor,
    points_at,
    polygon,
)

CMD = (0.5, 0.2, 0.1)


def nested() -> dict[str, dict[str, object]]:
    return {
        "Limit": polygon("polygon", 3.0, "limit"),
        "SlowDown": polygon("polygon", 2.0, "slowdown"),
        "Stop": polygon("polygon", 1.0, "stop"),
    }


def test_stop_slowdown_limit_by_where_the_obstacle_is() -> None:
    cm = monitor(nested())
    give_scan(cm, 4.5, 0.0)
    assert cm.process(CMD, 0.0).velocity == pytest.approx(CMD)
    give_scan(cm, 3.0, 0.1)
    action = cm.process(CMD, 0.1)
    ratio = min(LINEAR_LIMIT / math.hypot(0.5, 0.2), ANGULAR_LIMIT / 0.1)
    assert (action.action_type, action.polygon_name) == ("limit", "Limit")
    assert action.velocity == pytest.approx(tuple(v * ratio for v in CMD))
    give_scan(cm, 1.5, 0.2)
    action = cm.process(CMD, 0.2)
    assert (action.action_type, action.polygon_name) == ("slowdown", "SlowDown")
    assert action.velocity == pytest.approx(tuple(v * SLOWDOWN_RATIO for v in CMD))
    give_scan(cm, 0.5, 0.3)
    action = cm.process(CMD, 0.3)
    assert (action.action_type, action.polygon_name, action.velocity) == ("stop", "Stop", (0, 0, 0))
    assert "points in 'Stop'" in action.reason
    give_scan(cm, 4.5, 0.4)
    action = cm.process(CMD, 0.4)
    assert (action.action_type, action.polygon_name) == ("none", "")
    assert action.velocity == pytest.approx(CMD)


def test_approach_keeps_time_before_collision() -> None:
    cm = monitor({"Approach": polygon("circle", 1.0, "approach")})
    cmd = (0.5, 0.2, 0.0)
    give_scan(cm, 3.0, 0.0)
    assert cm.process(cmd, 0.0).velocity == pytest.approx(cmd)
    give_scan(cm, 1.2, 0.1)  # 0.2 m ahead of the footprint
    action = cm.process(cmd, 0.1)
    ratio = (0.2 / math.hypot(0.5, 0.2)) / TIME_BEFORE_COLLISION
    tolerance = SIMULATION_TIME_STEP / TIME_BEFORE_COLLISION
    assert (action.action_type, action.polygon_name) == ("approach", "Approach")
    assert action.velocity[0] == pytest.approx(0.5 * ratio, abs=0.5 * tolerance)
    assert action.velocity[1] == pytest.approx(0.2 * ratio, abs=0.2 * tolerance)
    give_scan(cm, 0.5, 0.2)  # inside the footprint: whatever the command, it stops
    assert cm.process((1e9, 0.2, 0.0), 0.2).velocity == pytest.approx((0.0, 0.0, 0.0))
    give_scan(cm, 3.0, 0.3)
    assert cm.process(cmd, 0.3).action_type == "none"


def test_approach_sees_a_turn_coming() -> None:
    """Turning in place towards a point beside the footprint: the collision is found
    only along the turned path (Nav2's testProcessApproachRotation, in spirit)."""
    long = "[[1.0, 0.2], [1.0, -0.2], [-1.0, -0.2], [-1.0, 0.2]]"
    cm = monitor({"Approach": polygon("polygon", 0.0, "approach", points=long, min_points=1)})
    cm.sources["Scan"].take(points_at((0.0, 0.75)), 0.0, 0.0)
    assert cm.process((0.0, 0.0, 0.0), 0.0).action_type == "none"
    action = cm.process((0.0, 0.0, 2.0), 0.0)
    assert action.action_type == "approach"
    # inside once 0.75 cos(2 t) < 0.2: t = acos(0.2 / 0.75) / 2 = 0.65 s of 1 s
    assert action.velocity[2] == pytest.approx(2.0 * 0.65, abs=2.0 * SIMULATION_TIME_STEP)


def test_a_stop_is_sent_for_stop_pub_timeout_then_nothing() -> None:
    cm = monitor({
        "Stop": polygon("polygon", 1.0, "stop"),
        "Approach": polygon("circle", 2.0, "approach"),
    })  # fmt: skip
    give_scan(cm, 1.5, 0.0)
    first = cm.process(CMD, 0.0)
    assert (first.action_type, first.velocity, first.publish) == ("approach", (0, 0, 0), True)
    assert not cm.process(CMD, STOP_PUB_TIMEOUT + 0.01).publish
    give_scan(cm, 3.0, 0.2)
    assert cm.process(CMD, 0.2).velocity == pytest.approx(CMD)
    give_scan(cm, 0.5, 0.3)
    assert cm.process(CMD, 0.3).publish
    assert cm.process(CMD, 0.35).publish  # within stop_pub_timeout
    assert not cm.process(CMD, 0.3 + STOP_PUB_TIMEOUT + 0.01).publish


def test_a_disabled_polygon_does_nothing() -> None:
    cm = monitor({"Stop": polygon("polygon", 1.0, "stop", enabled=False)})
    give_scan(cm, 0.5, 0.0)
    assert cm.process(CMD, 0.0).velocity == pytest.approx(CMD)


def test_a_disabled_source_is_not_looked_at() -> None:
    cm = monitor({"Stop": polygon("polygon", 1.0, "stop")})
    cm.sources["Scan"].params = type(cm.sources["Scan"].params)(name="Scan", enabled=False)
    give_scan(cm, 0.5, 0.0)
    assert cm.process(CMD, 0.0).velocity == pytest.approx(CMD)


def test_stale_or_missing_data_stops_the_robot_naming_the_source() -> None:
    cm = monitor(nested())
    missing = cm.process(CMD, 0.0)
    assert (missing.action_type, missing.polygon_name) == ("stop", INVALID_SOURCE)
    assert "'Scan' has sent nothing" in missing.reason
    give_scan(cm, 4.5, 1.0)
    assert cm.process(CMD, 1.0 + SOURCE_TIMEOUT).velocity == pytest.approx(CMD)
    stale = cm.process(CMD, 1.0 + SOURCE_TIMEOUT + 0.01)
    assert stale.velocity == (0.0, 0.0, 0.0)
    assert "'Scan' is 5.01 s old (source_timeout 5 s)" in stale.reason


def test_source_timeout_zero_never_goes_stale() -> None:
    cm = monitor(nested(), source_timeout=0.0)
    give_scan(cm, 4.5, 0.0)
    assert cm.process(CMD, 1000.0).velocity == pytest.approx(CMD)
    assert cm.stale_at() == math.inf


def test_stale_at_is_the_newest_data_plus_its_timeout() -> None:
    cm = monitor(nested())
    assert cm.stale_at() == math.inf  # nothing yet: process() stops for that itself
    give_scan(cm, 4.5, 1.0)
    assert cm.stale_at() == 1.0 + SOURCE_TIMEOUT
    assert cm.process(CMD, cm.stale_at()).velocity == pytest.approx(CMD)
    assert cm.process(CMD, cm.stale_at() + 1e-6).velocity == (0.0, 0.0, 0.0)


def test_data_far_ahead_of_the_robots_time_stops_as_stale_odometry() -> None:
    cm = monitor(nested())
    cm.robot_time = True  # ages by the data's stamps against now, the odometry's time
    give_scan(cm, 4.5, 10.0)
    assert cm.process(CMD, 10.0 - SOURCE_TIMEOUT).velocity == pytest.approx(CMD)
    ahead = cm.process(CMD, 10.0 - SOURCE_TIMEOUT - 0.01)
    assert (ahead.action_type, ahead.polygon_name) == ("stop", INVALID_SOURCE)
    assert "'Scan' is 5.01 s ahead of the robot's time" in ahead.reason


def test_toggled_off_the_polygons_rest_but_a_bad_source_still_stops() -> None:
    cm = monitor(nested())
    give_scan(cm, 0.5, 0.0)
    assert cm.toggle(False) == "Collision monitor toggled off successfully"
    assert cm.process(CMD, 0.0).velocity == pytest.approx(CMD)
    assert cm.process(CMD, 10.0).polygon_name == INVALID_SOURCE  # Nav2 checks sources anyway
    assert cm.toggle(True) == "Collision monitor toggled on successfully"
    give_scan(cm, 0.5, 10.0)
    assert cm.process(CMD, 10.0).action_type == "stop"


def test_a_polygon_watches_only_its_sources() -> None:
    polygons = {
        "StopOnRange": polygon("polygon", 1.0, "stop", sources_names=["Range"]),
        "SlowdownOnAll": polygon("polygon", 1.0, "slowdown"),
    }
    cm = monitor(polygons, observation_sources=["Scan", "Range"],
                 Range={"type": "scan", "topic": "range"})  # fmt: skip
    give_scan(cm, 0.5, 0.0)
    give_scan(cm, 5.0, 0.0, source="Range")
    assert cm.process(CMD, 0.0).action_type == "slowdown"
    give_scan(cm, 0.5, 0.1, source="Range")
    assert cm.process(CMD, 0.1).polygon_name == "StopOnRange"


def test_min_points_and_the_consecutive_cycle_debounce() -> None:
    debounce = {"trigger_consecutive_points": 2, "release_consecutive_points": 2}
    cm = monitor({"Stop": polygon("polygon", 1.0, "stop", min_points=3, **debounce)})
    two = points_at((0.5, 0.0), (0.6, 0.0))
    three = points_at((0.5, 0.0), (0.6, 0.0), (0.7, 0.0))
    cm.sources["Scan"].take(two, 0.0, 0.0)
    assert cm.process(CMD, 0.0).action_type == "none"
    cm.sources["Scan"].take(three, 0.1, 0.1)
    assert cm.process(CMD, 0.1).action_type == "none"  # one cycle: not yet
    assert cm.process(CMD, 0.15).action_type == "stop"
    cm.sources["Scan"].take(two, 0.2, 0.2)
    assert cm.process(CMD, 0.2).action_type == "stop"  # one clear cycle: still
    assert cm.process(CMD, 0.25).action_type == "none"


def test_base_shift_correction_moves_old_points_by_odometry() -> None:
    cm = monitor({"Stop": polygon("polygon", 0.3, "stop", min_points=1)},
                 base_shift_correction=True)  # fmt: skip
    assert cm.odom is not None
    cm.sources["Scan"].take(points_at((0.5, 0.0)), 1.0, 1.0)  # 0.5 m ahead at t=1
    assert "no odometry" in cm.process(CMD, 1.0).reason
    cm.odom.add(1.0, 0.0, 0.0, 0.0)
    cm.odom.add(1.4, 0.3, 0.0, 0.0)  # moved 0.3 m on since: the point is 0.2 m ahead now
    assert cm.process(CMD, 1.4).action_type == "stop"


def test_shift_turns_and_moves_points_into_the_base_frame_now() -> None:
    seen = points_at((0.5, 0.0), (0.0, 0.5))
    moved = shift(seen, (0.0, 0.0, 0.0), (0.0, 0.0, math.pi / 2))  # turned left in place
    assert moved == pytest.approx(np.array([[0.0, -0.5], [0.5, 0.0]]))
    moved = shift(seen, (1.0, 1.0, math.pi), (1.5, 1.0, math.pi))  # reversed 0.5 m
    assert moved == pytest.approx(np.array([[1.0, 0.0], [0.5, 0.5]]))


def test_odometry_is_interpolated_at_a_stamp_across_the_yaw_wrap() -> None:
    history = OdomHistory()
    history.add(1.0, 0.0, 0.0, math.pi - 0.1)
    history.add(1.1, 0.1, 0.2, -math.pi + 0.1)  # turned left 0.2 rad through +-pi
    x, y, yaw = history.pose_at(1.05)
    assert (x, y) == pytest.approx((0.05, 0.1))
    assert math.remainder(yaw - math.pi, math.tau) == pytest.approx(0.0, abs=1e-9)
    assert history.pose_at(0.5) == history.pose_at(1.0)  # before the history: its start
    assert history.pose_at(9.0) == history.latest()
    history.add(5.0, 1.0, 1.0, 0.0)  # more than ODOM_HISTORY later: the old ones go
    assert history.pose_at(1.05) == (1.0, 1.0, 0.0)
