"""The navigator: Nav2's bt_navigator (goal intake, one tree per goal, preemption,
feedback, error codes, the tree status stream), Zenoh-free at its core.

The service (``aiobt navigator``) lives in :mod:`aiobt_services.navigator.main`; embed
the logic with :class:`Navigator` and your own :class:`GoalChannel`.
"""

from aiobt_services.navigator.goals import (
    NAVIGATE_THROUGH_POSES,
    NAVIGATE_TO_POSE,
    MapBounds,
    NavRequest,
)
from aiobt_services.navigator.navigation import GoalChannel, Navigation
from aiobt_services.navigator.navigator import Navigator, NavigatorOptions, RobotState
from aiobt_services.navigator.status import StatusSink, TreeStatusStream
from aiobt_services.navigator.trees import TreeLibrary, TreeLoadFailure

__all__ = [
    "NAVIGATE_THROUGH_POSES",
    "NAVIGATE_TO_POSE",
    "GoalChannel",
    "MapBounds",
    "NavRequest",
    "Navigation",
    "Navigator",
    "NavigatorOptions",
    "RobotState",
    "StatusSink",
    "TreeLibrary",
    "TreeLoadFailure",
    "TreeStatusStream",
]
