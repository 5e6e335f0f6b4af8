"""The filter on a small room: tracking under odometry error, update gating,
global localization, refused poses that change nothing."""

import numpy as np
import pytest

from aiobt_services.localization import se2
from aiobt_services.localization.amcl import Amcl
from aiobt_services.localization.initial_pose import InitialPoseError
from aiobt_services.localization.laser_model import Beams, select_beams
from aiobt_services.localization.likelihood_field import LikelihoodField
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


@pytest.mark.parametrize("laser_model_type", ["likelihood_field", "likelihood_field_prob"])
def test_tracks_the_robot_through_a_5_percent_odometry_scale_error(laser_model_type: str) -> None:
    amcl = _filter(update_min_d=0.05, update_min_a=0.05, laser_model_type=laser_model_type)
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


class Draws:
    """How many random poses each resample drew from the free space."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.counts: list[int] = []
        real = LikelihoodField.random_free_poses

        def counted(f: LikelihoodField, count: int, rng: np.random.Generator) -> np.ndarray:
            self.counts.append(count)
            return real(f, count, rng)

        monkeypatch.setattr(LikelihoodField, "random_free_poses", counted)


def _lost(reset: bool, long_beams: float = 0.0) -> Amcl:
    """A filter tracking in the room whose averages say its fit just dropped by half."""
    amcl = _filter(recovery_alpha_slow=0.001, recovery_alpha_fast=0.01,
                   recovery_reset_after_injection=reset, update_min_d=0.05,
                   recovery_min_long_beams=long_beams)  # fmt: skip
    truth = np.array([1.0, 3.0, 0.0])
    amcl.initialize(amcl.check_pose(*truth))
    amcl.on_scan(np.zeros(3), _beams(truth))
    amcl.recovery.w_slow, amcl.recovery.w_fast = 2.0, 1.0
    return amcl


def _resample(amcl: Amcl, draws: Draws, step: float, truth: np.ndarray | None = None) -> int:
    """One update ``step`` m on (the scan taken at ``truth``, by default where the
    odometry says); how many random poses its resample drew (of 2,000)."""
    before = len(draws.counts)
    truth = np.array([1.0 + step, 3.0, 0.0]) if truth is None else truth
    assert amcl.on_scan(np.array([step, 0.0, 0.0]), _beams(truth)).resampled
    return sum(draws.counts[before:])


def test_nav2s_resample_draws_random_particles_once_then_restarts_the_averages(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    draws = Draws(monkeypatch)
    amcl = _lost(reset=True)
    assert 800 < _resample(amcl, draws, 0.1) < 1200  # w_diff 0.5 of max_particles
    assert (amcl.recovery.w_slow, amcl.recovery.w_fast) == (0.0, 0.0)  # pf.c's reset
    assert _resample(amcl, draws, 0.2) == 0  # averages restarted at this fit: none drawn


def test_without_the_reset_random_particles_keep_coming_while_the_fit_stays_low(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    draws = Draws(monkeypatch)
    amcl = _lost(reset=False)
    assert 800 < _resample(amcl, draws, 0.1) < 1200
    assert amcl.recovery.w_slow > amcl.recovery.w_fast > 0.0  # kept, as Augmented MCL
    amcl.recovery.w_slow, amcl.recovery.w_fast = 2.0, 1.0  # the fit still half of before
    assert _resample(amcl, draws, 0.2) > 800


def test_the_long_beam_gate_draws_only_when_beams_reach_past_the_walls(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    draws = Draws(monkeypatch)
    amcl = _lost(reset=False, long_beams=0.2)
    assert _resample(amcl, draws, 0.1) == 0  # the fit dropped, but the scan fits the map
    assert amcl.long_beams < 0.2
    amcl.recovery.w_slow, amcl.recovery.w_fast = 2.0, 1.0
    kidnapped = np.array([3.5, 1.0, 0.0])  # right of the wall stub, the filter left of it
    assert _resample(amcl, draws, 0.2, truth=kidnapped) > 800
    assert amcl.long_beams >= 0.2


def test_the_gate_stays_shut_where_a_mapped_crate_is_gone(monkeypatch: pytest.MonkeyPatch) -> None:
    draws = Draws(monkeypatch)
    amcl = _lost(reset=False, long_beams=0.05)
    on_the_map = CELLS.copy()
    on_the_map[54:66, 50:62] = 100  # a 0.6 m crate ahead of the robot, moved away since
    amcl.set_map(field(on_the_map))
    amcl.recovery.w_slow, amcl.recovery.w_fast = 2.0, 1.0
    assert _resample(amcl, draws, 0.1) == 0  # beams through it end on mapped walls
