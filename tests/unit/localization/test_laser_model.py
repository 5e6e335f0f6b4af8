import numpy as np
import pytest

from aiobt_services.localization.laser_model import (
    LikelihoodFieldModel,
    ScanError,
    check_scan_shape,
    effective_range_limits,
    select_beams,
)

from .maps import cast, field, room

BEARINGS = -np.pi + 2 * np.pi / 360 * np.arange(360, dtype=np.float64)


def test_beams_are_strided_as_amcl_and_unusable_readings_dropped() -> None:
    ranges = np.full(360, 3.0)
    ranges[0], ranges[6], ranges[12] = np.nan, 13.0, 0.01
    beams = select_beams(ranges, BEARINGS, max_beams=60, range_min=0.05, range_max=12.0)
    assert len(beams.ranges) == 57  # step (360-1)//59 = 6: 60 beams, 3 of them unusable
    np.testing.assert_allclose(beams.bearings[0], BEARINGS[18])


def test_the_true_pose_scores_higher_than_poses_beside_it() -> None:
    cells = room()
    truth = (2.5, 1.5, 0.4)
    ranges = cast(cells, truth, BEARINGS)
    beams = select_beams(ranges, BEARINGS, max_beams=60, range_min=0.05, range_max=12.0)
    model = LikelihoodFieldModel(field(cells), z_rand=0.5)
    candidates = np.array(
        [truth, (2.7, 1.5, 0.4), (2.5, 1.3, 0.4), (2.5, 1.5, 0.6), (4.5, 3.0, 2.0)]
    )
    scores = model.likelihood(candidates, beams)
    assert np.argmax(scores) == 0
    assert scores[0] > 1.5 * scores[-1]


def test_a_scan_whose_ray_count_does_not_match_its_angles_is_refused() -> None:
    check_scan_shape(360, -np.pi, np.pi - 2 * np.pi / 360, 2 * np.pi / 360)
    with pytest.raises(ScanError, match="359 ranges but its angles"):
        check_scan_shape(359, -np.pi, np.pi - 2 * np.pi / 360, 2 * np.pi / 360)


def test_range_limits_follow_amcl_node() -> None:
    assert effective_range_limits(0.05, 12.0, -1.0, 100.0) == (0.05, 12.0)
    assert effective_range_limits(0.05, 12.0, 0.2, 8.0) == (0.2, 8.0)
