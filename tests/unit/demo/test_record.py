"""The demo's record keeps the estimate's and the truth's tracks apart, each thinned."""

from __future__ import annotations

from aiobt.demo.record import Record
from aiobt.msgs import PoseStamped


def test_the_truth_and_the_estimate_are_two_tracks_each_thinned_to_2_cm() -> None:
    record = Record()
    for step in range(11):  # 1.5 cm apart: every other one kept
        record.on_pose(PoseStamped.from_xy_yaw(step * 0.015, 0.0))
        record.on_truth(PoseStamped.from_xy_yaw(step * 0.015, 1.0))
    assert record.trajectory == [(step * 0.015, 0.0) for step in range(0, 11, 2)]
    assert record.truth == [(step * 0.015, 1.0) for step in range(0, 11, 2)]
    assert record.position == (0.15, 0.0)  # where the estimate says the robot is
