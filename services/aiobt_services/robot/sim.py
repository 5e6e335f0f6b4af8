"""The simulated robot: a stepped, deterministic pybullet world around a diff-drive base.

:class:`Simulation` has its own time line (``time``, advanced by ``dt`` per
:meth:`step`); nothing in here reads the wall clock, so a test can step it as
fast as the CPU allows and get the same result every run.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from aiobt.geometry import Pose2D, wrap_angle

from .bumper import Bumper, ContactEvent
from .dock import build_station
from .drive import CommandVerdict, DriveController, DriveLimits
from .lidar import Solid, cast_solids
from .mapfile import MapInfo
from .obstacles import Motion, ObstacleError, ObstacleSpec, solid, validate
from .rest import RestGate
from .sensors import (
    Battery,
    BatteryConfig,
    LidarConfig,
    NoiseConfig,
    WheelOdometry,
    lidar_ranges,
    noisy_pose,
)
from .wheels import WheelJoints
from .world import Physics, RobotShape, substeps_for, wall_rectangles

log = logging.getLogger("aiobt_services.robot.sim")


class PoseError(ValueError):
    """A requested robot pose is outside the world or inside something solid."""


@dataclass(slots=True, frozen=True)
class SimConfig:
    dt: float = 0.01
    limits: DriveLimits = field(default_factory=DriveLimits)
    noise: NoiseConfig = field(default_factory=NoiseConfig)
    lidar: LidarConfig = field(default_factory=LidarConfig)
    battery: BatteryConfig = field(default_factory=BatteryConfig)
    robot: RobotShape = field(default_factory=RobotShape)
    gui: bool = False


@dataclass(slots=True, frozen=True)
class Scan:
    time: float
    ranges: npt.NDArray[np.float64]
    config: LidarConfig


CastKey = tuple[Pose2D, tuple[Solid, ...]]


@dataclass(slots=True)
class _Obstacle:
    spec: ObstacleSpec
    body: int
    since: float


class Simulation:
    """A world (walls from the map), one robot, obstacles; stepped by the caller."""

    def __init__(
        self, world: MapInfo, config: SimConfig | None = None, *, rest: bool = True
    ) -> None:
        """``rest``: leave the physics out of steps where nothing can move (:mod:`.rest`)."""
        self.world = world
        self.config = config or SimConfig()
        self.time = 0.0
        self.steps = 0
        self.drive = DriveController(self.config.limits)
        self.battery = Battery(self.config.battery)
        self.odometry = WheelOdometry()
        self.wheels = WheelJoints()  # the motors as joint_states reports them
        self._rng = np.random.default_rng(self.config.noise.seed)
        substeps = substeps_for(self.config.limits.max_linear, self.config.dt)
        self._physics = Physics(gui=self.config.gui, dt=self.config.dt, substeps=substeps)
        self._wall_rects = wall_rectangles(world)
        self._walls = set(self._physics.build_walls(self._wall_rects))
        self.dock_station, self._dock_body = build_station(world, self.config.robot, self._physics)
        self._camera_rng = np.random.default_rng(self.config.noise.seed + 1)
        self._headings = self.config.lidar.angles()
        # the last scan's rays: the robot's pose and the solids then, the distances
        self._last_cast: tuple[CastKey, npt.NDArray[np.float64]] | None = None
        start = Pose2D(*world.start)
        self._robot = self._physics.robot(self.config.robot, start)
        self._true = start
        self._loc_offset = Pose2D()
        self._obstacles: dict[str, _Obstacle] = {}
        self.movers: list[Callable[[], None]] = []  # each step, first (target.py's box)
        self._bumper = Bumper()
        self._rest = RestGate(rest)
        self._clamp_logged = False
        self._empty_logged = False
        try:
            self.check_free(start, self.config.robot.radius)
        except PoseError as exc:
            self.close()
            raise PoseError(f"{world.source}: start {exc}") from None

    # -- lifecycle -------------------------------------------------------
    def close(self) -> None:
        self._physics.close()

    def __enter__(self) -> Simulation:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- commands --------------------------------------------------------
    def command(self, linear: float, angular: float) -> CommandVerdict:
        verdict = self.drive.command(linear, angular, self.time)
        if not verdict.accepted:
            log.warning("velocity command dropped: %s", verdict.reason)
        elif verdict.clamped:
            level = logging.DEBUG if self._clamp_logged else logging.INFO
            self._clamp_logged = True
            log.log(
                level,
                "velocity command (%s, %s) clamped to the limits: (%s, %s)",
                linear,
                angular,
                verdict.linear,
                verdict.angular,
            )
        return verdict

    def step(self, count: int = 1) -> list[ContactEvent]:
        """Advance ``count`` physics steps; returns the bumper events that occurred."""
        events: list[ContactEvent] = []
        for _ in range(count):
            events.extend(self._step_once())
        return events

    def run_for(self, seconds: float) -> list[ContactEvent]:
        return self.step(max(0, round(seconds / self.config.dt)))

    def _step_once(self) -> list[ContactEvent]:
        dt, cfg = self.config.dt, self.config
        linear, angular = self._velocity(dt)
        before = self._true
        self._move_dynamic_obstacles()  # the movers first: a box moved unsettles the rest
        resting = self._rest.holds(linear, angular)
        if not resting:
            self._push(linear * (1.0 - cfg.noise.slip), angular, before.yaw)
        self.time = round(self.time + dt, 9)
        self.steps += 1
        if not resting:
            pose = self._physics.planar_pose(self._robot)
            self._physics.place(self._robot, pose, cfg.robot.z)  # keep the base flat
            self._true = pose
        pose = self._true
        wheels = (linear, angular)
        if self._bumper.touching:  # pushing an obstacle: the motors stall, the wheels turn
            wheels = self._achieved(before, pose, dt)  # with the body, no further
        self.odometry.update(*wheels, dt, cfg.noise, self._rng)
        self.wheels.update((linear, angular), wheels, dt)
        on_dock = self.dock_station is not None and self.dock_station.charging_contact(pose)
        self.battery.update(linear, angular, on_dock, dt)
        if resting:
            return []  # nothing touches the robot, nothing moved: no contact came or went
        events = self._contact_events()
        still = linear == 0.0 and angular == 0.0 and pose == before
        self._rest.stepped(still and not self._bumper.touching)
        return events

    def _velocity(self, dt: float) -> tuple[float, float]:
        """The drive's velocity for this step (zero on an empty battery)."""
        linear, angular = self.drive.update(self.time, dt)
        if self.battery.depleted:
            if (linear or angular) and not self._empty_logged:
                log.warning("battery empty: the base does not move until it is charged")
                self._empty_logged = True
            self.drive.stop()
            return 0.0, 0.0
        self._empty_logged = False
        return linear, angular

    def _push(self, body_speed: float, angular: float, yaw: float) -> None:
        """One pybullet step with the robot's body at this velocity."""
        velocity = (body_speed * math.cos(yaw), body_speed * math.sin(yaw), 0.0)
        self._physics.call("resetBaseVelocity", self._robot, velocity, (0.0, 0.0, angular))
        self._physics.call("stepSimulation")

    # -- state -----------------------------------------------------------
    @property
    def true_pose(self) -> Pose2D:
        """Ground truth in ``map``."""
        return self._true

    def localized_pose(self) -> Pose2D:
        """The localization stand-in: truth, offset by ``initialpose``, plus noise."""
        return noisy_pose(self._loc_offset.compose(self._true), self.config.noise, self._rng)

    def scan(self) -> Scan:
        """The lidar at the current step: walls and the obstacles taller than its plane,
        at their poses now (:mod:`.lidar`; the robot's own body is not seen). The rays
        are cast again only when the robot or such an obstacle moved (a robot standing
        still sees the same distances); the noise and dropouts are drawn for each scan."""
        cfg, pose = self.config.lidar, self._true
        solids = self._solids()
        if self._last_cast is None or self._last_cast[0] != (pose, solids):
            dist = self.cast_from(pose, pose.yaw + self._headings, solids)
            self._last_cast = ((pose, solids), dist)
        return Scan(self.time, lidar_ranges(self._last_cast[1], cfg, self._rng), cfg)

    def cast_from(
        self,
        pose: Pose2D,
        headings: npt.NDArray[np.float64],
        solids: tuple[Solid, ...] | None = None,
    ) -> npt.NDArray[np.float64]:
        """Distances from ``pose`` along world ``headings`` to the walls and to the
        obstacles taller than the lidar's plane (``solids``: those, where they stand now;
        ``inf``: nothing)."""
        solids = self._solids() if solids is None else solids
        return cast_solids(self._wall_rects, solids, (pose.x, pose.y), headings)

    def _solids(self) -> tuple[Solid, ...]:
        """The obstacles taller than the lidar's plane, where they stand now."""
        height = self.config.lidar.height
        return tuple(
            solid(o.spec, self.obstacle_pose(oid))
            for oid, o in self._obstacles.items()
            if o.spec.height > height
        )

    # -- the dock ----------------------------------------------------------
    def detect_dock(self) -> Pose2D | None:
        """The robot camera's detection of the dock's marker (in ``base_link``, noisy),
        or None when it is out of view or hidden."""
        station, pose = self.dock_station, self._true
        if station is None or not station.visible(pose, math.inf):
            return None  # out of range or view, whatever stands between: no ray to cast
        hit = float(self.cast_from(pose, np.array([station.bearing_from(pose)]))[0])
        return station.detect(pose, self._camera_rng) if station.visible(pose, hit) else None

    # -- robot pose ------------------------------------------------------
    def check_free(self, pose: Pose2D, clearance: float, ignore: str = "") -> None:
        """Raise :class:`PoseError` unless a disc of ``clearance`` at ``pose`` is free."""
        if not all(math.isfinite(v) for v in (pose.x, pose.y, pose.yaw)):
            raise PoseError(f"pose ({pose.x}, {pose.y}, {pose.yaw}) is not finite")
        if not self.world.contains(pose.x, pose.y, margin=clearance):
            raise PoseError(f"pose ({pose.x:.2f}, {pose.y:.2f}) is outside the world")
        if self.world.disc_blocked(pose.x, pose.y, clearance):
            raise PoseError(f"pose ({pose.x:.2f}, {pose.y:.2f}) overlaps a wall")
        for oid, obstacle in self._obstacles.items():
            here = obstacle.spec.pose_at(self.time - obstacle.since)
            if oid != ignore and obstacle.spec.distance_to(pose.x, pose.y, here) < clearance:
                raise PoseError(f"pose ({pose.x:.2f}, {pose.y:.2f}) overlaps obstacle '{oid}'")

    def teleport(self, pose: Pose2D) -> None:
        """Move the robot (e.g. ``initialpose``); odometry keeps running, motion stops."""
        self.check_free(pose, self.config.robot.radius)
        self._physics.place(self._robot, pose, self.config.robot.z)
        self._true = pose
        self._loc_offset = Pose2D()
        self.drive.stop()
        self._rest.disturb()

    def set_localization(self, estimate: Pose2D) -> None:
        """Make the localization believe the robot is at ``estimate`` (AMCL-style)."""
        self._loc_offset = estimate.compose(self._true.inverse())

    def reinitialize_localization(self) -> None:
        """Global localization: the estimate snaps back onto the truth."""
        self._loc_offset = Pose2D()

    # -- obstacles -------------------------------------------------------
    @property
    def obstacles(self) -> dict[str, ObstacleSpec]:
        return {oid: o.spec for oid, o in self._obstacles.items()}

    def obstacle_pose(self, oid: str) -> Pose2D:
        obstacle = self._obstacles[oid]
        return obstacle.spec.pose_at(self.time - obstacle.since)

    def spawn(self, spec: ObstacleSpec) -> None:
        if spec.id in self._obstacles:
            raise ObstacleError(f"obstacle '{spec.id}' already exists")
        validate(spec, self.world)
        self._check_clear_of_robot(spec, spec.pose)
        self._obstacles[spec.id] = _Obstacle(spec, self._physics.obstacle(spec), self.time)
        self._rest.disturb()

    def move(self, oid: str, pose: Pose2D, motion: Motion | None = None) -> None:
        obstacle = self._get(oid)
        spec = obstacle.spec.moved_to(pose, motion)
        validate(spec, self.world)
        self._check_clear_of_robot(spec, pose)
        obstacle.spec, obstacle.since = spec, self.time
        self._physics.place(obstacle.body, pose, 0.5 * spec.height)
        self._rest.disturb()

    def remove(self, oid: str) -> None:
        obstacle = self._get(oid)
        self._physics.remove(obstacle.body)
        del self._obstacles[oid]
        self._bumper.forget(oid)
        self._rest.disturb()

    def _get(self, oid: str) -> _Obstacle:
        if oid not in self._obstacles:
            known = ", ".join(sorted(self._obstacles)) or "none"
            raise ObstacleError(f"no obstacle '{oid}' (known: {known})")
        return self._obstacles[oid]

    def _check_clear_of_robot(self, spec: ObstacleSpec, pose: Pose2D) -> None:
        robot = self._true
        if spec.distance_to(robot.x, robot.y, pose) < self.config.robot.radius:
            raise ObstacleError(f"obstacle '{spec.id}' would overlap the robot")

    def _move_dynamic_obstacles(self) -> None:
        for mover in self.movers:
            mover()
        for obstacle in self._obstacles.values():
            if obstacle.spec.motion is not None:
                pose = obstacle.spec.pose_at(self.time - obstacle.since)
                self._physics.place(obstacle.body, pose, 0.5 * obstacle.spec.height)
                self._rest.disturb()

    # -- bumper ----------------------------------------------------------
    def _body_name(self, body: int) -> str | None:
        if body in self._walls:
            return "wall"
        if body == self._dock_body:
            return "dock"
        return next((oid for oid, o in self._obstacles.items() if o.body == body), None)

    def _achieved(self, before: Pose2D, after: Pose2D, dt: float) -> tuple[float, float]:
        """The wheel speeds that rolled the body from ``before`` to ``after`` (slip aside)."""
        forward = (after.x - before.x) * math.cos(before.yaw)
        forward += (after.y - before.y) * math.sin(before.yaw)
        turned = wrap_angle(after.yaw - before.yaw)
        return forward / dt / (1.0 - self.config.noise.slip), turned / dt

    def _contact_events(self) -> list[ContactEvent]:
        points = self._physics.call("getContactPoints", bodyA=self._robot)
        return self._bumper.update(points, self._body_name, self._true, self.time)

    @property
    def in_contact(self) -> list[str]:
        return self._bumper.touching
