"""DockRobot and UndockRobot (Nav2's docking server)."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import PoseStamped
from aiobt.msgs.remote_actions import DockRobot as DockRobotAction
from aiobt.msgs.remote_actions import UndockRobot as UndockRobotAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports


class DockRobot(BtAction):
    """``<DockRobot dock_id="home"/>`` (or ``use_dock_id="false" dock_pose="{pose}"``):
    SUCCESS once docked (``success``, ``num_retries``); FAILURE with the docking
    server's ``error_code_id`` (e.g. 904 FAILED_TO_DETECT_DOCK)."""

    ACTION = DockRobotAction
    PORTS = action_ports(
        "Dock robot",
        DockRobotAction.name,
        input_port("use_dock_id", bool, True, "Use the dock's ID, not the dock pose fields."),
        input_port("dock_id", str, description="Dock ID or name to use."),
        input_port("dock_pose", PoseStamped, description="The dock pose, if not using dock id."),
        input_port("dock_type", str, description="The dock plugin type, if using dock pose."),
        input_port("max_staging_time", float, 1000.0, "Maximum time to reach the staging pose."),
        input_port("navigate_to_staging_pose", bool, True, "Navigate to the staging pose."),
        output_port("success", bool, description="If the action was successful."),
        output_port("num_retries", int, description="The number of retries executed."),
    )

    def make_goal(self) -> Any:
        fields: dict[str, Any] = {
            "use_dock_id": self.get_input("use_dock_id"),
            "navigate_to_staging_pose": self.get_input("navigate_to_staging_pose"),
        }
        if fields["use_dock_id"]:
            fields["dock_id"] = self.get_input("dock_id", None) or ""
        else:
            fields.update(dock_pose=self.get_input("dock_pose"),
                          dock_type=self.get_input("dock_type", None) or "",
                          max_staging_time=self.get_input("max_staging_time"))  # fmt: skip
        return self.ACTION.goal_type()(**fields)

    def on_success(self, result: Any) -> Status:
        self.set_output("success", result.success)
        self.set_output("num_retries", result.num_retries)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self.set_output("success", result.success)
        self.set_output("num_retries", result.num_retries)
        return super().on_aborted(result)


class UndockRobot(BtAction):
    """``<UndockRobot dock_type="charger"/>``: SUCCESS once back at the staging pose;
    FAILURE with the docking server's ``error_code_id``."""

    ACTION = UndockRobotAction
    PORTS = action_ports(
        "Dock robot",
        UndockRobotAction.name,
        input_port("dock_type", str, description="The dock plugin type."),
        input_port("max_undocking_time", float, 30.0, "Maximum time to undock (s)."),
        output_port("success", bool, description="If the action was successful."),
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            dock_type=self.get_input("dock_type", None) or "",
            max_undocking_time=self.get_input("max_undocking_time"),
        )

    def on_success(self, result: Any) -> Status:
        self.set_output("success", result.success)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self.set_output("success", result.success)
        return super().on_aborted(result)
