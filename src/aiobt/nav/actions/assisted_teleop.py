"""AssistedTeleop (Nav2): the behavior server passes teleop commands, collision-checked."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port
from aiobt.msgs import AssistedTeleop as AssistedTeleopAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports


class AssistedTeleop(BtAction):
    """``<AssistedTeleop time_allowance="20.0"/>``: RUNNING while the operator drives;
    SUCCESS when the behavior ends it, FAILURE with its ``error_code_id`` (e.g. 731
    TIMEOUT). With ``is_recovery`` it counts in ``number_recoveries``."""

    ACTION = AssistedTeleopAction
    PORTS = action_ports(
        "Assisted teleop",
        AssistedTeleopAction.name,
        input_port("is_recovery", bool, False, "If true increment the recovery counter."),
        input_port("time_allowance", float, 10.0, "Time allowed before it is considered stuck."),
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(time_allowance=self.get_input("time_allowance"))

    def counts_as_recovery(self) -> bool:
        return bool(self.get_input("is_recovery"))
