"""Simulation state -> ``aiobt.msgs`` wire messages (and requests -> sim objects)."""

from __future__ import annotations

import numpy as np

from aiobt.geometry import Pose2D
from aiobt.msgs import (
    BatteryState,
    Header,
    LaserScan,
    OccupancyGrid,
    Odometry,
    Point,
    Pose,
    PoseStamped,
    PowerSupplyStatus,
    pose_fields,
)
from aiobt.msgs.sim import BumperEvent, MoveObstacle, ObstacleMotion, ObstacleState, SpawnObstacle

from .bumper import ContactEvent
from .mapfile import MapInfo
from .obstacles import Motion, ObstacleSpec
from .sensors import Battery
from .sim import Scan, Simulation

NO_RETURN_MARGIN = 1.0  # a beam without a return reads range_max + this (JSON has no inf)


# The 50 Hz messages are validated from one nested dict each (one call into pydantic's
# core instead of one per nested model: about half the CPU, the same message).
def odometry(sim: Simulation) -> Odometry:
    odom = sim.odometry
    return Odometry.model_validate(
        {
            "header": {"stamp": sim.time, "frame_id": "odom"},
            "child_frame_id": "base_link",
            "pose": pose_fields(odom.pose.x, odom.pose.y, odom.pose.yaw),
            "twist": {"linear": {"x": odom.linear}, "angular": {"z": odom.angular}},
        }
    )


def map_pose(sim: Simulation) -> PoseStamped:
    pose = sim.localized_pose()
    header = {"stamp": sim.time, "frame_id": "map"}
    return PoseStamped.model_validate(
        {"header": header, "pose": pose_fields(pose.x, pose.y, pose.yaw)}
    )


def true_pose(sim: Simulation) -> PoseStamped:
    """The simulation's truth (``{ns}/sim/pose``): for evaluation, never navigation."""
    pose = sim.true_pose
    header = {"stamp": sim.time, "frame_id": "map"}
    return PoseStamped.model_validate(
        {"header": header, "pose": pose_fields(pose.x, pose.y, pose.yaw)}
    )


def laser_scan(scan: Scan) -> LaserScan:
    cfg = scan.config
    ranges = np.where(np.isfinite(scan.ranges), scan.ranges, cfg.range_max + NO_RETURN_MARGIN)
    return LaserScan(
        header=Header(stamp=scan.time, frame_id="base_scan"),
        angle_min=cfg.angle_min,
        angle_max=cfg.angle_max,
        angle_increment=cfg.angle_increment,
        range_min=cfg.range_min,
        range_max=cfg.range_max,
        ranges=np.round(ranges, 4).tolist(),
    )


def dock_detection(marker: Pose2D, stamp: float) -> PoseStamped:
    """The dock's marker in the robot's frame, as a fiducial detector publishes it."""
    return PoseStamped.from_xy_yaw(marker.x, marker.y, marker.yaw, "base_link", stamp)


def battery_state(battery: Battery, stamp: float) -> BatteryState:
    cfg = battery.config
    volts = battery.voltage
    if battery.charging:
        status = PowerSupplyStatus.CHARGING
    elif battery.percentage >= 1.0:
        status = PowerSupplyStatus.FULL
    else:
        status = PowerSupplyStatus.DISCHARGING
    return BatteryState(
        header=Header(stamp=stamp),
        voltage=volts,
        current=battery.power_w / volts,
        charge=battery.energy_wh / cfg.full_voltage,
        capacity=cfg.capacity_wh / cfg.full_voltage,
        percentage=min(1.0, max(0.0, battery.percentage)),
        power_supply_status=status,
    )


def occupancy_grid(world: MapInfo, stamp: float = 0.0) -> OccupancyGrid:
    x, y, yaw = world.origin
    return OccupancyGrid.from_array(
        world.grid, world.resolution, origin=Pose.from_xy_yaw(x, y, yaw), stamp=stamp
    )


def bumper(event: ContactEvent) -> BumperEvent:
    return BumperEvent(
        header=Header(stamp=event.time, frame_id="map"),
        pressed=event.pressed,
        other=event.other,
        point=Point(x=event.x, y=event.y),
        angle=event.angle,
    )


def _motion(motion: ObstacleMotion | None) -> Motion | None:
    return None if motion is None else Motion(motion.to_x, motion.to_y, motion.speed)


def obstacle_spec(req: SpawnObstacle, oid: str) -> ObstacleSpec:
    return ObstacleSpec(
        id=oid,
        shape=req.shape,
        pose=Pose2D(req.x, req.y, req.yaw),
        size_x=req.size_x,
        size_y=req.size_y,
        radius=req.radius,
        height=req.height,
        motion=_motion(req.motion),
    )


def move_args(req: MoveObstacle) -> tuple[Pose2D, Motion | None]:
    return Pose2D(req.x, req.y, req.yaw), _motion(req.motion)


def obstacle_state(sim: Simulation, oid: str) -> ObstacleState:
    spec, pose = sim.obstacles[oid], sim.obstacle_pose(oid)
    return ObstacleState(
        id=oid,
        shape=spec.shape,
        x=pose.x,
        y=pose.y,
        yaw=pose.yaw,
        size_x=spec.size_x,
        size_y=spec.size_y,
        radius=spec.radius,
        height=spec.height,
        moving=spec.motion is not None,
    )
