"""The localization bench's error figures: estimate and truth matched by stamp."""

import math

from aiobt.msgs import PoseStamped
from bench.localization.stack import LocalizedStackConfig
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


def test_the_stack_runs_localization_and_a_robot_without_a_pose_in_map() -> None:
    config = LocalizedStackConfig(localization=["--params-file", "sim_robot"])
    robot = config.command("robot", "tcp/127.0.0.1:1", "ns")
    loc = config.command("localization", "tcp/127.0.0.1:1", "ns")
    assert robot[-2:] == ["--pose-source", "none"]
    assert loc[:2] == ["-m", "aiobt_services.localization"]
    assert loc[-2:] == ["--params-file", "sim_robot"]
    assert "set_initial_pose=true" in loc
    assert config.services.index("robot") < config.services.index("localization")
