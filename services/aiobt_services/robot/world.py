"""The pybullet side: a physics client, walls from the grid, robot and obstacle bodies."""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import pybullet

from aiobt.geometry import Pose2D

from .boxes import merge_boxes
from .lidar import Rectangles
from .mapfile import OCCUPIED, MapInfo
from .obstacles import ObstacleSpec

log = logging.getLogger("aiobt_services.robot.world")

WALL_HEIGHT = 1.0
MAX_TRAVEL_PER_SUBSTEP = 0.05  # m: a third of a wall, so a fast base cannot tunnel through
ROBOT_GROUP = 0x4  # collision filter group of the robot body


@dataclass(slots=True, frozen=True)
class RobotShape:
    """A round base (a cylinder), like most indoor differential-drive robots."""

    radius: float = 0.22
    height: float = 0.25
    mass: float = 15.0
    z: float = 0.15  # centre height; the base floats (no gravity), contacts stay planar


def substeps_for(max_speed: float, dt: float) -> int:
    """Physics sub-steps per step so that one sub-step moves the base at most a few cm."""
    return max(1, math.ceil(max_speed * dt / MAX_TRAVEL_PER_SUBSTEP))


def wall_rectangles(world: MapInfo) -> Rectangles:
    """The map's occupied cells merged into rectangles (in the map's orientation)."""
    boxes = merge_boxes(world.grid == OCCUPIED)
    xs, ys = world.cell_to_world(boxes[:, 0] + 0.5 * boxes[:, 2], boxes[:, 1] + 0.5 * boxes[:, 3])
    res = world.resolution
    walls = Rectangles.from_centres(
        xs, ys, 0.5 * res * boxes[:, 3], 0.5 * res * boxes[:, 2], world.origin[2]
    )
    log.info(
        "world %s: %d occupied cells merged into %d boxes",
        world.source,
        int(np.count_nonzero(world.grid == OCCUPIED)),
        len(boxes),
    )
    return walls


class Physics:
    """One pybullet client (DIRECT unless ``gui``), closed with :meth:`close`."""

    def __init__(self, *, gui: bool = False, dt: float = 0.01, substeps: int = 1) -> None:
        self.client = pybullet.connect(pybullet.GUI if gui else pybullet.DIRECT)
        if self.client < 0:
            raise RuntimeError("pybullet could not connect (is a display available for --gui?)")
        self.call("setGravity", 0.0, 0.0, 0.0)
        self.call("setTimeStep", dt)
        self.call(
            "setPhysicsEngineParameter",
            numSolverIterations=10,
            deterministicOverlappingPairs=1,
            numSubSteps=max(1, substeps),
        )

    def call(self, name: str, *args: Any, **kwargs: Any) -> Any:
        """``pybullet.<name>(..., physicsClientId=<ours>)``."""
        return getattr(pybullet, name)(*args, physicsClientId=self.client, **kwargs)

    def close(self) -> None:
        if self.client >= 0 and pybullet.isConnected(physicsClientId=self.client):
            pybullet.disconnect(physicsClientId=self.client)
        self.client = -1

    def static_box(self, x: float, y: float, yaw: float, half: tuple[float, float, float]) -> int:
        shape = self.call("createCollisionShape", pybullet.GEOM_BOX, halfExtents=half)
        orn = pybullet.getQuaternionFromEuler((0.0, 0.0, yaw))
        body: int = self.call(
            "createMultiBody",
            baseMass=0.0,
            baseCollisionShapeIndex=shape,
            basePosition=(x, y, half[2]),
            baseOrientation=orn,
        )
        return body

    def build_walls(self, walls: Rectangles) -> list[int]:
        """One static body per wall rectangle (see :func:`wall_rectangles`)."""
        c, s = math.cos(walls.yaw), math.sin(walls.yaw)
        centres, halves = 0.5 * (walls.lo + walls.hi), 0.5 * (walls.hi - walls.lo)
        half_z = 0.5 * WALL_HEIGHT
        return [
            self.static_box(float(c * u - s * v), float(s * u + c * v), walls.yaw, (hx, hy, half_z))
            for (u, v), (hx, hy) in zip(centres.tolist(), halves.tolist(), strict=True)
        ]

    def robot(self, shape: RobotShape, pose: Pose2D) -> int:
        collision = self.call(
            "createCollisionShape", pybullet.GEOM_CYLINDER, radius=shape.radius, height=shape.height
        )
        visual = self.call(
            "createVisualShape",
            pybullet.GEOM_CYLINDER,
            radius=shape.radius,
            length=shape.height,
            rgbaColor=(0.1, 0.3, 0.9, 1.0),
        )
        body: int = self.call(
            "createMultiBody",
            baseMass=shape.mass,
            baseCollisionShapeIndex=collision,
            baseVisualShapeIndex=visual,
            basePosition=(pose.x, pose.y, shape.z),
            baseOrientation=pybullet.getQuaternionFromEuler((0.0, 0.0, pose.yaw)),
        )
        self.call(
            "changeDynamics",
            body,
            -1,
            lateralFriction=0.0,
            linearDamping=0.0,
            angularDamping=0.0,
        )
        self.call("setCollisionFilterGroupMask", body, -1, ROBOT_GROUP, 0xFFFF)
        return body

    def obstacle(self, spec: ObstacleSpec) -> int:
        half_z = 0.5 * spec.height
        if spec.shape == "box":
            return self.static_box(
                spec.pose.x,
                spec.pose.y,
                spec.pose.yaw,
                (0.5 * spec.size_x, 0.5 * spec.size_y, half_z),
            )
        shape = self.call(
            "createCollisionShape", pybullet.GEOM_CYLINDER, radius=spec.radius, height=spec.height
        )
        body: int = self.call(
            "createMultiBody",
            baseMass=0.0,
            baseCollisionShapeIndex=shape,
            basePosition=(spec.pose.x, spec.pose.y, half_z),
        )
        return body

    def place(self, body: int, pose: Pose2D, z: float) -> None:
        orn = pybullet.getQuaternionFromEuler((0.0, 0.0, pose.yaw))
        self.call("resetBasePositionAndOrientation", body, (pose.x, pose.y, z), orn)

    def remove(self, body: int) -> None:
        self.call("removeBody", body)

    def planar_pose(self, body: int) -> Pose2D:
        pos, orn = self.call("getBasePositionAndOrientation", body)
        yaw = math.atan2(
            2.0 * (orn[3] * orn[2] + orn[0] * orn[1]), 1.0 - 2.0 * (orn[1] ** 2 + orn[2] ** 2)
        )
        return Pose2D(pos[0], pos[1], yaw)
