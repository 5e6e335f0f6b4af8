"""The dock detector's lifecycle (Nav2's ``startDetectionProcess`` and
``stopDetectionProcess`` of its SimpleChargingDock and SimpleNonChargingDock): the
docking server starts the detection before its first look for the dock and stops it
when the docking ends, however it ends.

- ``detector_service_name`` (empty: none): a ``std_srvs/Trigger`` service
  (``{ns}/srv/{name}``) called on start and again on stop, waiting up to
  ``detector_service_timeout`` s; a failed or unanswered call fails the start (the
  docking then ends FAILED_TO_DETECT_DOCK) and is logged on stop. As in Nav2 the same
  service starts and stops: the detector toggles.
- ``subscribe_toggle``: the plugin subscribes to ``detected_dock_pose`` only while
  started; otherwise the subscription lasts as long as the plugin.
- A detection received before the last stop is not used (Nav2's
  ``initial_pose_received_`` reset on stop): the next docking waits for a new one.
"""

from __future__ import annotations

import logging

from aiobt.geometry.pose_filter import StampedPose3D

from .plugins import DockWiring

log = logging.getLogger("aiobt_services.docking.detector")


class DetectorControl:
    def __init__(self, wiring: DockWiring, *, service: str, timeout: float,
                 subscribe_toggle: bool, detects: bool) -> None:  # fmt: skip
        """``detects``: the plugin reads the detections (``use_external_detection_pose``)."""
        self.wiring = wiring
        self.service = service
        self.timeout = timeout
        self.subscribe_toggle = subscribe_toggle
        self.active = False
        self.subscribed = detects and not subscribe_toggle
        self.stopped_at: float | None = None  # the newest detection's stamp at the last stop
        if self.subscribed:
            wiring.subscribe(True)

    def latest(self) -> StampedPose3D | None:
        """The newest detection received since the last stop (None: none yet)."""
        seen = self.wiring.detection() if self.subscribed else None
        if seen is None or (self.stopped_at is not None and seen.stamp <= self.stopped_at):
            return None
        return seen

    async def start(self) -> bool:
        if self.active:
            return True
        if self.service and not await self._call("start"):
            return False
        if self.subscribe_toggle and not self.subscribed:
            self.wiring.subscribe(True)
            self.subscribed = True
        self.active = True
        log.info("External detector activation requested.")
        return True

    async def stop(self) -> bool:
        if not self.active:
            return True
        if self.service and not await self._call("stop"):
            return False
        seen = self.wiring.detection() if self.subscribed else None
        self.stopped_at = None if seen is None else seen.stamp
        if self.subscribe_toggle and self.subscribed:
            self.wiring.subscribe(False)
            self.subscribed = False
        self.active = False
        log.info("External detector deactivation requested.")
        return True

    async def _call(self, what: str) -> bool:
        why = await self.wiring.trigger(self.service, self.timeout)
        if why is not None:
            log.error("Detector service '%s' failed to %s: %s", self.service, what, why)
        return why is None
