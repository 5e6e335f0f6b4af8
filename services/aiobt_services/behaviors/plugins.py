"""The behavior server's plugins (Nav2's ``nav2_core::Behavior``): one registry.

A plugin is one of Nav2's behavior actions: the action it serves, how a goal
becomes a running :class:`Behavior` (which the server steps once per cycle), and
its feedback. :data:`BEHAVIORS` holds them by action name; the server serves
every one of them (see docs/architecture.md for adding one).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from aiobt.costmap.checker import CollisionChecker
from aiobt.msgs import AssistedTeleop as AssistedTeleopAction
from aiobt.msgs import BackUp, DriveOnHeading, Msg, Spin, Wait

from . import goals
from .base import BehaviorStep, Inputs, Outcome, Safety


class Behavior(Protocol):
    """A running behavior, stepped once per cycle until a step says it is done."""

    def step(self, inputs: Inputs) -> BehaviorStep: ...


class BehaviorPlugin(Protocol):
    """One behavior action: its server's name, goals into behaviors, feedback, result."""

    @property
    def name(self) -> str: ...

    @property
    def action(self) -> Any: ...

    @property
    def owns_cmd_vel(self) -> bool:
        """Whether it drives the base (one such behavior runs at a time)."""
        ...

    def create(self, goal: Any, checker: CollisionChecker, safety: Safety) -> Behavior:
        """The running behavior for ``goal``; BehaviorInputError names a bad field."""
        ...

    def feedback(self, progress: float) -> Msg: ...

    def result(self, outcome: Outcome, message: str, elapsed: float) -> Any: ...


@dataclass(frozen=True, slots=True)
class ActionBehavior:
    """A :class:`BehaviorPlugin` for one of Nav2's behavior actions."""

    action: Any
    make: Callable[[Any, CollisionChecker, Safety], Behavior]
    progress: Callable[[float], Msg]
    owns_cmd_vel: bool = True

    @property
    def name(self) -> str:
        return str(self.action.name)

    def create(self, goal: Any, checker: CollisionChecker, safety: Safety) -> Behavior:
        return self.make(goal, checker, safety)

    def feedback(self, progress: float) -> Msg:
        return self.progress(progress)

    def result(self, outcome: Outcome, message: str, elapsed: float) -> Any:
        code = goals.error_code(self.action.ErrorCode, outcome)
        return self.action.Result(error_code=code, error_msg=message, total_elapsed_time=elapsed)


BEHAVIORS: dict[str, BehaviorPlugin] = {
    plugin.name: plugin
    for plugin in (
        ActionBehavior(Spin, goals.spin_of, lambda f: Spin.Feedback(angular_distance_traveled=f)),
        ActionBehavior(BackUp, goals.backup_of, lambda f: BackUp.Feedback(distance_traveled=f)),
        ActionBehavior(
            DriveOnHeading,
            goals.drive_of,
            lambda f: DriveOnHeading.Feedback(distance_traveled=f),
        ),
        ActionBehavior(
            Wait,
            lambda goal, _checker, _safety: goals.wait_of(goal),
            lambda f: Wait.Feedback(time_left=f),
            owns_cmd_vel=False,
        ),
        ActionBehavior(
            AssistedTeleopAction,
            goals.teleop_of,
            lambda f: AssistedTeleopAction.Feedback(current_teleop_duration=f),
        ),
    )
}
"""Every behavior the server runs, by action name."""
