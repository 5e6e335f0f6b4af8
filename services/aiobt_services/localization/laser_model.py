"""AMCL's likelihood-field laser model over all particles and beams at once
(``nav2_amcl/src/sensors/laser/likelihood_field_model.cpp``,
``laser_model_type: likelihood_field``), the beams a scan gives, and what every
laser model returns (:class:`LaserModel`; the other model is
:mod:`.likelihood_field_prob`).

A scan is first reduced to ``max_beams`` evenly strided beams (this model's step
``(n - 1) // (max_beams - 1)``; ``likelihood_field_prob``'s ``ceil(n /
max_beams)``), readings at or beyond the maximum range and NaNs dropped,
readings at or below the minimum range made maximum-range (so dropped) as
``amcl_node`` does. Each particle's weight is multiplied by ``1 + sum(pz^3)``
over its beams, with ``pz = z_hit * exp(-d^2 / 2 sigma^2) + z_rand /
range_max`` and ``d`` the distance of the beam's end point to the nearest
obstacle: AMCL's ad-hoc combination, kept for its behaviour.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Protocol

import numpy as np
import numpy.typing as npt

from .likelihood_field import LikelihoodField
from .se2 import FloatArray


class ScanError(ValueError):
    """A scan the filter cannot use (the message says why)."""


@dataclass(slots=True, frozen=True)
class Beams:
    """The beams a scan contributes: ranges and bearings in the robot's frame."""

    ranges: FloatArray
    bearings: FloatArray
    range_max: float


def check_scan_shape(count: int, angle_min: float, angle_max: float, increment: float) -> None:
    """Raise :class:`ScanError` unless ``count`` readings fit the scan's angles:
    ``(angle_max - angle_min) / angle_increment + 1`` of them."""
    if count == 0:
        raise ScanError("scan has no ranges")
    expected = (angle_max - angle_min) / increment + 1.0
    if abs(expected - count) > 0.5:
        raise ScanError(
            f"scan has {count} ranges but its angles (angle_min {angle_min:g}, angle_max "
            f"{angle_max:g}, angle_increment {increment:g}) make {expected:.1f}"
        )


class Likelihood(NamedTuple):
    """A scan's likelihood for each particle, ``factors * exp(log_scale)``: a model
    whose factors would under- or overflow returns them scaled by a common factor
    (the particles' normalised weights do not change with it)."""

    factors: FloatArray
    log_scale: float


class LaserModel(Protocol):
    """What :class:`.Amcl` weighs particles with (``laser_model_type``)."""

    def weigh(self, particles: FloatArray, beams: Beams, *, converged: bool) -> Likelihood:
        """The scan's likelihood for each particle (rows ``x, y, yaw``); ``converged``
        is ``pf.c``'s flag (beam skipping waits for it)."""
        ...


def select_beams(
    ranges: FloatArray,
    bearings: FloatArray,
    *,
    max_beams: int,
    range_min: float,
    range_max: float,
    laser_model_type: str = "likelihood_field",
) -> Beams:
    """AMCL's beam choice: strided to about ``max_beams`` as the model strides them,
    unusable readings dropped."""
    if laser_model_type == "likelihood_field_prob":
        step = max(1, math.ceil(len(ranges) / max_beams))
    else:
        step = max(1, (len(ranges) - 1) // (max_beams - 1))
    r, b = ranges[::step], bearings[::step]
    usable = np.isfinite(r) & (r > range_min) & (r < range_max)
    return Beams(r[usable].astype(np.float64), b[usable].astype(np.float64), range_max)


def end_points(
    particles: FloatArray, beams: Beams
) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]:
    """The beams' end points in the map, (particles, beams) each, in float32: by the
    angle-sum identities (the particles' and the beams' own sines and cosines, no
    (particle, beam) trigonometry)."""
    f32 = np.float32
    c, s = np.cos(particles[:, 2]).astype(f32), np.sin(particles[:, 2]).astype(f32)
    bx = (beams.ranges * np.cos(beams.bearings)).astype(f32)  # end points, robot frame
    by = (beams.ranges * np.sin(beams.bearings)).astype(f32)
    hx = particles[:, 0:1].astype(f32) + np.outer(c, bx) - np.outer(s, by)
    hy = particles[:, 1:2].astype(f32) + np.outer(s, bx) + np.outer(c, by)
    return hx, hy


@dataclass(slots=True, frozen=True)
class LikelihoodFieldModel:
    """``z_rand`` over a likelihood field built with ``z_hit`` and ``sigma_hit``."""

    field: LikelihoodField
    z_rand: float

    def likelihood(self, particles: FloatArray, beams: Beams) -> FloatArray:
        """The factor ``1 + sum(pz^3)`` for each particle (rows ``x, y, yaw``)."""
        if beams.ranges.size == 0:
            return np.ones(len(particles))
        hx, hy = end_points(particles, beams)
        pz = self.field.hit_terms(hx, hy) + np.float32(self.z_rand / beams.range_max)
        return np.asarray(1.0 + np.sum(pz * pz * pz, axis=1, dtype=np.float64), dtype=np.float64)

    def weigh(self, particles: FloatArray, beams: Beams, *, converged: bool) -> Likelihood:
        """:meth:`likelihood` unscaled (at most ``1 + max_beams``: no range to guard)."""
        return Likelihood(self.likelihood(particles, beams), 0.0)


def effective_range_limits(
    scan_min: float, scan_max: float, laser_min_range: float, laser_max_range: float
) -> tuple[float, float]:
    """``amcl_node``'s limits: the parameters narrow the scan's own when positive."""
    high = min(scan_max, laser_max_range) if laser_max_range > 0.0 else scan_max
    low = max(scan_min, laser_min_range) if laser_min_range > 0.0 else scan_min
    if not (math.isfinite(high) and high > 0.0):
        raise ScanError(f"scan range_max must be > 0, got {scan_max}")
    return low, high
