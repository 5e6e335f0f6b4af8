"""Localization's ``map`` -> ``odom`` correction, and the robot's pose in ``map`` from it.

Nav2's nodes get the robot's pose in ``map`` from TF: AMCL's ``map`` -> ``odom``
(sent with every scan it takes, the last one again while the filter does not
update) chained with the odometry's ``odom`` -> ``base_link``. aiobt's localization
sends the same correction on ``{ns}/tf`` (:func:`correction_message`), and on
``{ns}/pose`` the correction composed with each odometry message (:func:`compose`,
at the odometry's 50 Hz) for readers that take no odometry. A reader that takes the
odometry anyway composes the pose itself, with the same :func:`compose` and the
correction it read back (:func:`correction_of`): one 50 Hz stream fewer to receive
(:class:`MapSource`). The two agree to float rounding (the yaw's way through a
quaternion), at most one odometry message apart: localization's own stream takes a
new correction at the first odometry after its update, a reader at the first after
the correction's message arrived.
"""

from __future__ import annotations

import asyncio
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from aiobt.geometry import XYYaw
from aiobt.msgs import PoseStamped, TFMessage, yaw_to_quaternion

if TYPE_CHECKING:
    from aiobt.transport import Bus, Subscription

TF_TOPIC = "tf"  # localization's map -> odom, as Nav2's AMCL broadcasts it on /tf
POSE_TOPIC = "pose"  # the pose in map, composed by localization (or a robot's own)
MAP_FRAME = "map"
ODOM_FRAME = "odom"


def compose(correction: XYYaw, x: float, y: float, yaw: float) -> XYYaw:
    """``correction * (x, y, yaw)``: a pose in ``odom`` expressed in ``map``, in plain
    floats (the per-message work of a 50 Hz stream, where numpy's per-call cost would be
    most of it); the yaw wrapped to ``[-pi, pi)``."""
    cx, cy, cyaw = correction
    c, s = math.cos(cyaw), math.sin(cyaw)
    turned = (cyaw + yaw + math.pi) % (2.0 * math.pi) - math.pi
    return cx + c * x - s * y, cy + s * x + c * y, turned


@dataclass(slots=True, frozen=True)
class Correction:
    """``map`` -> ``odom`` as of ``stamp`` (robot time: the scan it was sent with)."""

    transform: XYYaw
    stamp: float


def correction_message(
    transform: XYYaw, stamp: float, parent: str = MAP_FRAME, child: str = ODOM_FRAME
) -> TFMessage:
    """The correction as localization sends it on ``{ns}/tf``."""
    x, y, yaw = transform
    qx, qy, qz, qw = yaw_to_quaternion(yaw)
    return TFMessage.model_validate(
        {
            "transforms": [
                {
                    "header": {"stamp": stamp, "frame_id": parent},
                    "child_frame_id": child,
                    "transform": {
                        "translation": {"x": x, "y": y},
                        "rotation": {"x": qx, "y": qy, "z": qz, "w": qw},
                    },
                }
            ]
        }
    )


def correction_of(
    msg: TFMessage, parent: str = MAP_FRAME, child: str = ODOM_FRAME
) -> Correction | None:
    """The ``parent`` -> ``child`` transform in ``msg`` (the last if several), or None if
    it has none (other frames share ``{ns}/tf``). Finite: the wire model refuses others."""
    for tf in reversed(msg.transforms):
        if tf.header.frame_id == parent and tf.child_frame_id == child:
            t = tf.transform.translation
            return Correction((t.x, t.y, tf.yaw), tf.header.stamp)
    return None


class MapSource:
    """Where a reader of odometry takes the robot's pose in ``map`` from, as an
    on-demand stream (:class:`~aiobt.transport.on_demand.OnDemand`): localization's
    correction on ``{ns}/tf``, handed to ``on_correction``, and ``{ns}/pose``, handed to
    ``on_pose`` only until the first correction comes. A robot whose own localization
    publishes no correction (``docs/robot_contract.md``), or a localization with
    ``tf_broadcast`` off, is so read as before; with a correction the pose stream is let
    go and the reader composes each odometry message with it (:func:`compose`).
    :meth:`wait_latest` waits for :meth:`ready`, which the reader calls with its first
    pose in ``map``."""

    __slots__ = ("_on_correction", "_on_pose", "_pose", "_ready", "_tf")

    def __init__(
        self,
        bus: Bus,
        on_pose: Callable[[PoseStamped], None],
        on_correction: Callable[[Correction], None],
    ) -> None:
        self._on_pose = on_pose
        self._on_correction = on_correction
        self._ready = asyncio.Event()
        self._tf: Subscription[TFMessage] = bus.subscribe(TF_TOPIC, TFMessage, self._take_tf)
        self._pose: Subscription[PoseStamped] | None = bus.subscribe(
            POSE_TOPIC, PoseStamped, self._take_pose
        )

    @property
    def composing(self) -> bool:
        """Whether a correction came (the pose stream is let go)."""
        return self._pose is None

    def _take_tf(self, msg: TFMessage) -> None:
        correction = correction_of(msg)
        if correction is None:
            return
        if self._pose is not None:
            self._pose.close()
            self._pose = None
        self._on_correction(correction)

    def _take_pose(self, msg: PoseStamped) -> None:
        self._on_pose(msg)
        self.ready()

    def ready(self) -> None:
        """The reader has a pose in ``map``."""
        self._ready.set()

    async def wait_latest(self, timeout: float | None = None) -> bool:  # noqa: ASYNC109
        async with asyncio.timeout(timeout):
            await self._ready.wait()
        return True

    def close(self) -> None:
        self._tf.close()
        if self._pose is not None:
            self._pose.close()
            self._pose = None
