"""The bridge: the robot's topics under one namespace -> Foxglove channels.

:class:`FoxgloveBridge` subscribes over :mod:`aiobt.transport` and writes each
message, converted by :mod:`aiobt.foxglove.convert`, to its channel of
:class:`~aiobt.foxglove.channels.Channels`. Whatever sinks the channels' context
has (the WebSocket server, an MCAP file) get them. Goals a Foxglove client
publishes arrive through :meth:`forward_goal` and go to ``{ns}/goal_pose``; pose
estimates (the 3D panel's tool) through :meth:`forward_initialpose` to ``{ns}/initialpose``.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from typing import Any, TypeVar

import foxglove
from foxglove import messages as fm

from aiobt.foxglove import convert, inbound
from aiobt.foxglove.channels import Channels
from aiobt.foxglove.costmap import CostmapMirror
from aiobt.foxglove.zones import zones_scene
from aiobt.msgs import (
    BtTransitions,
    BtTree,
    ComputePathToPose,
    LaserScan,
    MessageError,
    NavigateToPose,
    OccupancyGrid,
    Odometry,
    ParticleCloud,
    Path,
    PoseStamped,
    PoseWithCovarianceStamped,
)
from aiobt.msgs.docking import DockList
from aiobt.msgs.remote_actions import ComputeRoute
from aiobt.msgs.route_graph import RouteGraph
from aiobt.msgs.safety import CollisionPolygons
from aiobt.transport import Bus, Publisher, Subscription
from aiobt.transport.keys import SIM_POSE
from aiobt.transport.topics import declare_subscription

log = logging.getLogger("aiobt.foxglove.bridge")

Forwarded = TypeVar("Forwarded", PoseStamped, PoseWithCovarianceStamped)
DEFAULT_FOOTPRINT_RADIUS = 0.22  # m: the robot service's body
DEFAULT_COSTMAP_PERIOD = 1.0  # s of robot time between costmap updates


class FoxgloveBridge:
    """Feeds ``channels`` from ``bus``; :meth:`close` ends the subscriptions.

    ``truth``: bridge the simulation's truth (``{ns}/sim/pose``) too. A viewer may read
    it; the navigator's own recording (in a navigation service) does not.
    """

    def __init__(
        self,
        bus: Bus,
        context: foxglove.Context,
        footprint_radius: float = DEFAULT_FOOTPRINT_RADIUS,
        costmap_period: float = DEFAULT_COSTMAP_PERIOD,
        forwards_goals: bool = True,
        truth: bool = True,
    ) -> None:
        if not footprint_radius > 0.0 or not math.isfinite(footprint_radius):
            raise ValueError(f"footprint radius must be > 0 m, not {footprint_radius!r}")
        self.bus = bus
        self.ch = Channels.create(context)
        self.radius = footprint_radius
        self.truth = truth
        # declared up front: a put right after a publisher's declaration may be lost
        self.goals: Publisher[PoseStamped] | None = None
        self.initialposes: Publisher[PoseWithCovarianceStamped] | None = None
        if forwards_goals:
            self.goals = bus.publisher("goal_pose", PoseStamped, reliable=True)
            self.initialposes = bus.publisher(
                "initialpose", PoseWithCovarianceStamped, reliable=True
            )
        self.costmap = CostmapMirror(costmap_period) if costmap_period > 0.0 else None
        self._pose: PoseStamped | None = None
        self._odom: Odometry | None = None
        self._scan_frame: str | None = None
        self._tree: BtTree | None = None
        self._subs: list[Subscription[Any]] = []

    def start(self) -> None:
        bus, add = self.bus, self._subs.append
        add(bus.subscribe("map", OccupancyGrid, self.on_map, latched=True, queue_size=1))
        add(bus.subscribe("scan", LaserScan, self.on_scan, queue_size=2))
        add(bus.subscribe("pose", PoseStamped, self.on_pose, queue_size=2))
        add(bus.subscribe("odom", Odometry, self.on_odom, queue_size=2))
        add(bus.subscribe("goal_pose", PoseStamped, self.on_goal, queue_size=10))
        add(bus.subscribe("local_plan", Path, self.on_local_plan, queue_size=2))
        add(bus.subscribe("local_costmap/costmap", OccupancyGrid, self.on_local_costmap))
        add(bus.subscribe("bt/tree", BtTree, self.on_tree, latched=True, queue_size=1))
        add(bus.subscribe("bt/transitions", BtTransitions, self.on_transitions))
        add(bus.subscribe("collision_monitor/polygons", CollisionPolygons, self.on_zones,
                          latched=True, queue_size=1))  # fmt: skip
        add(bus.subscribe("particle_cloud", ParticleCloud, self.on_particles, queue_size=2))
        add(bus.subscribe("amcl_pose", PoseWithCovarianceStamped, self.on_amcl_pose,
                          latched=True, queue_size=1))  # fmt: skip
        if self.truth:
            add(bus.subscribe(SIM_POSE, PoseStamped, self.on_truth, queue_size=2))
        plans = bus.keys.action(ComputePathToPose.name).any_result
        feedback = bus.keys.action(NavigateToPose.name).any_feedback
        add(self._watch(plans, ComputePathToPose.result_type(), self.on_plan))
        routes = bus.keys.action(ComputeRoute.name).any_result
        add(self._watch(routes, ComputeRoute.result_type(), self.on_route))
        add(bus.subscribe("route_graph", RouteGraph, self.on_route_graph, latched=True))
        add(bus.subscribe("docks", DockList, self.on_docks, latched=True))
        add(self._watch(feedback, NavigateToPose.feedback_type(), self.on_feedback))
        add(bus.subscribe("filtered_dynamic_pose", PoseStamped, self.on_followed, queue_size=2))
        self.note(f"bridging namespace '{bus.namespace}'")

    def _watch(self, key: str, model: Any, callback: Any) -> Subscription[Any]:
        return declare_subscription(
            self.bus.session, self.bus.bridge, key, model,
            callback_fn=callback, latched=False, queue_size=10,
        )  # fmt: skip

    def close(self) -> None:
        for sub in self._subs:
            sub.close()
        self._subs.clear()

    # -- bus -> Foxglove -----------------------------------------------------------------
    def on_map(self, msg: OccupancyGrid) -> None:
        self.ch.map.log(convert.grid(msg))
        if self.costmap is not None:
            self.costmap.on_map(msg)

    def on_scan(self, msg: LaserScan) -> None:
        new_frame = msg.header.frame_id != self._scan_frame
        self._scan_frame = msg.header.frame_id
        if new_frame:
            self._transforms()
        self.ch.scan.log(convert.laser_scan(msg))
        costs = self.costmap.on_scan(msg) if self.costmap is not None else None
        if costs is not None:
            self.ch.costmap.log(convert.cost_grid(costs, msg.header.stamp))

    def on_pose(self, msg: PoseStamped) -> None:
        self._pose = msg
        if self.costmap is not None:
            self.costmap.on_pose(msg)
        self.ch.pose.log(convert.pose_in_frame(msg))
        self.ch.robot.log(convert.footprint(msg.header.stamp, self.radius))
        self._transforms()

    def on_particles(self, msg: ParticleCloud) -> None:
        self.ch.particles.log(convert.particle_cloud(msg))

    def on_amcl_pose(self, msg: PoseWithCovarianceStamped) -> None:
        self.ch.amcl_pose.log(convert.pose_in_frame(msg.as_pose_stamped()))

    def on_truth(self, msg: PoseStamped) -> None:
        self.ch.truth.log(convert.pose_in_frame(msg))

    def on_zones(self, msg: CollisionPolygons) -> None:
        self.ch.zones.log(zones_scene(msg))

    def on_odom(self, msg: Odometry) -> None:
        self._odom = msg
        self.ch.odom.log(convert.odometry(msg))
        self.ch.speed.log(convert.speed(msg))
        self._transforms()

    def _transforms(self) -> None:
        tf = convert.transforms(self._pose, self._odom, self._scan_frame)
        self.ch.tf.log(tf)

    def on_goal(self, msg: PoseStamped) -> None:
        self.ch.goal.log(convert.pose_in_frame(msg))

    def on_plan(self, result: Any) -> None:
        if result.error_code == 0 and result.path.poses:
            self.ch.plan.log(convert.poses_in_frame(result.path))

    def on_route(self, result: Any) -> None:
        if result.error_code == 0 and result.path.poses:
            self.ch.route.log(convert.poses_in_frame(result.path))

    def on_route_graph(self, msg: RouteGraph) -> None:
        self.ch.route_graph.log(convert.route_graph(msg))

    def on_followed(self, msg: PoseStamped) -> None:
        """The object the following server follows, in its fixed frame (placed by /tf)."""
        self.ch.followed.log(convert.pose_in_frame(msg))

    def on_docks(self, msg: DockList) -> None:
        stamp = self._pose.header.stamp if self._pose is not None else 0.0
        self.ch.docks.log(convert.docks(msg, stamp))

    def on_local_plan(self, msg: Path) -> None:
        """The controller's local plan; an empty one (its goal ended) clears the panel's."""
        self.ch.local_plan.log(convert.poses_in_frame(msg))

    def on_local_costmap(self, msg: OccupancyGrid) -> None:
        self.ch.local_costmap.log(convert.grid(msg))

    def on_feedback(self, feedback: Any) -> None:
        self.ch.feedback.log(convert.as_json(feedback))

    def on_tree(self, tree: BtTree) -> None:
        self._tree = tree
        self.note(f"tree {tree.tree_id} (run {tree.run}, {len(tree.nodes)} nodes) {tree.source}")

    def on_transitions(self, msg: BtTransitions) -> None:
        for line in convert.transition_logs(msg, self._tree):
            self.ch.log.log(line)

    def note(self, text: str, level: fm.LogLevel = fm.LogLevel.Info) -> None:
        """A line of the bridge's own on ``/log`` (and in the Python log)."""
        log.log(logging.WARNING if level == fm.LogLevel.Warning else logging.INFO, "%s", text)
        stamp = self._pose.header.stamp if self._pose is not None else 0.0
        self.ch.log.log(
            fm.Log(timestamp=convert.timestamp(stamp), level=level, message=text, name="foxglove")
        )

    # -- Foxglove -> bus -----------------------------------------------------------------
    def forward_goal(self, payload: bytes, topic: str) -> None:
        """A goal a Foxglove client published: on ``{ns}/goal_pose``, or a warning."""
        self._forward("goal", topic, payload, inbound.goal_from_json, self.goals)

    def forward_initialpose(self, payload: bytes, topic: str) -> None:
        """A pose estimate a Foxglove client published: on ``{ns}/initialpose`` (for the
        localization, as RViz's "2D Pose Estimate"), or a warning."""
        self._forward(
            "initialpose", topic, payload, inbound.initialpose_from_json, self.initialposes
        )

    def _forward(
        self, what: str, topic: str, payload: bytes,
        parse: Callable[[bytes], Forwarded], publisher: Publisher[Forwarded] | None,
    ) -> None:  # fmt: skip
        try:
            msg = parse(payload)
        except (MessageError, ValueError) as exc:
            self.note(f"{what} on {topic} refused: {exc}", fm.LogLevel.Warning)
            return
        if publisher is None:
            self.note(f"{what} on {topic} refused: this bridge only records", fm.LogLevel.Warning)
            return
        publisher.put(msg)
        self.note(f"{what} from Foxglove: ({msg.x:.2f}, {msg.y:.2f}) in {msg.header.frame_id}")
