"""BtCancelAction: Nav2's BtCancelActionNode, cancel every goal of an action server."""

from __future__ import annotations

import logging
from typing import Any, ClassVar

from aiobt.core.leaves import AsyncActionNode
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import ActionDef
from aiobt.nav import remote
from aiobt.nav.context import NavNode
from aiobt.transport import ServiceError

log = logging.getLogger("aiobt.nav.cancel")


class BtCancelAction(NavNode, AsyncActionNode):
    """Cancels all goals of ``server_name`` (anyone's), as Nav2's cancel nodes do.

    SUCCESS once the server has acknowledged the cancel; FAILURE, logged with the
    server's name, if no server answers within ``server_timeout``.
    """

    ACTION: ClassVar[type[ActionDef[Any, Any, Any]]]

    async def run(self) -> Status:
        name = remote.server_name(self, "server_name", self.ACTION.name)
        timeout = remote.server_timeout(self)
        client = remote.action_client(self, name, self.ACTION)
        try:
            if not await client.wait_for_server(timeout):
                raise ServiceError(f"no action server {name} within {timeout * 1000:.0f} ms")
            canceling = await client.cancel_all(timeout)
        except ServiceError as exc:
            log.warning("%s: failed to cancel the goals of %s: %s", self.path, name, exc)
            return FAILURE
        log.debug("%s: %s canceling %s", self.path, name, canceling)
        return SUCCESS


def cancel_ports(what: str, default_name: str) -> Any:
    return remote.server_ports(f"Action server to cancel the {what}", default_name)
