"""What the service leaves undone: the scans of a robot standing still (AMCL weighs
none), and the pose and particle cloud while nobody reads them."""

import math

import numpy as np
import pytest

from aiobt.msgs import PoseStamped, PoseWithCovarianceStamped
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
    assert outputs == ["amcl_pose", "tf", "particle_cloud"]


def test_one_pose_composed_in_floats_is_the_arrays_composition() -> None:
    rng = np.random.default_rng(4)
    for a, b in zip(rng.uniform(-4, 4, (50, 3)), rng.uniform(-4, 4, (50, 3)), strict=True):
        a[2], b[2] = a[2] * math.pi / 4, b[2] * math.pi / 4
        assert se2.compose_one(a, *map(float, b)) == pytest.approx(se2.compose(a, b), abs=1e-12)
