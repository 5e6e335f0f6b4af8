"""The velocity smoother's parameters: Nav2's names, defaults and refusals.

Axes are Nav2's 3-DOF ``[x, y, theta]`` (the 6-DOF form is refused: the base is
planar). Every refusal is a :class:`SmootherConfigError` naming the parameter,
its value and what it must be, raised at start so a bad configuration never runs.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

Feedback = Literal["OPEN_LOOP", "CLOSED_LOOP"]
AXES = ("x", "y", "theta")


class SmootherConfigError(ValueError):
    """A parameter of the velocity smoother that cannot run; the message names it."""


@dataclass(slots=True, frozen=True)
class SmootherParams:
    """Nav2 ``velocity_smoother`` parameters (its defaults)."""

    smoothing_frequency: float = 20.0
    feedback: Feedback = "OPEN_LOOP"
    scale_velocities: bool = False
    max_velocity: tuple[float, float, float] = (0.5, 0.0, 2.5)
    min_velocity: tuple[float, float, float] = (-0.5, 0.0, -2.5)
    max_accel: tuple[float, float, float] = (2.5, 0.0, 3.2)
    max_decel: tuple[float, float, float] = (-2.5, 0.0, -3.2)
    deadband_velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    velocity_timeout: float = 1.0
    odom_duration: float = 0.1
    odom_topic: str = "odom"
    axes: tuple[str, ...] = field(default=AXES, repr=False)

    def __post_init__(self) -> None:
        _positive("smoothing_frequency", self.smoothing_frequency)
        _non_negative("velocity_timeout", self.velocity_timeout)
        _positive("odom_duration", self.odom_duration)
        if self.feedback not in ("OPEN_LOOP", "CLOSED_LOOP"):
            raise SmootherConfigError(
                f"velocity_smoother: feedback {self.feedback!r}: the options are "
                "OPEN_LOOP and CLOSED_LOOP"
            )
        for name in ("max_velocity", "min_velocity", "max_accel", "max_decel"):
            _three_finite(name, getattr(self, name))
        _three_finite("deadband_velocity", self.deadband_velocity)
        _signed("max_velocity", self.max_velocity, +1, "positive (or 0)")
        _signed("max_accel", self.max_accel, +1, "positive (or 0) to speed up")
        _signed("min_velocity", self.min_velocity, -1, "negative (or 0)")
        _signed("max_decel", self.max_decel, -1, "negative (or 0) to slow down")
        _signed("deadband_velocity", self.deadband_velocity, +1, "positive (or 0)")
        for axis, low, high in zip(AXES, self.min_velocity, self.max_velocity, strict=True):
            if low > high:
                raise SmootherConfigError(
                    f"velocity_smoother: min_velocity {low:g} is above max_velocity "
                    f"{high:g} on axis {axis}"
                )

    @property
    def period(self) -> float:
        return 1.0 / self.smoothing_frequency


def _positive(name: str, value: float) -> None:
    if not (math.isfinite(value) and value > 0.0):
        raise SmootherConfigError(f"velocity_smoother: {name} {value!r} must be a number > 0")


def _non_negative(name: str, value: float) -> None:
    if not (math.isfinite(value) and value >= 0.0):
        raise SmootherConfigError(f"velocity_smoother: {name} {value!r} must be a number >= 0")


def _three_finite(name: str, values: Sequence[float]) -> None:
    if len(values) != 3:
        raise SmootherConfigError(
            f"velocity_smoother: {name} has {len(values)} values {list(values)}: "
            "it must have 3, for the axes x, y, theta"
        )
    if not all(math.isfinite(v) for v in values):
        raise SmootherConfigError(f"velocity_smoother: {name} {list(values)} must be finite")


def _signed(name: str, values: Sequence[float], sign: int, what: str) -> None:
    for axis, value in zip(AXES, values, strict=True):
        if value * sign < 0.0:
            raise SmootherConfigError(
                f"velocity_smoother: {name} is {value:g} on axis {axis}: it must be {what}"
            )
