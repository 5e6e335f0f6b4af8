"""The dock detector's switch: ``{ns}/srv/dock_detector/toggle``, a ``std_srvs/Trigger``
service as Nav2's SimpleChargingDock calls it (``detector_service_name``: the same
service on start and on stop), so that the camera's detection of the dock runs only
while a docking needs it, as a real detector would save its GPU.

The detector publishes ``{ns}/detected_dock_pose`` from the start (for a docking server
that never calls the service); the first call puts it under the caller's control and
leaves it on (that call is a start), each later call turns it off or on again. The
reply's message says which (``dock detector on`` / ``off``).
"""

from __future__ import annotations

import logging

from aiobt.msgs import Trigger

log = logging.getLogger("aiobt_services.robot.dock_detector")
SERVICE = "dock_detector/toggle"


class DockDetectorSwitch:
    __slots__ = ("on", "on_demand")

    def __init__(self) -> None:
        self.on = True
        self.on_demand = False  # a caller has taken control

    def toggle(self, _request: Trigger.Request) -> Trigger.Response:
        self.on = not self.on if self.on_demand else True
        self.on_demand = True
        state = "on" if self.on else "off"
        log.info("dock detector %s", state)
        return Trigger.Response(success=True, message=f"dock detector {state}")
