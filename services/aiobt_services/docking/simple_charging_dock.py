"""Nav2's ``SimpleChargingDock``: the simple dock (:mod:`.simple_dock`: found by its
detection or taken blind, docked within ``docking_threshold`` or by stall detection)
that charges: charging when the battery's current exceeds ``charging_threshold``
(``use_battery_status``) or, without battery status, when docked.
"""

from __future__ import annotations

from dataclasses import dataclass

from .plugins import DockWiring
from .simple_dock import SimpleDock, SimpleDockParams


@dataclass(slots=True, frozen=True)
class SimpleChargingDockParams(SimpleDockParams):
    """Nav2's parameters of the plugin, with its defaults."""

    use_battery_status: bool = True
    charging_threshold: float = 0.5


class SimpleChargingDock(SimpleDock):
    is_charger = True

    def __init__(self, name: str, params: SimpleChargingDockParams, wiring: DockWiring) -> None:
        super().__init__(name, params, wiring)
        self.charging = params

    def is_charging(self) -> bool:
        if not self.charging.use_battery_status:
            return self.is_docked()
        battery = self.wiring.battery()
        return battery is not None and battery.current > self.charging.charging_threshold

    def disable_charging(self) -> bool:
        return True

    def has_stopped_charging(self) -> bool:
        return not self.is_charging()
