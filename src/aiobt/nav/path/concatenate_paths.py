"""ConcatenatePaths (Nav2): one path after the other."""

from __future__ import annotations

import logging

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Path
from aiobt.msgs.geometry import Header

log = logging.getLogger("aiobt.nav.concatenate_paths")


class ConcatenatePaths(SyncActionNode):
    """``<ConcatenatePaths input_path1="{a}" input_path2="{b}" output_path="{ab}"/>`` (Nav2).

    SUCCESS, writing the poses of ``input_path1`` then ``input_path2`` under the
    first path's header (the second's if the first has an empty header); FAILURE
    when both are empty (or unset).
    """

    __slots__ = ()
    PORTS = (
        input_port("input_path1", Path, description="First path to concatenate."),
        input_port("input_path2", Path, description="Second path to concatenate."),
        output_port("output_path", Path, description="Output concatenated path."),
    )

    def on_tick(self) -> Status:
        first: Path = self.get_input("input_path1", Path())
        second: Path = self.get_input("input_path2", Path())
        if not first.poses and not second.poses:
            log.error("%s: both input paths are empty", self.path)
            return FAILURE
        header = first.header if first.header != Header() else second.header
        poses = [*first.poses, *second.poses]
        self.set_output("output_path", Path.model_construct(header=header, poses=poses))
        return SUCCESS
