"""The docking server's parameters (Nav2's ``docking_server`` names and defaults)."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(slots=True, frozen=True)
class DockingParams:
    controller_frequency: float = 50.0  # Hz of robot time
    initial_perception_timeout: float = 5.0
    wait_charge_timeout: float = 5.0
    dock_approach_timeout: float = 30.0
    rotate_to_dock_timeout: float = 10.0
    undock_linear_tolerance: float = 0.05
    undock_angular_tolerance: float = 0.05
    max_retries: int = 3
    fixed_frame: str = "odom"
    dock_prestaging_tolerance: float = 0.5
    rotation_angular_tolerance: float = 0.05
    navigator_bt_xml: str = ""

    def __post_init__(self) -> None:
        if not (math.isfinite(self.controller_frequency) and self.controller_frequency > 0.0):
            raise ValueError(f"controller_frequency must be > 0, got {self.controller_frequency}")
        if self.max_retries < 0:
            raise ValueError(f"max_retries must be >= 0, got {self.max_retries}")
        if self.fixed_frame not in ("odom", "map"):
            raise ValueError(f"fixed_frame must be odom or map, got '{self.fixed_frame}'")

    @property
    def period(self) -> float:
        return 1.0 / self.controller_frequency
