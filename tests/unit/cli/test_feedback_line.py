"""``aiobt navigate``'s progress line: poses counted down, the newest feedback shown last."""

from __future__ import annotations

import io

from aiobt.cli.feedback_line import FeedbackLine, PassedPoses
from aiobt.display import plural
from aiobt.msgs import NavigateThroughPoses, NavigateToPose, PoseStamped

THROUGH = [(1.0, 1.0), (1.5, -1.0), (0.0, 0.0)]


def through(x: float, y: float, distance: float, navigators_count: int = 3) -> object:
    return NavigateThroughPoses.Feedback(
        current_pose=PoseStamped.from_xy_yaw(x, y, 0.0),
        distance_remaining=distance,
        number_of_poses_remaining=navigators_count,
    )


def test_poses_are_counted_down_in_order_as_the_robot_passes_them() -> None:
    passed = PassedPoses(THROUGH)
    assert passed.update(0.0, 0.0) == 3  # at the last pose, but the first two are ahead
    assert passed.update(1.5, -1.0) == 3  # the second, before the first: not in order
    assert passed.update(1.2, 0.8) == 2
    assert passed.update(1.4, -0.9) == 1
    assert passed.update(0.0, 0.0) == 1  # the last one is left until the goal is reached


def test_the_line_shows_the_lower_of_the_navigators_count_and_the_poses_passed() -> None:
    out = io.StringIO()
    line = FeedbackLine(out, THROUGH)
    line(through(1.1, 1.0, 4.0))  # type: ignore[arg-type]
    assert out.getvalue().splitlines()[-1].endswith("2 poses left")
    assert line.text(through(1.5, -1.0, 2.0, navigators_count=2)).endswith("1 pose left")  # type: ignore[arg-type]


def test_the_newest_feedback_is_shown_at_the_end_when_the_last_line_was_older() -> None:
    out = io.StringIO()
    line = FeedbackLine(out)
    line(NavigateToPose.Feedback(distance_remaining=0.0))  # no path yet: no "0.00 m" line
    assert out.getvalue() == ""
    for distance in (2.0, 1.2, 0.1):  # within a second: only the first is printed at once
        line(NavigateToPose.Feedback(distance_remaining=distance, number_of_recoveries=1))
    assert "2.00 m" in out.getvalue()
    assert "0.10 m" not in out.getvalue()
    line.end()
    last = out.getvalue().splitlines()[-1]
    assert "0.10 m" in last
    assert last.endswith("1 recovery")


def test_plural() -> None:
    assert [plural(n, "recovery") for n in (0, 1, 2)] == [
        "0 recoveries",
        "1 recovery",
        "2 recoveries",
    ]
    assert plural(1, "goal") == "1 goal"
    assert plural(3, "goal") == "3 goals"
    assert plural(2, "day") == "2 days"
