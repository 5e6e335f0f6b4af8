"""The long-beam share: beams that reach past the map's walls from a pose (a wrong
pose gives them, obstacles missing from the map do not)."""

import numpy as np

from aiobt_services.localization.laser_model import Beams, select_beams
from aiobt_services.localization.long_beams import long_beam_share

from .maps import cast, field, room

BEARINGS = -np.pi + 2 * np.pi / 360 * np.arange(360, dtype=np.float64)
CELLS = room()
FIELD = field(CELLS)
TRUTH = np.array([1.0, 3.0, 0.3])  # left of the wall stub (x 2.0, y 0..2)


def _beams(ranges: np.ndarray) -> Beams:
    return select_beams(ranges, BEARINGS, max_beams=60, range_min=0.05, range_max=12.0)


def test_from_the_true_pose_no_beam_is_long() -> None:
    beams = _beams(cast(CELLS, tuple(TRUTH), BEARINGS))
    assert len(beams.ranges) > 50
    assert long_beam_share(FIELD, TRUTH, beams, margin=0.4) == 0.0


def test_obstacles_missing_from_the_map_shorten_beams_but_make_none_long() -> None:
    ranges = cast(CELLS, tuple(TRUTH), BEARINGS)
    ranges[:180] = np.minimum(ranges[:180], 0.5)  # a crate close by on half the scan
    assert long_beam_share(FIELD, TRUTH, _beams(ranges), margin=0.4) == 0.0


def test_from_a_wrong_pose_many_beams_are_long() -> None:
    robot = (3.5, 1.0, 0.3)  # right of the wall stub, the estimate left of it
    beams = _beams(cast(CELLS, robot, BEARINGS))
    share = long_beam_share(FIELD, np.array([1.0, 1.0, 0.3]), beams, margin=0.4)
    assert 0.25 < share < 0.75  # the stub stands in front of the estimate, not the robot
    beams = _beams(cast(CELLS, tuple(TRUTH), BEARINGS))
    assert long_beam_share(FIELD, np.array([1.0, 1.5, 0.3]), beams, margin=0.4) > 0.1


def test_a_beam_is_long_only_beyond_the_margin() -> None:
    one = np.array([0.0])  # straight ahead along +x from (1, 3): the wall at x 5.95
    wall = float(cast(CELLS, (1.0, 3.0, 0.0), one)[0])
    pose = np.array([1.0, 3.0, 0.0])
    assert long_beam_share(FIELD, pose, Beams(np.array([wall + 0.3]), one, 12.0), 0.4) == 0.0
    assert long_beam_share(FIELD, pose, Beams(np.array([wall + 0.5]), one, 12.0), 0.4) == 1.0


def test_no_beams_no_evidence() -> None:
    empty = Beams(np.zeros(0), np.zeros(0), 12.0)
    assert long_beam_share(FIELD, TRUTH, empty, margin=0.4) == 0.0


FAR = 0.5 * np.exp(-2.0)  # z_hit's term 2 sigma_hit from a wall: what Amcl passes


def test_a_mapped_obstacle_that_is_gone_lengthens_beams_onto_mapped_walls_only() -> None:
    on_the_map = CELLS.copy()
    on_the_map[50:62, 20:32] = 100  # a 0.6 m crate at (1.0-1.6, 2.5-3.1), moved away since
    moved_away = field(on_the_map)
    pose = np.array([0.5, 2.8, 0.0])  # the crate just ahead
    beams = _beams(cast(CELLS, tuple(pose), BEARINGS))
    assert long_beam_share(moved_away, pose, beams, margin=0.4) > 0.05  # through the crate
    assert long_beam_share(moved_away, pose, beams, 0.4, far_term=FAR) == 0.0  # on walls


def test_a_wrong_pose_still_has_long_beams_that_end_away_from_the_walls() -> None:
    beams = _beams(cast(CELLS, (3.5, 1.0, 0.3), BEARINGS))
    assert long_beam_share(FIELD, np.array([1.0, 1.0, 0.3]), beams, 0.4, far_term=FAR) > 0.1
