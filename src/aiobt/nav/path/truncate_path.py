"""TruncatePath (Nav2): cut a path short of its goal."""

from __future__ import annotations

import math

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import SUCCESS, Status
from aiobt.msgs import Path, PoseStamped, Quaternion
from aiobt.nav.path_math import distance


class TruncatePath(SyncActionNode):
    """``<TruncatePath distance="1.0" input_path="{path}" output_path="{truncated}"/>`` (Nav2).

    Always SUCCESS. Drops the poses within ``distance`` of the goal (keeping
    at least two), then points the new last pose along the line from it to
    the original goal. An empty path is passed through.
    """

    __slots__ = ()
    PORTS = (
        input_port("input_path", Path, description="The original path to be truncated."),
        input_port(
            "distance", float, 1.0, "The distance to the original goal for truncating the path."
        ),
        output_port("output_path", Path, description="The resulting truncated path."),
    )

    def on_tick(self) -> Status:
        path: Path = self.get_input("input_path")
        limit: float = self.get_input("distance")
        if not path.poses:
            self.set_output("output_path", path)
            return SUCCESS
        poses = list(path.poses)
        goal = poses[-1]
        while len(poses) > 2 and distance(poses[-1], goal) < limit:
            poses.pop()
        last = poses[-1]
        dx = goal.pose.position.x - last.pose.position.x
        dy = goal.pose.position.y - last.pose.position.y
        yaw = math.atan2(dy, dx)  # 0 when the last pose is the goal, as Nav2's fallback
        pose = last.pose.model_copy(update={"orientation": Quaternion.from_yaw(yaw)})
        poses[-1] = PoseStamped.model_construct(header=last.header, pose=pose)
        self.set_output("output_path", Path.model_construct(header=path.header, poses=poses))
        return SUCCESS
