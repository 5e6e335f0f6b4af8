"""Spin (Nav2): the behavior server turns the robot in place."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port
from aiobt.msgs import Spin as SpinAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports


class Spin(BtAction):
    """``<Spin spin_dist="1.57"/>``: turn by ``spin_dist`` radians.

    SUCCESS when turned; FAILURE with the behavior's ``error_code_id`` (e.g. 703
    COLLISION_AHEAD, 701 TIMEOUT after ``time_allowance`` s). With ``is_recovery``
    each activation adds one to the ``number_recoveries`` blackboard entry.
    """

    ACTION = SpinAction
    PORTS = action_ports(
        "Spin",
        SpinAction.name,
        input_port("spin_dist", float, 1.57, "Spin distance (radians)."),
        input_port("time_allowance", float, 10.0, "Time allowed before it is considered stuck."),
        input_port("is_recovery", bool, True, "True if the action is being used as a recovery."),
        input_port("disable_collision_checks", bool, False, "Disable collision checking."),
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            target_yaw=self.get_input("spin_dist"),
            time_allowance=self.get_input("time_allowance"),
            disable_collision_checks=self.get_input("disable_collision_checks"),
        )

    def counts_as_recovery(self) -> bool:
        return bool(self.get_input("is_recovery"))
