"""Wait (Nav2): the behavior server waits (robot time)."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port
from aiobt.msgs import Wait as WaitAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports


class Wait(BtAction):
    """``<Wait wait_duration="5.0"/>``: SUCCESS after ``wait_duration`` s of the
    server's robot time (a negative duration is made positive, with a warning, as
    Nav2 does). Each activation adds one to ``number_recoveries``."""

    ACTION = WaitAction
    PORTS = action_ports(
        "Wait",
        WaitAction.name,
        input_port("wait_duration", float, 1.0, "Wait time (s)."),
    )

    def make_goal(self) -> Any:
        duration: float = self.get_input("wait_duration")
        if duration <= 0:
            self.log.warning("%s: wait_duration %s is not positive: using %s",
                             self.path, duration, -duration)  # fmt: skip
            duration = -duration
        return self.ACTION.goal_type()(time=duration)

    def counts_as_recovery(self) -> bool:
        return True
