"""GetPoseFromPath (Nav2): one pose of a path, by index."""

from __future__ import annotations

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Path, PoseStamped


class GetPoseFromPath(SyncActionNode):
    """``<GetPoseFromPath path="{path}" index="-1" pose="{goal}"/>`` (Nav2).

    SUCCESS, writing pose ``index`` of ``path`` (negative: from the end) with
    the path's frame if the pose has none; FAILURE for an empty path or an
    index out of range.
    """

    __slots__ = ()
    PORTS = (
        input_port("path", Path, description="Path to extract pose from."),
        input_port(
            "index",
            int,
            0,
            "Index from path to use. Use `-1` to get the last pose, `-2` for second to last, "
            "and so on.",
        ),
        output_port("pose", PoseStamped, description="Pose from path, with the Path's set header."),
    )

    def on_tick(self) -> Status:
        path: Path = self.get_input("path")
        index: int = self.get_input("index")
        count = len(path.poses)
        if index < 0:
            index += count
        if not 0 <= index < count:
            return FAILURE
        pose = path.poses[index]
        if not pose.header.frame_id:
            pose = pose.model_copy(
                update={"header": pose.header.model_copy(update={"frame_id": path.header.frame_id})}
            )
        self.set_output("pose", pose)
        return SUCCESS
