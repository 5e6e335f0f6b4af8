"""BackUp and DriveOnHeading (Nav2): the behavior server drives straight."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port
from aiobt.msgs import BackUp as BackUpAction
from aiobt.msgs import DriveOnHeading as DriveOnHeadingAction
from aiobt.msgs import Point
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

_COMMON = (
    input_port("time_allowance", float, 10.0, "Time allowed before it is considered stuck."),
    input_port("disable_collision_checks", bool, False, "Disable collision checking."),
)


class _Drive(BtAction):
    DISTANCE = ""
    SPEED = ""

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            target=Point(x=self.get_input(self.DISTANCE)),
            speed=self.get_input(self.SPEED),
            time_allowance=self.get_input("time_allowance"),
            disable_collision_checks=self.get_input("disable_collision_checks"),
        )


class BackUp(_Drive):
    """``<BackUp backup_dist="0.30" backup_speed="0.15"/>``: drive backwards.

    SUCCESS once ``backup_dist`` m are covered; FAILURE with the behavior's
    ``error_code_id`` (e.g. 714 COLLISION_AHEAD, 711 TIMEOUT). Each activation
    adds one to the ``number_recoveries`` blackboard entry (Nav2).
    """

    ACTION = BackUpAction
    DISTANCE, SPEED = "backup_dist", "backup_speed"
    PORTS = action_ports(
        "Backup",
        BackUpAction.name,
        input_port("backup_dist", float, 0.15, "Total distance to backup (m)."),
        input_port("backup_speed", float, 0.025, "Backup speed (m/s)."),
        *_COMMON,
    )

    def counts_as_recovery(self) -> bool:
        return True


class DriveOnHeading(_Drive):
    """``<DriveOnHeading dist_to_travel="0.5" speed="0.2"/>``: drive along the current heading.

    SUCCESS once ``dist_to_travel`` m are covered; FAILURE with the behavior's
    ``error_code_id`` (e.g. 723 COLLISION_AHEAD, 721 TIMEOUT).
    """

    ACTION = DriveOnHeadingAction
    DISTANCE, SPEED = "dist_to_travel", "speed"
    PORTS = action_ports(
        "Drive on heading",
        DriveOnHeadingAction.name,
        input_port("dist_to_travel", float, 0.15, "Distance to travel (m)."),
        input_port("speed", float, 0.025, "Speed at which to travel (m/s)."),
        *_COMMON,
    )
