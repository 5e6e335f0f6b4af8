"""SmoothPath (Nav2): the smoother server smooths a planned path."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import Path
from aiobt.msgs import SmoothPath as SmoothPathAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports


class SmoothPath(BtAction):
    """``<SmoothPath unsmoothed_path="{path}" smoothed_path="{path}"/>``

    - SUCCESS: ``smoothed_path``, ``smoothing_duration`` (s) and ``was_completed``
      (false when ``max_smoothing_duration`` cut the smoothing short);
    - FAILURE with the smoother's ``error_code_id`` (e.g. 503 SMOOTHED_PATH_IN_COLLISION).
    """

    ACTION = SmoothPathAction
    PORTS = action_ports(
        "Follow smoother",
        SmoothPathAction.name,
        input_port("unsmoothed_path", Path, description="The path to smooth."),
        input_port("max_smoothing_duration", float, 3.0, "Maximum time to smooth for (s)."),
        input_port("check_for_collisions", bool, False, "Check the smoothed path for collisions."),
        input_port("smoother_id", str, description="The smoother plugin to use."),
        output_port("smoothed_path", Path, description="The smoothed path."),
        output_port("smoothing_duration", float, description="The time spent smoothing (s)."),
        output_port("was_completed", bool, description="Whether smoothing completed in time."),
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            path=self.get_input("unsmoothed_path"),
            smoother_id=self.get_input("smoother_id", None) or "",
            max_smoothing_duration=self.get_input("max_smoothing_duration"),
            check_for_collisions=self.get_input("check_for_collisions"),
        )

    def on_success(self, result: Any) -> Status:
        self.set_output("smoothed_path", result.path)
        self.set_output("smoothing_duration", result.smoothing_duration)
        self.set_output("was_completed", result.was_completed)
        return super().on_success(result)
