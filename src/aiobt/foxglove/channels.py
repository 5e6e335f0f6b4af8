"""The Foxglove channels the bridge writes, one per topic, in one Foxglove context.

Topic names (what Foxglove shows and the shipped layout uses):

====================  ===========================  =====================================
topic                 schema                       from (under the namespace ``ns``)
====================  ===========================  =====================================
/map                  foxglove.Grid                ``{ns}/map`` (latched)
/global_costmap       foxglove.Grid                ``{ns}/map``, ``pose``, ``scan`` (mirrored)
/scan                 foxglove.LaserScan           ``{ns}/scan``
/pose                 foxglove.PoseInFrame         ``{ns}/pose``
/odom                 foxglove.Odometry            ``{ns}/odom``
/tf                   foxglove.FrameTransforms     ``{ns}/pose`` and ``{ns}/odom``
/robot                foxglove.SceneUpdate         the footprint, at every pose
/plan                 foxglove.PosesInFrame        ``compute_path_to_pose`` results
/route                foxglove.PosesInFrame        ``compute_route`` results (the route server)
/route_graph          foxglove.SceneUpdate         ``{ns}/route_graph`` (latched): lanes, nodes
/docks                foxglove.SceneUpdate         ``{ns}/docks`` (latched): docks, staging poses
/local_plan           foxglove.PosesInFrame        ``{ns}/local_plan`` (the controller)
/local_costmap        foxglove.Grid                ``{ns}/local_costmap/costmap``
/goal                 foxglove.PoseInFrame         ``{ns}/goal_pose`` and navigation goals
/navigator/feedback   JSON                         ``navigate_to_pose`` feedback
/odom/speed           JSON                         ``{ns}/odom`` (speed, for the plot)
/log                  foxglove.Log                 ``{ns}/bt/transitions`` + bridge lines
/collision_monitor    foxglove.SceneUpdate         ``{ns}/collision_monitor/polygons``
/particle_cloud       foxglove.PosesInFrame        ``{ns}/particle_cloud`` (localization)
/amcl_pose            foxglove.PoseInFrame         ``{ns}/amcl_pose`` (localization, latched)
/sim/pose             foxglove.PoseInFrame         ``{ns}/sim/pose``: the simulation's truth
                                                   (not in the navigator's recordings)
/followed             foxglove.PoseInFrame         ``{ns}/filtered_dynamic_pose`` (following)
====================  ===========================  =====================================
"""

from __future__ import annotations

from dataclasses import dataclass

import foxglove
from foxglove import channels as fc

from aiobt.msgs import NavigateToPose

GOAL_TOPIC = "/goal_pose"  # the client channel a Publish panel sends goals on
INITIALPOSE_TOPIC = "/initialpose"  # the one the 3D panel's pose estimate tool sends on

# JSON schemas: Foxglove's message path editor (plots, raw messages) offers the fields
_FEEDBACK = {
    **NavigateToPose.feedback_type().model_json_schema(),
    "title": "aiobt.NavigateToPose.Feedback",
}
_SPEED = {
    "type": "object",
    "title": "aiobt.OdomSpeed",
    "properties": {
        "stamp": {"type": "number", "description": "robot clock, s"},
        "linear": {"type": "number", "description": "forward speed, m/s"},
        "angular": {"type": "number", "description": "turn rate, rad/s"},
        "speed": {"type": "number", "description": "planar speed, m/s"},
    },
}


@dataclass(slots=True)
class Channels:
    map: fc.GridChannel
    costmap: fc.GridChannel
    scan: fc.LaserScanChannel
    pose: fc.PoseInFrameChannel
    odom: fc.OdometryChannel
    tf: fc.FrameTransformsChannel
    robot: fc.SceneUpdateChannel
    plan: fc.PosesInFrameChannel
    route: fc.PosesInFrameChannel
    route_graph: fc.SceneUpdateChannel
    docks: fc.SceneUpdateChannel
    local_plan: fc.PosesInFrameChannel
    local_costmap: fc.GridChannel
    goal: fc.PoseInFrameChannel
    feedback: foxglove.Channel
    speed: foxglove.Channel
    log: fc.LogChannel
    zones: fc.SceneUpdateChannel
    particles: fc.PosesInFrameChannel
    amcl_pose: fc.PoseInFrameChannel
    truth: fc.PoseInFrameChannel
    followed: fc.PoseInFrameChannel

    @classmethod
    def create(cls, context: foxglove.Context) -> Channels:
        c = context
        return cls(
            map=fc.GridChannel("/map", context=c),
            costmap=fc.GridChannel("/global_costmap", context=c),
            scan=fc.LaserScanChannel("/scan", context=c),
            pose=fc.PoseInFrameChannel("/pose", context=c),
            odom=fc.OdometryChannel("/odom", context=c),
            tf=fc.FrameTransformsChannel("/tf", context=c),
            robot=fc.SceneUpdateChannel("/robot", context=c),
            plan=fc.PosesInFrameChannel("/plan", context=c),
            route=fc.PosesInFrameChannel("/route", context=c),
            route_graph=fc.SceneUpdateChannel("/route_graph", context=c),
            docks=fc.SceneUpdateChannel("/docks", context=c),
            local_plan=fc.PosesInFrameChannel("/local_plan", context=c),
            local_costmap=fc.GridChannel("/local_costmap", context=c),
            goal=fc.PoseInFrameChannel("/goal", context=c),
            feedback=foxglove.Channel("/navigator/feedback", schema=_FEEDBACK, context=c),
            speed=foxglove.Channel("/odom/speed", schema=_SPEED, context=c),
            log=fc.LogChannel("/log", context=c),
            zones=fc.SceneUpdateChannel("/collision_monitor", context=c),
            particles=fc.PosesInFrameChannel("/particle_cloud", context=c),
            amcl_pose=fc.PoseInFrameChannel("/amcl_pose", context=c),
            truth=fc.PoseInFrameChannel("/sim/pose", context=c),
            followed=fc.PoseInFrameChannel("/followed", context=c),
        )

    def topics(self) -> set[str]:
        """Every channel's topic."""
        return {getattr(self, name).topic() for name in self.__dataclass_fields__}
