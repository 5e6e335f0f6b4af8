"""The result's error code, aggregated from the tree's blackboard as bt_navigator does.

Nav2's trees bind each action's ``error_code_id`` output to a root blackboard
entry ``{prefix}_error_code`` (and ``error_msg`` to ``{prefix}_error_msg``);
the navigator reports the lowest non-zero code among the prefixes it knows
(``error_code_name_prefixes``), with its message.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from typing import Any, NamedTuple

from aiobt.core.blackboard import Blackboard
from aiobt.msgs import NavigateThroughPoses, NavigateToPose
from aiobt_services.navigator.goals import NavRequest

log = logging.getLogger("aiobt_services.navigator.errors")

# nav2_params.yaml's error_code_name_prefixes
ERROR_CODE_PREFIXES: tuple[str, ...] = (
    "assisted_teleop",
    "backup",
    "compute_path",
    "dock_robot",
    "drive_on_heading",
    "follow_object",
    "follow_path",
    "nav_thru_poses",
    "nav_to_pose",
    "route",
    "spin",
    "smoother",
    "undock_robot",
    "wait",
)


def _as_code(name: str, value: Any) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        log.warning("blackboard entry %s = %r is not an error code; ignored", name, value)
        return 0


def aggregate_error(blackboard: Blackboard, prefixes: Iterable[str]) -> tuple[int, str] | None:
    """The lowest non-zero ``{prefix}_error_code`` and its message, or None if none is set."""
    found: tuple[int, str] | None = None
    for prefix in prefixes:
        name = f"{prefix}_error_code"
        code = _as_code(name, blackboard.get(name, 0))
        if code != 0 and (found is None or code < found[0]):
            message = blackboard.get(f"{prefix}_error_msg", "")
            found = (code, str(message) if message is not None else "")
    return found


def clear_error_codes(blackboard: Blackboard, prefixes: Iterable[str]) -> None:
    """Every ``{prefix}_error_code`` 0 and ``{prefix}_error_msg`` empty, as bt_navigator
    leaves them between goals (conditions such as WouldAControllerRecoveryHelp read
    them before the action that writes them has run)."""
    for prefix in prefixes:
        blackboard.set(f"{prefix}_error_code", 0)
        blackboard.set(f"{prefix}_error_msg", "")


class NavigatorCodes(NamedTuple):
    """The navigator's own result codes for one action (9000s: to pose, 9100s: through)."""

    unknown: int
    failed_to_load: int
    tf_error: int


def navigator_codes(request: NavRequest) -> NavigatorCodes:
    codes = NavigateThroughPoses.ErrorCode if request.through_poses else NavigateToPose.ErrorCode
    return NavigatorCodes(
        int(codes.UNKNOWN), int(codes.FAILED_TO_LOAD_BEHAVIOR_TREE), int(codes.TF_ERROR)
    )
