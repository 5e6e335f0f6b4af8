"""Nav2's speed limit (``nav2_msgs/SpeedLimit`` on ``{ns}/speed_limit``), as the controllers
apply it: ``setSpeedLimit(speed_limit, percentage)`` on every controller plugin.

0 (``NO_SPEED_LIMIT``) restores the configured maximum; a percentage scales it; an
absolute limit replaces it (RPP) or, below the maximum only, scales the velocity limits
by its ratio to the maximum (DWB's kinematics).
"""

from __future__ import annotations

from dataclasses import dataclass

NO_SPEED_LIMIT = 0.0


@dataclass(slots=True, frozen=True)
class SpeedLimit:
    """The limit in force: ``speed_limit`` percent of the maximum when ``percentage``,
    else m/s; 0 means none."""

    speed_limit: float = NO_SPEED_LIMIT
    percentage: bool = True

    def __post_init__(self) -> None:
        if not self.speed_limit >= 0.0:  # also refuses NaN
            raise ValueError(f"speed_limit must be >= 0, got {self.speed_limit}")

    def __str__(self) -> str:
        if not self.active:
            return "none"
        return f"{self.speed_limit:g} %" if self.percentage else f"{self.speed_limit:g} m/s"

    @property
    def active(self) -> bool:
        return self.speed_limit != NO_SPEED_LIMIT

    def replaced(self, base: float) -> float:
        """RPP's ``max_linear_vel`` under this limit, from its configured ``base``."""
        if not self.active:
            return base
        return base * self.speed_limit / 100.0 if self.percentage else self.speed_limit

    def ratio(self, base_speed: float) -> float:
        """The factor DWB scales its velocity limits by, ``base_speed`` its maximum speed."""
        if not self.active:
            return 1.0
        if self.percentage:
            return self.speed_limit / 100.0
        return self.speed_limit / base_speed if self.speed_limit < base_speed else 1.0


NONE = SpeedLimit()
