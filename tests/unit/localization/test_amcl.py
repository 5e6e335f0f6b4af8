"""The filter on a small room: tracking under odometry error, update gating,
global localization, refused poses that change nothing."""

import numpy as np
import pytest

from aiobt_services.localization import se2
from aiobt_services.localization.amcl import Amcl
from aiobt_services.localization.initial_pose import InitialPoseError
from aiobt_services.localization.laser_model import Beams, select_beams
from aiobt_services.localization.params import AmclParams

from .maps import cast, field, room

BEARINGS = -np.pi + 2 * np.pi / 360 * np.arange(360, dtype=np.float64)
CELLS = room()


def _beams(truth: np.ndarray) -> Beams:
    ranges = cast(CELLS, tuple(truth), BEARINGS)
    return select_beams(ranges, BEARINGS, max_beams=60, range_min=0.05, range_max=12.0)


def _filter(**params: object) -> Amcl:
    amcl = Amcl(AmclParams.from_mapping({"random_seed": 7, **params}))
    amcl.set_map(field(CELLS))
    return amcl


def _drive(
    amcl: Amcl, truth: np.ndarray, odom: np.ndarray, steps: int, scale: float
) -> tuple[np.ndarray, np.ndarray]:
    """Drive a loop around the room; odometry reads ``scale`` times the true motion."""
    for i in range(steps):
        turn = 0.25 if (i // 12) % 2 else -0.05
        motion = np.array([0.1, 0.0, turn])
        truth = se2.compose(truth, motion)
        odom = se2.compose(odom, np.array([0.1 * scale, 0.0, turn * scale]))
        amcl.on_scan(odom, _beams(truth))
    return truth, odom


def _error(amcl: Amcl, truth: np.ndarray, odom: np.ndarray) -> tuple[float, float]:
    assert amcl.map_to_odom is not None
    est = se2.compose(amcl.map_to_odom, odom)
    return float(np.hypot(*(est[:2] - truth[:2]))), abs(float(se2.angle_diff(est[2], truth[2])))


def test_no_update_before_update_min_d_of_motion_unless_asked() -> None:
    amcl = _filter()
    truth = np.array([1.0, 3.0, 0.0])
    amcl.initialize(amcl.check_pose(*truth))
    assert amcl.on_scan(np.zeros(3), _beams(truth)).updated  # the first scan always
    assert not amcl.on_scan(np.array([0.2, 0.0, 0.0]), _beams(truth)).updated
    assert amcl.on_scan(np.array([0.26, 0.0, 0.0]), _beams(truth)).updated
    assert not amcl.on_scan(np.array([0.26, 0.0, 0.1]), _beams(truth)).updated
    amcl.request_nomotion_update()
    assert amcl.on_scan(np.array([0.26, 0.0, 0.1]), _beams(truth)).updated


def test_tracks_the_robot_through_a_5_percent_odometry_scale_error() -> None:
    amcl = _filter(update_min_d=0.05, update_min_a=0.05)
    truth = np.array([1.0, 3.0, 0.0])
    amcl.initialize(amcl.check_pose(*truth))
    truth, odom = _drive(amcl, truth, np.zeros(3), 60, scale=1.05)
    error, heading = _error(amcl, truth, odom)
    assert error < 0.1
    assert heading < np.deg2rad(3)
    assert len(amcl.particles) < 1000  # converged: KLD shrank the set


def test_global_localization_finds_the_robot_from_particles_over_the_whole_map() -> None:
    amcl = _filter(update_min_d=0.05, update_min_a=0.05)
    amcl.global_localization()
    assert len(amcl.particles) == 2000
    truth, odom = _drive(amcl, np.array([4.5, 1.0, np.pi / 2]), np.zeros(3), 40, scale=1.0)
    error, heading = _error(amcl, truth, odom)
    assert error < 0.25
    assert heading < np.deg2rad(10)


def test_a_refused_initial_pose_leaves_the_particles_as_they_were() -> None:
    amcl = _filter()
    amcl.initialize(amcl.check_pose(1.0, 3.0, 0.0))
    before = amcl.particles.copy()
    with pytest.raises(InitialPoseError, match="off the map"):
        amcl.initialize(amcl.check_pose(50.0, 3.0, 0.0))
    assert np.array_equal(before, amcl.particles)


def test_without_a_pose_or_a_map_scans_do_nothing() -> None:
    amcl = Amcl(AmclParams())
    assert not amcl.on_scan(np.zeros(3), _beams(np.array([1.0, 3.0, 0.0]))).updated
    amcl.set_map(field(CELLS))
    assert not amcl.on_scan(np.zeros(3), _beams(np.array([1.0, 3.0, 0.0]))).updated
    with pytest.raises(RuntimeError, match="no map"):
        Amcl(AmclParams()).global_localization()
