"""Nav2's error-code numbers, as the nav2_msgs action files define them."""

from __future__ import annotations

from enum import IntEnum

import pytest

import aiobt.msgs as msgs

EXPECTED: list[tuple[type[IntEnum], str, int]] = [
    (msgs.FollowPathError, "UNKNOWN", 100),
    (msgs.FollowPathError, "INVALID_CONTROLLER", 101),
    (msgs.FollowPathError, "TF_ERROR", 102),
    (msgs.FollowPathError, "INVALID_PATH", 103),
    (msgs.FollowPathError, "PATIENCE_EXCEEDED", 104),
    (msgs.FollowPathError, "FAILED_TO_MAKE_PROGRESS", 105),
    (msgs.FollowPathError, "NO_VALID_CONTROL", 106),
    (msgs.FollowPathError, "CONTROLLER_TIMED_OUT", 107),
    (msgs.ComputePathToPoseError, "UNKNOWN", 200),
    (msgs.ComputePathToPoseError, "INVALID_PLANNER", 201),
    (msgs.ComputePathToPoseError, "GOAL_OCCUPIED", 206),
    (msgs.ComputePathToPoseError, "TIMEOUT", 207),
    (msgs.ComputePathToPoseError, "NO_VALID_PATH", 208),
    (msgs.ComputePathThroughPosesError, "UNKNOWN", 300),
    (msgs.ComputePathThroughPosesError, "NO_VALID_PATH", 308),
    (msgs.ComputePathThroughPosesError, "NO_VIAPOINTS_GIVEN", 309),
    (msgs.SmoothPathError, "UNKNOWN", 500),
    (msgs.SmoothPathError, "INVALID_PATH", 505),
    (msgs.SpinError, "UNKNOWN", 700),
    (msgs.SpinError, "COLLISION_AHEAD", 703),
    (msgs.BackUpError, "UNKNOWN", 710),
    (msgs.BackUpError, "INVALID_INPUT", 713),
    (msgs.BackUpError, "COLLISION_AHEAD", 714),
    (msgs.DriveOnHeadingError, "UNKNOWN", 720),
    (msgs.DriveOnHeadingError, "COLLISION_AHEAD", 723),
    (msgs.DriveOnHeadingError, "INVALID_INPUT", 724),
    (msgs.AssistedTeleopError, "UNKNOWN", 730),
    (msgs.WaitError, "UNKNOWN", 740),
    (msgs.WaitError, "TIMEOUT", 741),
    (msgs.ComputeCoveragePathError, "INVALID_MODE_SET", 802),
    (msgs.NavigateToPoseError, "UNKNOWN", 9000),
    (msgs.NavigateToPoseError, "FAILED_TO_LOAD_BEHAVIOR_TREE", 9001),
    (msgs.NavigateThroughPosesError, "UNKNOWN", 9100),
]


@pytest.mark.parametrize(("table", "name", "code"), EXPECTED)
def test_error_code_numbers(table: type[IntEnum], name: str, code: int) -> None:
    assert table[name] == code
    assert table["NONE"] == 0


def test_every_action_names_its_own_table() -> None:
    actions = [
        value
        for value in vars(msgs).values()
        if isinstance(value, type)
        and issubclass(value, msgs.ActionDef)
        and value is not msgs.ActionDef
    ]
    assert len(actions) == 12
    for action in actions:
        assert action.ErrorCode is getattr(msgs, f"{action.__name__}Error"), action.__name__
        assert action.ErrorCode["NONE"] == 0, action.__name__
    assert int(msgs.ComputePathToPose.ErrorCode.NO_VALID_PATH) == 208
