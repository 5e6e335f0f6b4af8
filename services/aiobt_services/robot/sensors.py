"""Sensor models without physics: battery, wheel odometry, localization, lidar rays."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from aiobt.geometry import Pose2D, wrap_angle


@dataclass(slots=True, frozen=True)
class BatteryConfig:
    """Energy model: idle draw, draw per unit of motion, charging on the dock."""

    capacity_wh: float = 50.0
    idle_w: float = 4.0
    linear_w_per_mps: float = 30.0
    angular_w_per_radps: float = 8.0
    charge_w: float = 100.0
    full_voltage: float = 12.6
    empty_voltage: float = 10.5
    initial_percentage: float = 1.0


@dataclass(slots=True)
class Battery:
    """Charge drains with time and motion and refills on the dock."""

    config: BatteryConfig = field(default_factory=BatteryConfig)
    energy_wh: float = -1.0
    charging: bool = False
    power_w: float = 0.0

    def __post_init__(self) -> None:
        if self.energy_wh < 0.0:
            self.energy_wh = self.config.capacity_wh * self.config.initial_percentage

    @property
    def percentage(self) -> float:
        return self.energy_wh / self.config.capacity_wh

    @property
    def voltage(self) -> float:
        cfg = self.config
        return cfg.empty_voltage + (cfg.full_voltage - cfg.empty_voltage) * self.percentage

    @property
    def depleted(self) -> bool:
        return self.energy_wh <= 0.0

    def update(self, linear: float, angular: float, on_dock: bool, dt: float) -> None:
        cfg = self.config
        draw = cfg.idle_w + cfg.linear_w_per_mps * abs(linear)
        draw += cfg.angular_w_per_radps * abs(angular)
        self.charging = on_dock and self.energy_wh < cfg.capacity_wh
        self.power_w = (cfg.charge_w if self.charging else 0.0) - draw
        energy = self.energy_wh + self.power_w * dt / 3600.0
        self.energy_wh = min(cfg.capacity_wh, max(0.0, energy))


@dataclass(slots=True, frozen=True)
class NoiseConfig:
    """Odometry and localization noise (all zero: exact and deterministic)."""

    odom_linear: float = 0.0  # std of the relative error on wheel speed
    odom_angular: float = 0.0  # std of the relative error on turn rate
    slip: float = 0.0  # fraction of wheel motion the body loses to slip
    odom_angular_scale: float = 0.0  # relative error of the odometry's turn rate (wheel base)
    pose_xy: float = 0.0  # std of the localization error, metres
    pose_yaw: float = 0.0  # std of the localization error, radians
    seed: int = 0

    def __post_init__(self) -> None:
        for name in ("odom_linear", "odom_angular", "pose_xy", "pose_yaw"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"NoiseConfig.{name} must be finite and >= 0, got {value}")
        scale = self.odom_angular_scale
        if not abs(scale) < 1.0:
            raise ValueError(f"NoiseConfig.odom_angular_scale must be within (-1, 1), got {scale}")
        if not 0.0 <= self.slip < 1.0:
            raise ValueError(f"NoiseConfig.slip must be within [0, 1), got {self.slip}")


@dataclass(slots=True)
class WheelOdometry:
    """Integrates what the wheels did (so it drifts when they slip; against an obstacle the
    motors stall and the wheels turn only as the body moves)."""

    pose: Pose2D = field(default_factory=Pose2D)
    linear: float = 0.0
    angular: float = 0.0

    def update(
        self, linear: float, angular: float, dt: float, noise: NoiseConfig, rng: np.random.Generator
    ) -> None:
        if noise.odom_linear:
            linear *= 1.0 + rng.normal(0.0, noise.odom_linear)
        if noise.odom_angular:
            angular *= 1.0 + rng.normal(0.0, noise.odom_angular)
        angular *= 1.0 + noise.odom_angular_scale
        self.linear, self.angular = linear, angular
        mid_yaw = self.pose.yaw + 0.5 * angular * dt
        self.pose = Pose2D(
            self.pose.x + linear * dt * math.cos(mid_yaw),
            self.pose.y + linear * dt * math.sin(mid_yaw),
            wrap_angle(self.pose.yaw + angular * dt),
        )


def noisy_pose(pose: Pose2D, noise: NoiseConfig, rng: np.random.Generator) -> Pose2D:
    """The localization stand-in: ``pose`` plus white noise, if configured."""
    if not (noise.pose_xy or noise.pose_yaw):
        return pose
    dx, dy = rng.normal(0.0, noise.pose_xy, 2) if noise.pose_xy else (0.0, 0.0)
    dyaw = rng.normal(0.0, noise.pose_yaw) if noise.pose_yaw else 0.0
    return Pose2D(pose.x + float(dx), pose.y + float(dy), wrap_angle(pose.yaw + float(dyaw)))


@dataclass(slots=True, frozen=True)
class LidarConfig:
    """A planar lidar on the robot's centre; angles relative to its heading."""

    rays: int = 360
    angle_min: float = -math.pi
    angle_max: float = math.pi * (1.0 - 2.0 / 360)
    range_min: float = 0.05
    range_max: float = 12.0
    height: float = 0.2
    noise: float = 0.0  # std of range noise, metres
    dropout: float = 0.0  # share of beams that return nothing (dark or shiny surfaces)

    def __post_init__(self) -> None:
        if not 0.0 <= self.dropout < 1.0:
            raise ValueError(f"LidarConfig.dropout must be within [0, 1), got {self.dropout}")
        if not (math.isfinite(self.noise) and self.noise >= 0.0):
            raise ValueError(f"LidarConfig.noise must be finite and >= 0, got {self.noise}")
        if self.rays < 1:
            raise ValueError(f"LidarConfig.rays must be >= 1, got {self.rays}")
        if not 0.0 <= self.range_min < self.range_max:
            raise ValueError("LidarConfig needs 0 <= range_min < range_max")

    @property
    def angle_increment(self) -> float:
        return (self.angle_max - self.angle_min) / max(1, self.rays - 1)

    def angles(self) -> npt.NDArray[np.float64]:
        return self.angle_min + self.angle_increment * np.arange(self.rays, dtype=np.float64)


def lidar_ranges(
    distances: npt.NDArray[np.float64],
    cfg: LidarConfig,
    rng: np.random.Generator | None = None,
) -> npt.NDArray[np.float64]:
    """Distances to the first hit along each beam -> ranges, noisy and clipped to the
    lidar's limits; no hit within ``range_max`` (or a dropped beam) is ``inf`` (as ROS)."""
    hit = distances <= cfg.range_max
    if cfg.dropout and rng is not None:
        hit &= rng.uniform(0.0, 1.0, hit.shape) >= cfg.dropout
    ranges = np.where(hit, distances, cfg.range_max)
    if cfg.noise and rng is not None:
        ranges = ranges + rng.normal(0.0, cfg.noise, ranges.shape)
    clipped = np.clip(ranges, cfg.range_min, cfg.range_max)
    return np.where(hit, clipped, np.inf).astype(np.float64)
