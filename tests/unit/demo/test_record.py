"""The demo's record keeps the estimate's and the truth's tracks apart, each thinned, and
how far the estimate was off the truth."""

from __future__ import annotations

import math

import pytest

from aiobt.demo.record import Record
from aiobt.demo.tracking import KEEP
from aiobt.msgs import PoseStamped


def test_the_truth_and_the_estimate_are_two_tracks_each_thinned_to_2_cm() -> None:
    record = Record()
    for step in range(11):  # 1.5 cm apart: every other one kept
        record.on_pose(PoseStamped.from_xy_yaw(step * 0.015, 0.0))
        record.on_truth(PoseStamped.from_xy_yaw(step * 0.015, 1.0))
    assert record.trajectory == [(step * 0.015, 0.0) for step in range(0, 11, 2)]
    assert record.truth == [(step * 0.015, 1.0) for step in range(0, 11, 2)]
    assert record.position == (0.15, 0.0)  # where the estimate says the robot is


def _at(x: float, y: float, stamp: float) -> PoseStamped:
    pose = PoseStamped.from_xy_yaw(x, y, 0.0)
    pose.header.stamp = stamp
    return pose


def test_the_estimate_is_measured_against_the_truth_of_the_same_stamp_in_either_order() -> None:
    record = Record()
    record.on_truth(_at(1.0, 1.0, stamp=0.02))  # the truth first
    record.on_pose(_at(1.03, 1.04, stamp=0.02))  # 5 cm off
    record.on_pose(_at(2.0, 2.0, stamp=0.04))  # the estimate first: no error yet
    assert record.tracking.pairs == 1
    record.on_truth(_at(2.0, 2.0, stamp=0.06))  # another stamp: not paired
    record.on_truth(_at(2.0, 2.0, stamp=0.04))  # on it
    assert record.tracking.pairs == 2
    assert record.tracking.worst == pytest.approx(0.05)
    assert record.tracking.rms == pytest.approx(math.sqrt(0.05**2 / 2))
    assert record.tracking.summary() == "pose estimate off the truth by 3.5 cm RMS, 5.0 cm at worst"


def test_without_a_truth_nothing_is_said_of_the_estimate() -> None:
    record = Record()
    for step in range(300):
        record.on_pose(_at(0.0, 0.0, stamp=step * 0.02))
    assert record.tracking.pairs == 0
    assert record.tracking.summary() == ""
    assert len(record.tracking._estimates) == KEEP  # bounded
