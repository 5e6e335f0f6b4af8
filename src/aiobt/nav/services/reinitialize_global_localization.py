"""ReinitializeGlobalLocalization (Nav2): ask localization to relocalize globally."""

from __future__ import annotations

from typing import Any

from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Empty, Msg
from aiobt.msgs import ReinitializeGlobalLocalization as ReinitializeSrv
from aiobt.nav.remote import service_ports
from aiobt.nav.services.base import BtService


class ReinitializeGlobalLocalization(BtService):
    """``<ReinitializeGlobalLocalization/>``: SUCCESS once the robot's localization
    has reinitialized; FAILURE if it refuses or does not answer within
    ``server_timeout``."""

    SERVICE = ReinitializeSrv.service_name
    RESPONSE = ReinitializeSrv.Response
    PORTS = service_ports(SERVICE)

    def make_request(self) -> Msg:
        return Empty()

    def on_completion(self, response: Any) -> Status:
        if not response.ok:
            self.log.error("%s: localization refused to reinitialize: %s",
                           self.path, response.message)  # fmt: skip
            return FAILURE
        return SUCCESS
