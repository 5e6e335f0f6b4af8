"""The service's message handling without Zenoh: map, odometry, scans, initial
poses (bad ones refused, nothing changed) and the services."""

import math
import threading
from collections.abc import Sequence

import numpy as np
import pytest

from aiobt.msgs import (
    Header,
    LaserScan,
    OccupancyGrid,
    Odometry,
    PoseStamped,
    PoseWithCovarianceStamped,
    pose_fields,
)
from aiobt_services.localization.laser_model import ScanError
from aiobt_services.localization.node import LocalizationNode
from aiobt_services.localization.params import AmclParams

from .maps import RES, cast, room

BEARINGS = -np.pi + 2 * np.pi / 360 * np.arange(360, dtype=np.float64)
CELLS = room()


def _grid() -> OccupancyGrid:
    return OccupancyGrid.from_array(CELLS, RES)


def _odom(stamp: float, x: float, y: float, yaw: float) -> Odometry:
    return Odometry.model_validate(
        {"header": {"stamp": stamp, "frame_id": "odom"}, "pose": pose_fields(x, y, yaw)}
    )


def _scan(stamp: float, truth: tuple[float, float, float], count: int = 360) -> LaserScan:
    ranges = np.nan_to_num(cast(CELLS, truth, BEARINGS), posinf=13.0)[:count]
    return LaserScan(
        header=Header(stamp=stamp, frame_id="base_scan"),
        angle_min=-math.pi, angle_max=math.pi - 2 * math.pi / 360,
        angle_increment=2 * math.pi / 360, range_min=0.05, range_max=12.0,
        ranges=ranges.tolist(),
    )  # fmt: skip


def _topics(out: Sequence[tuple[str, object]]) -> list[str]:
    return [topic for topic, _ in out]


def _node(**params: object) -> LocalizationNode:
    node = LocalizationNode(AmclParams.from_mapping({"random_seed": 1, **params}))
    assert node.on_map(_grid()).ok
    return node


def test_pose_is_the_estimate_composed_with_each_new_odometry() -> None:
    node = _node()
    truth = (1.0, 3.0, 0.5)
    assert node.on_odom(_odom(0.0, 0.0, 0.0, 0.0)) == []  # no estimate yet: no pose
    assert node.on_initialpose(
        PoseWithCovarianceStamped.model_validate({"x": 1.0, "y": 3.0, "yaw": 0.5})
    ).ok
    topics = [t for t, _ in node.on_scan(_scan(0.0, truth))]
    assert topics == ["amcl_pose", "particle_cloud", "tf"]
    # the base moves 0.1 m ahead in odom: pose moves 0.1 m along the estimate's heading
    ((topic, msg),) = node.on_odom(_odom(0.02, 0.1, 0.0, 0.0))
    assert topic == "pose"
    assert isinstance(msg, PoseStamped)
    assert msg.header.stamp == 0.02
    est = node.amcl.last_estimate
    assert est is not None
    assert msg.x == pytest.approx(est.mean[0] + 0.1 * math.cos(est.mean[2]), abs=1e-9)
    assert abs(msg.x - 1.0 - 0.1 * math.cos(0.5)) < 0.1  # and near the truth


def test_bad_initial_poses_are_refused_and_change_nothing() -> None:
    node = _node()
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(1.0, 3.0, 0.0)).ok
    before = node.amcl.particles.copy()
    bad_cov = [0.0] * 36
    bad_cov[0] = bad_cov[7] = 0.1  # yaw variance 0: not positive definite
    refusals = {
        "off the map": PoseWithCovarianceStamped.from_xy_yaw(40.0, 3.0, 0.0),
        "wall": PoseWithCovarianceStamped.from_xy_yaw(0.01, 3.0, 0.0),
        "positive definite": PoseWithCovarianceStamped.from_xy_yaw(1.0, 3.0, 0.0, bad_cov),
        "frame_id": PoseWithCovarianceStamped.from_xy_yaw(1.0, 3.0, 0.0, frame_id="odom"),
    }
    for why, msg in refusals.items():
        reply = node.on_initialpose(msg)
        assert not reply.ok
        assert why in reply.message
    assert np.array_equal(before, node.amcl.particles)


def test_a_scan_whose_ranges_do_not_match_its_angles_is_refused() -> None:
    node = _node()
    node.on_odom(_odom(0.0, 0.0, 0.0, 0.0))
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(1.0, 3.0, 0.0)).ok
    with pytest.raises(ScanError, match="300 ranges"):
        node.on_scan(_scan(0.0, (1.0, 3.0, 0.0), count=300))


def test_without_a_map_poses_and_global_localization_are_refused_with_the_reason() -> None:
    node = LocalizationNode(AmclParams())
    assert (
        "no map yet" in node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(1, 1, 0)).message
    )
    assert "no map yet" in node.reinitialize_global_localization().message
    assert "no pose yet" in node.request_nomotion_update().message


def test_set_initial_pose_parameter_seeds_the_filter_when_the_map_comes() -> None:
    node = LocalizationNode(
        AmclParams.from_mapping({"set_initial_pose": True, "initial_pose": {"x": 1.0, "y": 3.0}})
    )
    assert not node.amcl.initialized
    assert node.on_map(_grid()).ok
    assert node.amcl.initialized
    bad = LocalizationNode(AmclParams.from_mapping({"set_initial_pose": True}))  # (0, 0): a wall
    reply = bad.on_map(_grid())
    assert not reply.ok
    assert "parameter initial_pose" in reply.message


def test_scans_wait_for_odometry_at_their_stamp_and_nomotion_forces_an_update() -> None:
    node = _node()
    truth = (1.0, 3.0, 0.0)
    node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*truth))
    assert node.on_scan(_scan(1.0, truth)) == []  # no odometry yet
    assert node.stats.skipped_no_odom == 1
    node.on_odom(_odom(1.0, 0.0, 0.0, 0.0))
    assert node.on_scan(_scan(1.0, truth))
    assert _topics(node.on_scan(_scan(1.0, truth))) == ["tf"]  # no motion: no update
    assert node.request_nomotion_update().ok
    assert node.on_scan(_scan(1.0, truth))


def test_the_pose_stream_goes_on_while_an_update_holds_the_filter() -> None:
    node = _node()
    assert node.on_initialpose(
        PoseWithCovarianceStamped.model_validate({"x": 1.0, "y": 3.0, "yaw": 0.5})
    ).ok
    job = node.scan_job(_scan(0.0, (1.0, 3.0, 0.5)))
    assert job is None  # no odometry at the scan's stamp yet
    node.on_odom(_odom(0.0, 0.0, 0.0, 0.0))
    job = node.scan_job(_scan(0.0, (1.0, 3.0, 0.5)))
    assert job is not None
    assert node.update(job)  # the first estimate
    holding, release = threading.Event(), threading.Event()

    def long_update() -> None:  # as the service's worker thread, mid-update
        with node.lock:
            holding.set()
            release.wait(3.0)

    worker = threading.Thread(target=long_update)
    worker.start()
    try:
        assert holding.wait(10.0)
        poses = [node.on_odom(_odom(0.02 * i, 0.01 * i, 0.0, 0.0)) for i in range(1, 6)]
        assert all(p and p[0][0] == "pose" for p in poses)
        assert worker.is_alive()  # they came while the update still held the filter
    finally:
        release.set()
        worker.join(10.0)


def test_a_scan_taken_before_an_initial_pose_is_not_weighed_against_it() -> None:
    """The robot carried off (a teleport, a kidnap), then its pose given: a scan still
    queued from before shows the old place; weighed against the new particles it reads
    as a kidnap (and, with recovery on, draws random particles). Scans from the newest
    odometry's stamp on are used; so after a global reset."""
    node = _node()
    old, new = (1.0, 3.0, 0.0), (3.0, 1.0, math.pi / 2)
    node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*old))
    node.on_odom(_odom(1.0, 0.0, 0.0, 0.0))
    node.on_odom(_odom(2.0, 0.0, 0.0, 0.0))
    node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*new))
    assert node.on_scan(_scan(1.5, old)) == []  # taken at the old place, before the pose
    assert node.stats.skipped_before_reset == 1
    assert node.on_scan(_scan(2.0, new))  # from the pose's time on: weighed
    node.on_odom(_odom(3.0, 0.0, 0.0, 0.0))
    assert node.reinitialize_global_localization().ok
    assert _topics(node.on_scan(_scan(2.5, new))) == ["tf"]
    assert node.stats.skipped_before_reset == 2


@pytest.mark.parametrize(
    ("laser_model_type", "step"), [("likelihood_field", 7), ("likelihood_field_prob", 8)]
)
def test_a_scans_beams_are_strided_as_the_laser_model_does(
    laser_model_type: str, step: int
) -> None:
    node = _node(laser_model_type=laser_model_type, max_beams=50)
    node.on_odom(_odom(0.0, 0.0, 0.0, 0.0))
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(1.0, 3.0, 0.0)).ok
    job = node.scan_job(_scan(0.0, (1.0, 3.0, 0.0)))
    assert job is not None
    gaps = np.diff(job.beams.bearings) / (2 * math.pi / 360)
    assert gaps.min() == pytest.approx(step)  # 359 // 49 and ceil(360 / 50)
