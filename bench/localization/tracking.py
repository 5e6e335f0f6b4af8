"""The estimate (``{ns}/pose``) against the simulation's truth (``{ns}/sim/pose``),
matched by stamp: position error RMS and p99, heading error RMS."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from aiobt.msgs import PoseStamped
from aiobt.transport import Bus
from aiobt.transport.keys import SIM_POSE


@dataclass(slots=True, frozen=True)
class Errors:
    count: int
    rms: float
    p99: float
    worst: float
    heading_rms_deg: float

    def line(self) -> str:
        return (
            f"{self.count} poses: position RMS {100 * self.rms:.1f} cm, p99 "
            f"{100 * self.p99:.1f} cm, max {100 * self.worst:.1f} cm; heading RMS "
            f"{self.heading_rms_deg:.2f} deg"
        )


@dataclass
class Tracking:
    estimates: dict[float, tuple[float, float, float]] = field(default_factory=dict)
    truths: dict[float, tuple[float, float, float]] = field(default_factory=dict)

    def attach(self, bus: Bus) -> None:
        bus.subscribe("pose", PoseStamped, callback=self._estimate, queue_size=500)
        bus.subscribe(SIM_POSE, PoseStamped, callback=self._truth, queue_size=500)

    def _estimate(self, msg: PoseStamped) -> None:
        self.estimates[round(msg.header.stamp, 6)] = (msg.x, msg.y, msg.yaw)

    def _truth(self, msg: PoseStamped) -> None:
        self.truths[round(msg.header.stamp, 6)] = (msg.x, msg.y, msg.yaw)

    def errors(self) -> Errors:
        stamps = sorted(self.estimates.keys() & self.truths.keys())
        if not stamps:
            return Errors(0, float("nan"), float("nan"), float("nan"), float("nan"))
        est = np.array([self.estimates[s] for s in stamps])
        tru = np.array([self.truths[s] for s in stamps])
        dist = np.hypot(est[:, 0] - tru[:, 0], est[:, 1] - tru[:, 1])
        heading = (est[:, 2] - tru[:, 2] + np.pi) % (2 * np.pi) - np.pi
        return Errors(
            len(stamps),
            float(np.sqrt(np.mean(dist**2))),
            float(np.percentile(dist, 99)),
            float(dist.max()),
            float(np.degrees(np.sqrt(np.mean(heading**2)))),
        )
