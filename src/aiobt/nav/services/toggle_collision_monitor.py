"""ToggleCollisionMonitor (Nav2): switch the collision monitor on or off."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Msg, Toggle
from aiobt.nav.remote import service_ports
from aiobt.nav.services.base import BtService


class ToggleCollisionMonitor(BtService):
    """``<ToggleCollisionMonitor enable="false" service_name="collision_monitor/toggle"/>``:
    SUCCESS once the monitor has switched; FAILURE if it refuses or does not answer
    within ``server_timeout``."""

    RESPONSE = Toggle.Response
    PORTS = service_ports(
        "",
        input_port("enable", bool, True, "Whether to enable or disable the collision monitor."),
    )

    def make_request(self) -> Msg:
        return Toggle.Request(enable=self.get_input("enable"))

    def on_completion(self, response: Any) -> Status:
        if not response.success:
            self.log.error("%s: the collision monitor refused: %s", self.path, response.message)
            return FAILURE
        return SUCCESS
