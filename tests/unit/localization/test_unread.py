"""What the service leaves undone: the scans of a robot standing still (AMCL weighs
none), and the pose and particle cloud while nobody reads them."""

import math

import numpy as np
import pytest

from aiobt.msgs import PoseStamped, PoseWithCovarianceStamped, TFMessage
from aiobt.robot.correction import Correction, compose, correction_of
from aiobt_services.localization import se2
from aiobt_services.localization.node import LocalizationNode
from aiobt_services.localization.params import AmclParams

from .test_node import _grid, _odom, _scan

TRUTH = (1.0, 3.0, 0.0)


def _started(readers: set[str]) -> LocalizationNode:
    node = LocalizationNode(
        AmclParams.from_mapping({"random_seed": 1}), wanted=lambda topic: topic in readers
    )
    assert node.on_map(_grid()).ok
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*TRUTH)).ok
    node.on_odom(_odom(1.0, 0.0, 0.0, 0.0))
    return node


def test_standing_still_a_scan_is_not_prepared_until_the_robot_moves() -> None:
    node = _started({"pose"})
    first = node.scan_job(_scan(1.0, TRUTH))
    assert first is not None
    assert node.update(first)  # the first scan since the pose: weighed
    for stamp in (1.1, 1.2):
        node.on_odom(_odom(stamp, 0.0, 0.0, 0.0))
        assert node.scan_job(_scan(stamp, TRUTH)) is None
    assert node.stats.skipped_still == 2
    node.on_odom(_odom(1.3, 0.1, 0.0, 0.0))  # under update_min_d (0.25 m): still nothing
    assert node.scan_job(_scan(1.3, TRUTH)) is None
    node.on_odom(_odom(1.4, 0.3, 0.0, 0.0))  # past it: the scan goes to the filter
    moved = node.scan_job(_scan(1.4, (1.3, 3.0, 0.0)))
    assert moved is not None
    assert node.update(moved)
    assert node.stats.updates == 2
    assert node.scan_job(_scan(1.4, (1.3, 3.0, 0.0))) is None
    assert node.request_nomotion_update().ok  # asked: the next scan is weighed anyway
    assert node.scan_job(_scan(1.4, (1.3, 3.0, 0.0))) is not None
    assert node.stats.skipped_still == 4


@pytest.mark.parametrize("turn", [0.1, 0.25])
def test_a_turn_in_place_past_update_min_a_is_motion(turn: float) -> None:
    node = _started(set())
    first = node.scan_job(_scan(1.0, TRUTH))
    assert first is not None
    node.update(first)
    node.on_odom(_odom(1.1, 0.0, 0.0, turn))  # update_min_a: 0.2 rad
    wanted = node.scan_job(_scan(1.1, (1.0, 3.0, turn))) is not None
    assert wanted == (turn > 0.2)


def test_pose_and_cloud_are_built_only_for_a_reader() -> None:
    readers: set[str] = set()
    node = _started(readers)
    assert [t for t, _ in node.on_scan(_scan(1.0, TRUTH))] == ["amcl_pose", "tf"]
    assert node.on_odom(_odom(1.02, 0.0, 0.0, 0.0)) == []
    readers.update({"pose", "particle_cloud"})
    ((topic, pose),) = node.on_odom(_odom(1.04, 0.0, 0.0, 0.0))
    assert topic == "pose"
    assert isinstance(pose, PoseStamped)
    assert pose.header.stamp == 1.04
    node.on_odom(_odom(1.1, 0.3, 0.0, 0.0))
    outputs = [t for t, _ in node.on_scan(_scan(1.1, (1.3, 3.0, 0.0)))]
    assert outputs == ["amcl_pose", "particle_cloud", "tf"]


def test_one_pose_composed_in_floats_is_the_arrays_composition() -> None:
    rng = np.random.default_rng(4)
    for a, b in zip(rng.uniform(-4, 4, (50, 3)), rng.uniform(-4, 4, (50, 3)), strict=True):
        a[2], b[2] = a[2] * math.pi / 4, b[2] * math.pi / 4
        one = compose((float(a[0]), float(a[1]), float(a[2])), *map(float, b))
        assert one == pytest.approx(se2.compose(a, b), abs=1e-12)


def test_a_reader_composing_odometry_with_the_sent_correction_has_localizations_pose() -> None:
    """The correction comes with every scan (still or not, as AMCL republishes), stamped
    as the scan; a reader composing each odometry with the newest one it read back from
    the wire has ``pose`` exactly (to float rounding)."""
    node = _started({"pose"})
    held: Correction | None = None
    track = [(1.02 + 0.02 * i, 0.012 * i, 0.004 * i, 0.01 * i) for i in range(60)]
    for i, (stamp, x, y, yaw) in enumerate(track):
        msg = _odom(stamp, x, y, yaw)
        poses = [m for t, m in node.on_odom(msg) if t == "pose"]
        assert (held is None) == (not poses)  # neither has a pose before the first update
        if held is not None:
            (pose,) = poses
            assert isinstance(pose, PoseStamped)
            mine = compose(held.transform, msg.pose.position.x, msg.pose.position.y, msg.pose.yaw)
            assert mine == pytest.approx((pose.x, pose.y, pose.yaw), abs=1e-12)
        if i % 5 == 4:  # a scan every 0.1 s, the robot still for the first ones
            sent = dict(node.on_scan(_scan(stamp, (TRUTH[0] + x, TRUTH[1] + y, yaw))))
            wire = TFMessage.model_validate_json(sent["tf"].model_dump_json())
            held = correction_of(wire)
            assert held is not None
            assert held.stamp == stamp
    assert node.stats.skipped_still >= 1
    assert node.stats.updates >= 2


def test_no_correction_before_a_pose_or_with_tf_broadcast_off() -> None:
    node = LocalizationNode(AmclParams.from_mapping({"random_seed": 1}))
    assert node.on_map(_grid()).ok
    assert node.on_scan(_scan(1.0, TRUTH)) == []  # no pose yet: nothing to correct with
    quiet = LocalizationNode(AmclParams.from_mapping({"random_seed": 1, "tf_broadcast": False}))
    assert quiet.on_map(_grid()).ok
    assert quiet.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*TRUTH)).ok
    quiet.on_odom(_odom(1.0, 0.0, 0.0, 0.0))
    assert "tf" not in dict(quiet.on_scan(_scan(1.0, TRUTH)))
