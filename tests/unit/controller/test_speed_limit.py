"""Nav2's speed limit as the controllers apply it (``setSpeedLimit``), and a goal that
takes a limit mid-way or switches controller under one."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D, Velocity
from aiobt.robot.freshness import FRESH
from aiobt.robot.state import RobotState
from aiobt_services.controller.base import ControlContext
from aiobt_services.controller.dwb import DWBController, DWBParams
from aiobt_services.controller.rpp import RegulatedPurePursuit, RPPParams
from aiobt_services.controller.session import ControllerConfig, FollowPathSession, FollowRequest
from aiobt_services.controller.speed_limit import NONE, SpeedLimit

from .courses import straight

CTX = ControlContext(dt=0.05, goal_xy_tolerance=0.25, collision=None)
START = Pose2D(0.0, 0.0, 0.0)
CRUISING = Velocity(0.5, 0.0)


def _rpp_speed(limit: SpeedLimit) -> float:
    rpp = RegulatedPurePursuit(RPPParams(desired_linear_vel=0.5))
    rpp.set_plan(straight(6.0))
    rpp.set_speed_limit(limit)
    return rpp.compute_velocity(START, CRUISING, CTX).v


@pytest.mark.parametrize(
    ("limit", "expected"),
    [
        (NONE, 0.5),
        (SpeedLimit(50.0, percentage=True), 0.25),
        (SpeedLimit(0.3, percentage=False), 0.3),
        (SpeedLimit(0.8, percentage=False), 0.8),  # RPP takes an absolute limit as it is
    ],
)
def test_rpp_cruises_at_the_limit(limit: SpeedLimit, expected: float) -> None:
    assert _rpp_speed(limit) == pytest.approx(expected)


def test_rpp_limit_lifted_restores_the_configured_speed() -> None:
    rpp = RegulatedPurePursuit(RPPParams(desired_linear_vel=0.5))
    rpp.set_plan(straight(6.0))
    rpp.set_speed_limit(SpeedLimit(20.0))
    rpp.set_speed_limit(SpeedLimit(50.0))  # from the configured speed, not the last limit
    assert rpp.compute_velocity(START, CRUISING, CTX).v == pytest.approx(0.25)
    rpp.set_speed_limit(NONE)
    assert rpp.compute_velocity(START, CRUISING, CTX).v == pytest.approx(0.5)


@pytest.mark.parametrize(
    ("limit", "ratio"),
    [
        (NONE, 1.0),
        (SpeedLimit(40.0), 0.4),
        (SpeedLimit(0.25, percentage=False), 0.5),
        (SpeedLimit(0.9, percentage=False), 1.0),  # above the maximum: DWB keeps its own
    ],
)
def test_dwb_scales_its_velocity_limits_together(limit: SpeedLimit, ratio: float) -> None:
    dwb = DWBController(DWBParams(max_vel_x=0.5, max_vel_theta=1.8))
    dwb.set_speed_limit(limit)
    assert (dwb.params.max_vel_x, dwb.params.max_vel_theta) == pytest.approx(
        (0.5 * ratio, 1.8 * ratio)
    )
    dwb.set_plan(straight(6.0))
    cmd = dwb.compute_velocity(START, CRUISING, CTX)
    assert 0.0 < cmd.v <= 0.5 * ratio + 1e-9
    assert abs(cmd.w) <= 1.8 * ratio + 1e-9


@pytest.mark.parametrize("bad", [-1.0, math.nan])
def test_a_negative_or_nan_limit_is_refused(bad: float) -> None:
    with pytest.raises(ValueError, match="speed_limit must be >= 0"):
        SpeedLimit(bad)


def _state() -> dict[str, RobotState]:
    return {"map": RobotState(START, CRUISING, 0.0, FRESH)}


def test_a_goal_obeys_a_limit_set_mid_way_and_keeps_it_for_the_next_controller() -> None:
    session = FollowPathSession(FollowRequest(straight(6.0)), ControllerConfig(), 0.0, None)
    assert session.step(0.0, _state()).cmd.v == pytest.approx(0.5)
    session.set_speed_limit(SpeedLimit(50.0))
    assert session.step(0.05, _state()).cmd.v == pytest.approx(0.25)
    session.replace(FollowRequest(straight(6.0), controller_id="DWB"), 0.1)
    assert 0.0 < session.step(0.1, _state()).cmd.v <= 0.25 + 1e-9


def test_a_new_goal_starts_under_the_limit_in_force() -> None:
    session = FollowPathSession(
        FollowRequest(straight(6.0)), ControllerConfig(), 0.0, None, SpeedLimit(0.2, False)
    )
    assert session.step(0.0, _state()).cmd.v == pytest.approx(0.2)
