"""Localization's correction handed to a reader of odometry that is called per message.

The controller takes every odometry message (its loop runs on them) and composes its
pose in ``map`` from each with the correction on ``{ns}/tf``, read back as it comes
(:class:`MapSource`); the frames, :func:`compose` and :func:`correction_of` are in
:mod:`aiobt.geometry.correction`, where the navigator and the planner read them too
(:mod:`aiobt.geometry.map_pose`, which reads when asked instead).
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import TYPE_CHECKING

from aiobt.geometry.correction import (
    MAP_FRAME,
    ODOM_FRAME,
    POSE_TOPIC,
    TF_TOPIC,
    Correction,
    compose,
    correction_message,
    correction_of,
)
from aiobt.msgs import PoseStamped, TFMessage

if TYPE_CHECKING:
    from aiobt.transport import Bus, Subscription

__all__ = [
    "MAP_FRAME",
    "ODOM_FRAME",
    "POSE_TOPIC",
    "TF_TOPIC",
    "Correction",
    "MapSource",
    "compose",
    "correction_message",
    "correction_of",
]


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
