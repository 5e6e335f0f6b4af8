"""aiobt messages -> Foxglove messages: pure functions, no server, no bus.

Stamps are robot-clock seconds (``Header.stamp``) turned into Foxglove
:class:`~foxglove.messages.Timestamp`; frames keep their names (``map``,
``odom``, ``base_link``, ``base_scan``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from foxglove import messages as fm

from aiobt.costmap import CostGrid
from aiobt.msgs import (
    BtTransitions,
    BtTree,
    LaserScan,
    Msg,
    OccupancyGrid,
    Odometry,
    ParticleCloud,
    Path,
    PoseStamped,
)
from aiobt.msgs import Pose as AiobtPose
from aiobt.msgs.docking import DockList
from aiobt.msgs.route_graph import RouteGraph

_INT8 = fm.PackedElementFieldNumericType.Int8
_UINT8 = fm.PackedElementFieldNumericType.Uint8
_LEVELS = {"FAILURE": fm.LogLevel.Warning, "SKIPPED": fm.LogLevel.Debug}


def timestamp(seconds: float) -> fm.Timestamp:
    sec = math.floor(seconds)
    nsec = min(round((seconds - sec) * 1e9), 999_999_999)
    return fm.Timestamp(sec=sec, nsec=nsec)


def pose(p: AiobtPose) -> fm.Pose:
    q = p.orientation
    return fm.Pose(
        position=fm.Vector3(x=p.position.x, y=p.position.y, z=p.position.z),
        orientation=fm.Quaternion(x=q.x, y=q.y, z=q.z, w=q.w),
    )


def grid(msg: OccupancyGrid) -> fm.Grid:
    """An occupancy grid (-1 unknown, 0..100 cost) as a one-field int8 Grid, row 0 at the
    origin like ROS's."""
    info = msg.info
    cells = np.ascontiguousarray(msg.array, dtype=np.int8)
    return fm.Grid(
        timestamp=timestamp(msg.header.stamp),
        frame_id=msg.header.frame_id,
        pose=pose(info.origin),
        column_count=info.width,
        cell_size=fm.Vector2(x=info.resolution, y=info.resolution),
        row_stride=info.width,
        cell_stride=1,
        fields=[fm.PackedElementField(name="occupancy", offset=0, type=_INT8)],
        data=cells.tobytes(),
    )


def cost_grid(costs: CostGrid, stamp: float, frame_id: str = "map") -> fm.Grid:
    """A costmap (uint8 Nav2 costs: 0 free .. 253 inscribed, 254 lethal, 255 unknown) as a
    one-field uint8 Grid."""
    g = costs.geometry
    return fm.Grid(
        timestamp=timestamp(stamp),
        frame_id=frame_id,
        pose=pose(AiobtPose.from_xy_yaw(g.origin_x, g.origin_y)),
        column_count=g.width,
        cell_size=fm.Vector2(x=g.resolution, y=g.resolution),
        row_stride=g.width,
        cell_stride=1,
        fields=[fm.PackedElementField(name="cost", offset=0, type=_UINT8)],
        data=np.ascontiguousarray(costs.costs, dtype=np.uint8).tobytes(),
    )


def laser_scan(msg: LaserScan) -> fm.LaserScan:
    # Foxglove spaces the ranges evenly between start and end: end is the last ray's bearing
    end = msg.angle_min + msg.angle_increment * max(len(msg.ranges) - 1, 0)
    return fm.LaserScan(
        timestamp=timestamp(msg.header.stamp),
        frame_id=msg.header.frame_id,
        pose=pose(AiobtPose()),
        start_angle=msg.angle_min,
        end_angle=end,
        ranges=[r if math.isfinite(r) else math.inf for r in msg.ranges],
        intensities=list(msg.intensities),
    )


def pose_in_frame(msg: PoseStamped) -> fm.PoseInFrame:
    return fm.PoseInFrame(
        timestamp=timestamp(msg.header.stamp), frame_id=msg.header.frame_id, pose=pose(msg.pose)
    )


def poses_in_frame(msg: Path) -> fm.PosesInFrame:
    return fm.PosesInFrame(
        timestamp=timestamp(msg.header.stamp),
        frame_id=msg.header.frame_id,
        poses=[pose(p.pose) for p in msg.poses],
    )


def particle_cloud(msg: ParticleCloud) -> fm.PosesInFrame:
    """The localization's particles as poses (RViz draws ``nav2_msgs/ParticleCloud`` as
    arrows; the 3D panel draws PosesInFrame so)."""
    return fm.PosesInFrame(
        timestamp=timestamp(msg.header.stamp),
        frame_id=msg.header.frame_id,
        poses=[pose(p.pose) for p in msg.particles],
    )


def odometry(msg: Odometry) -> fm.Odometry:
    lin, ang = msg.twist.linear, msg.twist.angular
    return fm.Odometry(
        timestamp=timestamp(msg.header.stamp),
        frame_id=msg.header.frame_id,
        body_frame_id=msg.child_frame_id,
        pose=pose(msg.pose),
        linear_velocity=fm.Vector3(x=lin.x, y=lin.y, z=lin.z),
        angular_velocity=fm.Vector3(x=ang.x, y=ang.y, z=ang.z),
    )


def _transform(stamp: float, parent: str, child: str, p: AiobtPose) -> fm.FrameTransform:
    q = p.orientation
    return fm.FrameTransform(
        timestamp=timestamp(stamp),
        parent_frame_id=parent,
        child_frame_id=child,
        translation=fm.Vector3(x=p.position.x, y=p.position.y, z=p.position.z),
        rotation=fm.Quaternion(x=q.x, y=q.y, z=q.z, w=q.w),
    )


def map_to_odom(map_pose: PoseStamped, odom: Odometry) -> AiobtPose:
    """The ``map -> odom`` transform that puts ``odom``'s body at ``map_pose`` (2-D)."""
    yaw = map_pose.pose.yaw - odom.pose.yaw
    ox, oy = odom.pose.position.x, odom.pose.position.y
    c, s = math.cos(yaw), math.sin(yaw)
    x = map_pose.pose.position.x - (c * ox - s * oy)
    y = map_pose.pose.position.y - (s * ox + c * oy)
    return AiobtPose.from_xy_yaw(x, y, yaw)


def transforms(
    map_pose: PoseStamped | None, odom: Odometry | None, scan_frame: str | None
) -> fm.FrameTransforms:
    """``map -> odom -> base_link`` (and ``base_link -> scan_frame`` at the centre, where
    the robot's lidar sits) from what is known so far; with no odometry yet, map -> odom
    is the identity and odom -> base_link follows the map pose."""
    out: list[fm.FrameTransform] = []
    body = odom.child_frame_id if odom is not None else "base_link"
    if odom is not None:
        stamp = odom.header.stamp
        link = map_to_odom(map_pose, odom) if map_pose is not None else AiobtPose()
        out.append(_transform(stamp, "map", odom.header.frame_id, link))
        out.append(_transform(stamp, odom.header.frame_id, body, odom.pose))
    elif map_pose is not None:
        stamp = map_pose.header.stamp
        out.append(_transform(stamp, "map", "odom", AiobtPose()))
        out.append(_transform(stamp, "odom", body, map_pose.pose))
    if out and scan_frame and scan_frame != body:
        out.append(_transform(stamp, body, scan_frame, AiobtPose()))
    return fm.FrameTransforms(transforms=out)


def footprint(stamp: float, radius: float, frame_id: str = "base_link") -> fm.SceneUpdate:
    """The robot's round footprint and a heading arrow, locked to ``frame_id``."""
    n = 32
    angles = [2 * math.pi * i / n for i in range(n)]
    ring = [fm.Point3(x=radius * math.cos(a), y=radius * math.sin(a)) for a in angles]
    blue = fm.Color(r=0.2, g=0.5, b=1.0, a=1.0)
    entity = fm.SceneEntity(
        timestamp=timestamp(stamp),
        frame_id=frame_id,
        id="footprint",
        frame_locked=True,
        lines=[
            fm.LinePrimitive(
                type=fm.LinePrimitiveLineType.LineLoop,
                pose=pose(AiobtPose()),
                thickness=0.02,
                points=ring,
                color=blue,
            )
        ],
        arrows=[
            fm.ArrowPrimitive(
                pose=pose(AiobtPose()),
                shaft_length=radius,
                shaft_diameter=0.03,
                head_length=0.08,
                head_diameter=0.08,
                color=blue,
            )
        ],
    )
    return fm.SceneUpdate(entities=[entity])


def as_json(msg: Msg) -> dict[str, Any]:
    """A message for a JSON channel (raw messages panel, plots)."""
    return msg.model_dump(mode="json")


def transition_logs(msg: BtTransitions, tree: BtTree | None) -> list[fm.Log]:
    """One Log line per node status change; node names from the latest tree."""
    names = {n.uid: n.path for n in tree.nodes} if tree is not None and tree.run == msg.run else {}
    return [
        fm.Log(
            timestamp=timestamp(t.stamp),
            level=_LEVELS.get(t.status, fm.LogLevel.Info),
            message=f"{names.get(t.uid, f'node {t.uid}')}: {t.previous} -> {t.status}",
            name="navigator.bt",
        )
        for t in msg.transitions
    ]


def speed(msg: Odometry) -> dict[str, float]:
    """The odometry's speeds for a plot: forward, turn rate and planar speed."""
    lin = msg.twist.linear
    return {
        "stamp": msg.header.stamp,
        "linear": lin.x,
        "angular": msg.twist.angular.z,
        "speed": math.hypot(lin.x, lin.y),
    }


def route_graph(msg: RouteGraph) -> fm.SceneUpdate:
    """The route server's graph: every lane as a line, every node as a dot, in ``map``."""
    green = fm.Color(r=0.3, g=0.75, b=0.35, a=1.0)
    lanes = [fm.Point3(x=p.x, y=p.y) for e in msg.edges for p in (e.start, e.end)]
    dots = [fm.Point3(x=n.position.x, y=n.position.y) for n in msg.nodes]
    entity = fm.SceneEntity(
        timestamp=timestamp(msg.header.stamp),
        frame_id=msg.header.frame_id or "map",
        id="route_graph",
        lines=[
            fm.LinePrimitive(type=fm.LinePrimitiveLineType.LineList, pose=pose(AiobtPose()),
                             thickness=0.03, points=lanes, color=green),
            fm.LinePrimitive(type=fm.LinePrimitiveLineType.LineList, pose=pose(AiobtPose()),
                             thickness=0.15, points=[q for d in dots for q in (d, d)], color=green),
        ],
    )  # fmt: skip
    return fm.SceneUpdate(entities=[entity])


def docks(msg: DockList, stamp: float) -> fm.SceneUpdate:
    """The docking server's docks (dark green, pointing into the dock) and their staging
    poses (light green), as arrows in ``map``."""

    def arrow(p: PoseStamped, length: float, green: float) -> fm.ArrowPrimitive:
        return fm.ArrowPrimitive(pose=pose(p.pose), shaft_length=length, shaft_diameter=0.04,
                                 head_length=0.1, head_diameter=0.12,
                                 color=fm.Color(r=0.15, g=green, b=0.2, a=1.0))  # fmt: skip

    arrows = [arrow(d.pose, 0.3, 0.5) for d in msg.docks]
    arrows += [arrow(d.staging, 0.2, 0.85) for d in msg.docks if d.staging is not None]
    entity = fm.SceneEntity(timestamp=timestamp(stamp), frame_id="map", id="docks", arrows=arrows)
    return fm.SceneUpdate(entities=[entity])
