"""The geometric lidar (:mod:`aiobt_services.robot.lidar`) against pybullet's own rays."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import numpy.typing as npt
import pybullet
import pytest

from aiobt.geometry import Pose2D
from aiobt_services.robot.lidar import Disc, Rectangles, cast, disc_distances, rectangle_distances
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.obstacles import ObstacleSpec
from aiobt_services.robot.sensors import LidarConfig
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.world import ROBOT_GROUP
from aiobt_services.robot.worlds import OFFICE

RAY_MASK = 0xFFFF & ~ROBOT_GROUP  # what Bullet's rays must skip: the robot's own body


def one(x: float, y: float, hx: float, hy: float, yaw: float = 0.0) -> Rectangles:
    arr = np.array
    return Rectangles.from_centres(arr([x]), arr([y]), arr([hx]), arr([hy]), yaw)


def unit(angles: list[float]) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    a = np.array(angles)
    return np.cos(a), np.sin(a)


def test_rectangle_distances_front_back_inside_and_misses() -> None:
    box = one(3.0, 0.0, 1.0, 0.5)  # x 2..4, y -0.5..0.5
    ux, uy = unit([0.0, math.pi, math.pi / 2, math.atan2(0.5, 2.0)])
    dist = rectangle_distances(box, 0.0, 0.0, ux, uy)
    assert dist[0] == pytest.approx(2.0)
    assert dist[1] == math.inf  # behind the origin
    assert dist[2] == math.inf  # beside it
    assert dist[3] == pytest.approx(math.hypot(2.0, 0.5))  # its near corner
    assert rectangle_distances(box, 3.0, 0.0, ux, uy)[0] == 0.0  # from inside


def test_a_rotated_rectangle_is_hit_on_its_rotated_face() -> None:
    diamond = one(2.0, 0.0, 0.5, 0.5, yaw=math.pi / 4)  # a corner points at the origin
    ux, uy = unit([0.0])
    assert rectangle_distances(diamond, 0.0, 0.0, ux, uy)[0] == pytest.approx(2.0 - math.sqrt(0.5))


def test_disc_distances() -> None:
    ux, uy = unit([0.0, math.pi / 2])
    dist = disc_distances([Disc(2.0, 0.0, 0.5)], 0.0, 0.0, ux, uy)
    assert dist[0] == pytest.approx(1.5)
    assert dist[1] == math.inf
    assert disc_distances([Disc(0.0, 0.0, 0.5)], 0.1, 0.0, ux, uy)[0] == 0.0  # inside
    assert disc_distances([Disc(-2.0, 0.0, 0.5)], 0.0, 0.0, ux, uy)[0] == math.inf  # behind


def test_cast_takes_the_nearest_of_walls_rectangles_and_discs() -> None:
    walls = one(5.0, 0.0, 0.1, 10.0)
    headings = np.array([0.0, math.pi / 2])
    assert cast(walls, [], [], (0.0, 0.0), headings)[0] == pytest.approx(4.9)
    near = cast(walls, [one(3.0, 0.0, 0.5, 0.5)], [Disc(0.0, 1.0, 0.25)], (0.0, 0.0), headings)
    assert near.tolist() == pytest.approx([2.5, 0.75])


def test_negative_half_extents_are_refused() -> None:
    with pytest.raises(ValueError, match="half extents"):
        one(0.0, 0.0, -1.0, 1.0)


@pytest.fixture
def office() -> Iterator[Simulation]:
    with Simulation(load_map(OFFICE)) as sim:
        yield sim


def bullet_ranges(sim: Simulation) -> npt.NDArray[np.float64]:
    """The scan as pybullet's rays see the same bodies (as the robot cast it before)."""
    cfg, pose = sim.config.lidar, sim.true_pose
    heading = pose.yaw + cfg.angles()
    unit3 = np.stack([np.cos(heading), np.sin(heading), np.zeros_like(heading)], axis=1)
    centre = np.array([pose.x, pose.y, cfg.height])
    results = pybullet.rayTestBatch(
        np.repeat(centre[None, :], len(heading), axis=0).tolist(),
        (centre + unit3 * cfg.range_max).tolist(),
        numThreads=1,
        collisionFilterMask=RAY_MASK,
        physicsClientId=sim._physics.client,
    )
    return np.array([r[2] * cfg.range_max if r[0] >= 0 else np.inf for r in results])


def test_the_scan_matches_pybullets_rays_in_the_office(office: Simulation) -> None:
    office.spawn(ObstacleSpec("box", "box", Pose2D(4.0, 9.5, 0.4), size_x=0.6, size_y=0.3))
    office.spawn(ObstacleSpec("can", "cylinder", Pose2D(3.0, 10.4, 0.0), radius=0.2))
    office.spawn(ObstacleSpec("low", "box", Pose2D(2.0, 10.6, 0.0), height=0.1))  # under the rays
    rng = np.random.default_rng(3)
    compared = 0
    for _ in range(40):
        pose = Pose2D(*rng.uniform((0.5, 0.5, -math.pi), (19.5, 19.5, math.pi)))
        try:
            office.teleport(pose)
        except ValueError:
            continue  # inside a wall or an obstacle
        ours, bullet = office.scan().ranges, bullet_ranges(office)
        assert np.array_equal(np.isinf(ours), np.isinf(bullet)) or (
            np.count_nonzero(np.isinf(ours) != np.isinf(bullet)) <= 2  # corner grazes
        )
        both = np.isfinite(ours) & np.isfinite(bullet)
        close = np.abs(ours[both] - bullet[both]) <= 0.025
        assert np.count_nonzero(~close) <= 4, (pose, np.flatnonzero(~close))
        compared += 1
    assert compared >= 15


def test_a_still_robot_casts_once_and_a_move_or_an_obstacle_casts_again(
    office: Simulation, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Standing still the rays are not cast again, the noise is drawn anew; whatever
    moved (the robot, an obstacle spawned, moved or removed) is in the next scan."""
    casts: list[int] = []
    real = office.cast_from

    def counted(*args: object) -> npt.NDArray[np.float64]:
        casts.append(1)
        return real(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(office, "cast_from", counted)
    start = office.true_pose
    first, again = office.scan().ranges, office.scan().ranges
    assert len(casts) == 1
    assert np.array_equal(first, again)  # no noise configured: the same distances
    ahead = Pose2D(start.x + 0.7 * math.cos(start.yaw), start.y + 0.7 * math.sin(start.yaw), 0.0)
    office.spawn(ObstacleSpec("box", "box", ahead, size_x=0.3, size_y=0.3))
    boxed = office.scan().ranges
    assert len(casts) == 2
    assert np.nanmin(boxed) < 0.7 < np.nanmin(first)
    office.move("box", Pose2D(ahead.x, ahead.y + 0.05, 0.0))
    office.scan()
    office.remove("box")
    assert np.array_equal(office.scan().ranges, first)
    office.teleport(Pose2D(start.x + 0.1, start.y, start.yaw))
    office.scan()
    assert len(casts) == 5


def test_a_still_robots_scans_draw_their_noise_each_time() -> None:
    config = SimConfig(lidar=LidarConfig(noise=0.01, dropout=0.1))
    with Simulation(load_map(OFFICE), config) as sim:
        first, again = sim.scan().ranges, sim.scan().ranges
        later = [sim.scan().ranges for _ in range(30)]
    # each drawn on the same distances: the dropouts and the noise do not pile up
    assert 0.05 < np.mean(np.isinf(later[-1])) < 0.15
    seen = np.isfinite(later[-1]) & np.isfinite(first)
    assert np.std(later[-1][seen] - first[seen]) < 0.03
    both = np.isfinite(first) & np.isfinite(again)  # a dropped beam is inf
    assert not np.array_equal(np.isfinite(first), np.isfinite(again))  # other dropouts
    assert 0.0 < np.max(np.abs(first[both] - again[both])) < 0.1  # other noise, same walls
