"""Nav2's cancel leaves (BtCancelActionNode): cancel all goals of one server."""

from aiobt.core.node import TreeNode
from aiobt.nav.cancel.base import BtCancelAction
from aiobt.nav.cancel.behaviors import (
    CancelAssistedTeleop,
    CancelBackUp,
    CancelComputeAndTrackRoute,
    CancelControl,
    CancelCoverage,
    CancelDriveOnHeading,
    CancelFollowObject,
    CancelSpin,
    CancelWait,
)

CANCEL_NODES: tuple[type[TreeNode], ...] = (
    CancelAssistedTeleop,
    CancelBackUp,
    CancelComputeAndTrackRoute,
    CancelControl,
    CancelCoverage,
    CancelDriveOnHeading,
    CancelFollowObject,
    CancelSpin,
    CancelWait,
)

__all__ = ["CANCEL_NODES", "BtCancelAction"]
