"""The localization bench's error figures: estimate and truth matched by stamp."""

import math

from aiobt.msgs import PoseStamped
from bench.localization.nav_track import config
from bench.localization.tracking import Tracking


def _pose(stamp: float, x: float, yaw: float = 0.0) -> PoseStamped:
    return PoseStamped.from_xy_yaw(x, 0.0, yaw, stamp=stamp)


def test_errors_pair_estimates_with_the_truth_of_the_same_stamp() -> None:
    tracking = Tracking()
    for i in range(100):
        tracking._truth(_pose(0.02 * i, 0.0, math.pi - 0.001))
        if i % 2 == 0:  # half the stamps only: the others are not paired
            tracking._estimate(_pose(0.02 * i, 0.03 if i else 0.3, -math.pi + 0.001))
    errors = tracking.errors()
    assert errors.count == 50
    assert errors.worst == 0.3
    assert abs(errors.rms - math.sqrt((49 * 0.03**2 + 0.3**2) / 50)) < 1e-9
    assert errors.heading_rms_deg < 0.2  # across +-pi: 0.002 rad, not 2 pi


def test_the_stack_runs_localization_with_the_params_asked_for() -> None:
    stack = config(speed=4.0, seed=3, params="nav2", sets=["max_beams=30"])
    robot = stack.command("robot", "tcp/127.0.0.1:1", "ns")
    loc = stack.command("localization", "tcp/127.0.0.1:1", "ns")
    assert "--pose-source" not in robot  # its default: no pose in map
    assert loc[-4:] == ["--params-file", "nav2", "--set", "max_beams=30"]  # after the defaults
    assert "initial_pose={x: 2, y: 9.75, yaw: 0}" in loc
    assert stack.services.index("robot") < stack.services.index("localization")


def test_realtime_raises_localization_with_the_others_and_keeps_its_params() -> None:
    stack = config(speed=10.0, seed=1, params="sim_robot", sets=[], realtime=True)
    loc = stack.command("localization", "tcp/127.0.0.1:1", "ns")
    assert "--realtime-priority" in loc
    assert loc[-2:] == ["--params-file", "sim_robot"]
    assert "--realtime-priority" in stack.command("robot", "tcp/127.0.0.1:1", "ns")
    assert "--realtime-priority" not in config(10.0, 1, "sim_robot", []).command(
        "localization", "tcp/127.0.0.1:1", "ns"
    )
