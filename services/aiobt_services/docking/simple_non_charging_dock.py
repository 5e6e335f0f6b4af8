"""Nav2's ``SimpleNonChargingDock``: the simple dock (:mod:`.simple_dock`) that does not
charge (a conveyor, a cart, a parking spot): docked within ``docking_threshold`` of the
dock pose or by stall detection; the docking server waits for no charge and undocks
without disabling one, and the charging questions are errors, as in Nav2."""

from __future__ import annotations

from .simple_dock import SimpleDock

NOT_A_CHARGER = "This dock is not a charging dock!"


class SimpleNonChargingDock(SimpleDock):
    is_charger = False

    def is_charging(self) -> bool:
        raise RuntimeError(NOT_A_CHARGER)

    def disable_charging(self) -> bool:
        raise RuntimeError(NOT_A_CHARGER)

    def has_stopped_charging(self) -> bool:
        raise RuntimeError(NOT_A_CHARGER)
