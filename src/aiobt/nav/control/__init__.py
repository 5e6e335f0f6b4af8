"""Nav2's control nodes (BehaviorTree.CPP's own live in aiobt.nodes.control)."""

from aiobt.core.node import TreeNode
from aiobt.nav.control.nonblocking_sequence import NonblockingSequence
from aiobt.nav.control.pause_resume_controller import PauseResumeController
from aiobt.nav.control.persistent_sequence import PersistentSequence
from aiobt.nav.control.pipeline_sequence import PipelineSequence
from aiobt.nav.control.recovery_node import RecoveryNode
from aiobt.nav.control.round_robin import RoundRobin

CONTROL_NODES: tuple[type[TreeNode], ...] = (
    PipelineSequence,
    RecoveryNode,
    RoundRobin,
    NonblockingSequence,
    PersistentSequence,
    PauseResumeController,
)

__all__ = [
    "CONTROL_NODES",
    "NonblockingSequence",
    "PauseResumeController",
    "PersistentSequence",
    "PipelineSequence",
    "RecoveryNode",
    "RoundRobin",
]
