"""Nav2's control nodes that talk to the outside (the others live in aiobt.nodes.control)."""

from aiobt.core.node import TreeNode
from aiobt.nav.control.pause_resume_controller import PauseResumeController

CONTROL_NODES: tuple[type[TreeNode], ...] = (PauseResumeController,)

__all__ = ["CONTROL_NODES", "PauseResumeController"]
