"""The bus side of the web view: what the robot's topics say, converted at the page's pace.

Every message only replaces the newest one of its stream (:class:`Latest`);
:meth:`Sources.flush`, called at the page's update rate, converts what changed
since the last flush and hands it to the :class:`Hub`. Streams:

=============  ==========================================================
``map``        ``{ns}/map`` (latched), sent when it changes
``costmap``    the map inflated as the planner's global costmap, with it
``pose``       ``{ns}/pose``
``truth``      ``{ns}/sim/pose``: the simulation's truth, beside the estimate (a
               viewer may read it; no navigation service does)
``amcl_pose``  ``{ns}/amcl_pose`` (latched): the localization's estimate with
               its covariance
``particles``  ``{ns}/particle_cloud``: the localization's particles (map frame)
``scan``       ``{ns}/scan``, as map-frame points seen from the latest pose
``local``      ``{ns}/cmd_vel`` driven for 1.5 s from the pose (where the
               current command alone takes the robot)
``local_plan`` ``{ns}/local_plan``: the trajectory the controller follows (its
               local plan; empty when its goal ended), map-frame plans only
``local_costmap`` ``{ns}/local_costmap/costmap``: the controller's rolling
               window (Nav2's occupancy values), at the controller's 2 Hz
``zones``      ``{ns}/collision_monitor/polygons`` (latched) placed at the pose:
               the collision monitor's polygons, the acting one marked
``plan``       the planner's latest path (``compute_path_to_pose`` and
               ``compute_path_through_poses`` results)
``route``      the route server's latest dense path (``compute_route`` results)
``route_graph`` ``{ns}/route_graph`` (latched): the route server's graph
``followed``   ``{ns}/filtered_dynamic_pose``: the object the following server
               follows, put in ``map`` (:mod:`aiobt.web.followed`)
``docks``       ``{ns}/docks`` (latched): the docking server's docks and staging poses
``feedback``   navigate_to_pose / navigate_through_poses feedback
``tree``       ``{ns}/bt/tree``; ``status`` from ``bt/transitions`` and
``nav``        ``bt/snapshot`` (the navigation's state, and the goal it
               drives to: the navigator's, however it was sent)
=============  ==========================================================
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from aiobt.costmap.inflation import InflationParams
from aiobt.msgs import (
    ActionDef,
    ComputePathThroughPoses,
    ComputePathToPose,
    LaserScan,
    Msg,
    NavigateThroughPoses,
    NavigateToPose,
    OccupancyGrid,
    Odometry,
    ParticleCloud,
    Path,
    PoseStamped,
    PoseWithCovarianceStamped,
    Twist,
)
from aiobt.msgs.bt import BtSnapshot, BtTransitions, BtTree
from aiobt.msgs.docking import DockList
from aiobt.msgs.remote_actions import ComputeRoute
from aiobt.msgs.route_graph import RouteGraph
from aiobt.msgs.safety import CollisionPolygons
from aiobt.transport import Bus, Subscription
from aiobt.transport.keys import SIM_POSE
from aiobt.transport.topics import declare_subscription
from aiobt.web import convert, followed
from aiobt.web.coalesce import Hub, Latest
from aiobt.web.tree import TreeStatus

log = logging.getLogger("aiobt.web.sources")
GOAL_TIMEOUT = 2.0  # s for a navigator to subscribe to goal_pose before a click is refused
_PLANNERS: tuple[type[ActionDef[Any, Any, Any]], ...] = (ComputePathToPose, ComputePathThroughPoses)
_NAVIGATORS: tuple[type[ActionDef[Any, Any, Any]], ...] = (NavigateToPose, NavigateThroughPoses)


@dataclass(slots=True)
class _Robot:
    """The latest messages conversions combine."""

    pose: PoseStamped | None = None
    command: Twist = field(default_factory=Twist)
    grid: OccupancyGrid | None = None
    zones: CollisionPolygons | None = None


class Sources:
    """Subscribes to the robot's topics on ``bus`` and feeds ``hub`` on :meth:`flush`."""

    def __init__(self, bus: Bus, hub: Hub, inflation: InflationParams | None = None) -> None:
        self.bus = bus
        self.hub = hub
        self.inflation = inflation or InflationParams()
        self.raw: Latest[Msg] = Latest()
        self.tree = TreeStatus()
        self._robot = _Robot()
        self._tree_changed = False
        self._skipped_frames: set[tuple[str, str]] = set()
        self._subs: list[Subscription[Any]] = []
        self._goal_pub = bus.publisher("goal_pose", PoseStamped, reliable=True)
        self._odom = bus.latest("odom", Odometry)  # read only to place a followed object

    def attach(self) -> None:
        # the robot is drawn as its inscribed circle, the radius the costmap is inflated with
        self.hub.publish("footprint", {"radius": self.inflation.inscribed_radius})
        topics: list[tuple[str, type[Msg], bool]] = [
            ("map", OccupancyGrid, True), ("pose", PoseStamped, False),
            ("scan", LaserScan, False), ("cmd_vel", Twist, False),
            ("bt/snapshot", BtSnapshot, False),
            ("local_plan", Path, False), ("local_costmap/costmap", OccupancyGrid, False),
            ("collision_monitor/polygons", CollisionPolygons, True),
            ("route_graph", RouteGraph, True), ("docks", DockList, True),
            (SIM_POSE, PoseStamped, False), ("particle_cloud", ParticleCloud, False),
            ("amcl_pose", PoseWithCovarianceStamped, True),
            (followed.TOPIC, PoseStamped, False),
        ]  # fmt: skip
        for name, model, latched in topics:
            sub = self.bus.subscribe(
                name, model, self._keep(name), latched=latched, queue_size=1
            )  # fmt: skip
            self._subs.append(sub)
        self._subs.append(self.bus.subscribe("bt/tree", BtTree, self._on_tree, latched=True))
        self._subs.append(self.bus.subscribe("bt/transitions", BtTransitions, self._on_changes))
        for planner in _PLANNERS:
            self._watch(
                self.bus.keys.action(planner.name).any_result, planner.result_type(), "plan"
            )
        route_results = self.bus.keys.action(ComputeRoute.name).any_result
        self._watch(route_results, ComputeRoute.result_type(), "route")
        for navigator in _NAVIGATORS:
            keys = self.bus.keys.action(navigator.name)
            self._watch(keys.any_feedback, navigator.feedback_type(), "feedback")

    def _watch(self, key: str, model: type[Msg], stream: str) -> None:
        sub = declare_subscription(
            self.bus.session, self.bus.bridge, key, model,
            callback_fn=self._keep(stream), latched=False, queue_size=1,
        )  # fmt: skip
        self._subs.append(sub)

    def _keep(self, stream: str) -> Callable[[Msg], None]:
        return lambda message: self.raw.set(stream, message)

    def _on_tree(self, tree: BtTree) -> None:
        self.hub.publish("tree", self.tree.on_tree(tree))
        self._tree_changed = True

    def _on_changes(self, message: BtTransitions) -> None:
        self._tree_changed |= self.tree.on_transitions(message)

    def flush(self) -> None:
        """Convert what changed since the last flush and publish it to the hub."""
        fresh = self.raw.drain()
        for stream, message in fresh.items():
            try:
                self._convert(stream, message)
            except (ValueError, TypeError, ArithmeticError) as exc:
                log.warning("%s: message not shown: %s", stream, exc)
        if "pose" in fresh or "cmd_vel" in fresh:
            self._publish_local()
        if "pose" in fresh or "collision_monitor/polygons" in fresh:
            self._publish_zones()
        if self._tree_changed:
            self._tree_changed = False
            self.hub.publish("status", self.tree.payload())

    def _convert(self, stream: str, message: Msg) -> None:
        robot = self._robot
        if stream == "local_costmap/costmap" and isinstance(message, OccupancyGrid):
            self.hub.publish("local_costmap", convert.map_payload(message))
        elif isinstance(message, OccupancyGrid):
            self._on_map(message)
        elif isinstance(message, Path):
            self._on_local_plan(message)
        elif stream == "pose" and isinstance(message, PoseStamped):
            robot.pose = message
            self.hub.publish("pose", convert.pose_payload(message))
        elif stream == SIM_POSE and isinstance(message, PoseStamped):
            self.hub.publish("truth", convert.pose_payload(message))
        elif isinstance(message, ParticleCloud):
            if self._in_map_frame("particle_cloud", message.header.frame_id):
                self.hub.publish("particles", convert.particles_payload(message))
        elif isinstance(message, PoseWithCovarianceStamped):
            if self._in_map_frame("amcl_pose", message.header.frame_id):
                self.hub.publish("amcl_pose", convert.estimate_payload(message))
        elif stream == followed.TOPIC and isinstance(message, PoseStamped):
            where = followed.followed_in_map(message, robot.pose, self._odom.get())
            if where is not None:
                self.hub.publish("followed", followed.followed_payload(where, message.header.stamp))
        elif isinstance(message, LaserScan) and robot.pose is not None:
            self.hub.publish("scan", convert.scan_points(message, robot.pose))
        elif isinstance(message, Twist):
            robot.command = message
        elif isinstance(message, CollisionPolygons):
            robot.zones = message
        elif isinstance(message, BtSnapshot):
            self._tree_changed |= self.tree.on_snapshot(message)
            self.hub.publish("nav", convert.navigation_payload(message))
        elif isinstance(message, ComputePathToPose.Result) and message.error_code == 0:
            self.hub.publish("plan", convert.path_points(message.path))
        elif stream == "route" and isinstance(message, ComputeRoute.Result):
            if message.error_code == 0:
                self.hub.publish("route", convert.path_points(message.path))
        elif isinstance(message, RouteGraph):
            self.hub.publish("route_graph", convert.route_graph_payload(message), on_change=True)
        elif isinstance(message, DockList):
            self.hub.publish("docks", convert.docks_payload(message), on_change=True)
        elif stream == "feedback":
            self.hub.publish("feedback", _feedback(message))

    def _on_map(self, grid: OccupancyGrid) -> None:
        if self._robot.grid is not None and self._robot.grid == grid:
            return
        self._robot.grid = grid
        self.hub.publish("map", convert.map_payload(grid), on_change=True)
        self.hub.publish("costmap", convert.costmap_payload(grid, self.inflation), on_change=True)

    def _on_local_plan(self, path: Path) -> None:
        if self._in_map_frame("local_plan", path.header.frame_id):
            self.hub.publish("local_plan", convert.path_points(path))

    def _in_map_frame(self, stream: str, frame: str) -> bool:
        """The page draws in the map frame (a plan in odom would drift): any other frame
        is said once per stream and frame, and not drawn."""
        if frame == "map":
            return True
        if (stream, frame) not in self._skipped_frames:
            self._skipped_frames.add((stream, frame))
            log.warning("%s in frame %r not shown (map-frame only)", stream, frame)
        return False

    def _publish_local(self) -> None:
        if self._robot.pose is not None:
            self.hub.publish("local", convert.rollout(self._robot.pose, self._robot.command))

    def _publish_zones(self) -> None:
        robot = self._robot
        if robot.pose is not None and robot.zones is not None:
            self.hub.publish("zones", convert.zones_payload(robot.zones, robot.pose))

    async def send_goal(self, x: float, y: float, yaw: float) -> str:
        """Put a goal on ``{ns}/goal_pose``; "" when sent, else why not."""
        if not all(math.isfinite(v) for v in (x, y, yaw)):
            return f"goal ({x}, {y}, {yaw}): x, y and yaw must be finite numbers"
        # this view's own goal_pose subscription matches too: ask for the navigator itself
        navigator = self.bus.presence(self.bus.keys.topic("nodes/navigator"))
        if not await navigator.wait(GOAL_TIMEOUT):
            return f"{self.bus.namespace}: no navigator is up (nodes/navigator) to take the goal"
        self._goal_pub.put(PoseStamped.from_xy_yaw(x, y, yaw))
        log.info("goal (%.2f, %.2f, yaw %.2f) sent on %s/goal_pose", x, y, yaw, self.bus.namespace)
        return ""

    def close(self) -> None:
        for sub in reversed(self._subs):
            sub.close()
        self._subs.clear()
        self._goal_pub.close()


def _feedback(message: Msg) -> convert.Json:
    data = message.model_dump(mode="json")
    current = data.pop("current_pose", None)
    if current is not None:
        position = current["pose"]["position"]
        data["x"], data["y"] = round(position["x"], 3), round(position["y"], 3)
    return {"recoveries": data.pop("number_of_recoveries", 0), **data}
