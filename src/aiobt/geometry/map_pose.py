"""The robot's pose in ``map`` read when asked: its odometry composed with localization's
correction, as Nav2's nodes look ``map`` -> ``base_link`` up in TF.

A :class:`MapPose` reads three rings (:meth:`Bus.latest <aiobt.transport.Bus.latest>`:
no Python per message): ``{ns}/odom``, ``{ns}/tf`` and, only until a pose has been
composed, ``{ns}/pose``. A robot with its own localization, or a localization with
``tf_broadcast`` off, publishes the pose and no correction (``docs/robot_contract.md``):
it is read as before. Once a correction comes and the odometry composes with it, the
pose's ring is let go (localization composes ``{ns}/pose`` only while somebody reads
it) and each read composes the newest odometry with the newest correction
(:func:`~aiobt.geometry.correction.compose`), stamped with the odometry's stamp, in
``map``. A correction with no odometry yet to compose with (the rings opened together:
one can come first), or none old enough (a correction sent late, older than every
odometry message kept since the rings opened), leaves the pose read from ``{ns}/pose``
meanwhile: a reader never goes from a pose back to none.

Staleness is TF's: the pose is composed from the newest odometry stamped no later than
the correction's stamp plus ``tolerance`` (AMCL's ``transform_tolerance``, by which it
post-dates the transform it sends). While localization runs it sends a correction with
every scan, and every odometry message qualifies; when it stops, the pose stops at that
point (a TF lookup's latest common time), as localization's own ``{ns}/pose`` stopped.
When the odometry stops, the pose keeps the last one's stamp, as before.
"""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from typing import TYPE_CHECKING, Protocol, TypeVar

from aiobt.msgs import Odometry, PoseStamped, TFMessage, pose_fields
from aiobt.transport.latest import first_read

from .correction import MAP_FRAME, POSE_TOPIC, TF_TOPIC, Correction, compose, correction_of

if TYPE_CHECKING:
    from aiobt.transport import Bus

M = TypeVar("M", covariant=True)
ODOM_TOPIC = "odom"
TF_KEPT = 4  # tf messages looked through for the correction (other frames may share the key)
TRANSFORM_TOLERANCE = 1.0  # robot s: nav2_amcl's transform_tolerance default
SETTLE_LOOK = 1.0  # wall s between looks for the first correction (:meth:`MapPose.settle`)


class Reader(Protocol[M]):
    """What :class:`MapPose` reads: a :class:`~aiobt.transport.Latest` (or a shared one)."""

    def get(self) -> M | None: ...

    def newest_first(self) -> Iterator[M]: ...

    def close(self) -> None: ...


class MapPose:
    """The robot's pose in ``map`` (see the module's docstring). ``get`` returns the same
    message object while neither the odometry nor the correction changed."""

    __slots__ = ("_correction", "_made", "_odom", "_pose", "_tf", "_tf_read", "tolerance")

    def __init__(
        self,
        odom: Reader[Odometry],
        tf: Reader[TFMessage],
        pose: Reader[PoseStamped] | None,
        tolerance: float = TRANSFORM_TOLERANCE,
    ) -> None:
        if not tolerance >= 0.0:
            raise ValueError(f"map pose: tolerance must be >= 0 robot s, got {tolerance!r}")
        self._odom = odom
        self._tf = tf
        self._pose = pose
        self.tolerance = tolerance
        self._correction: Correction | None = None
        self._tf_read: TFMessage | None = None  # the newest tf message looked at
        # the newest odometry and the correction read last, and the pose they gave
        self._made: tuple[Odometry, Correction, PoseStamped] | None = None

    @classmethod
    def read(
        cls,
        bus: Bus,
        *,
        keep: int = 1,
        namespace: str | None = None,
        tolerance: float = TRANSFORM_TOLERANCE,
    ) -> MapPose:
        """Read ``bus``'s streams (in ``namespace``), the last ``keep`` odometry messages
        (and poses, until one is composed) kept for :meth:`newest_first`."""
        return cls(
            bus.latest(ODOM_TOPIC, Odometry, keep=keep, namespace=namespace),
            bus.latest(TF_TOPIC, TFMessage, keep=TF_KEPT, namespace=namespace),
            bus.latest(POSE_TOPIC, PoseStamped, keep=keep, namespace=namespace),
            tolerance,
        )

    @property
    def correction(self) -> Correction | None:
        """The newest ``map`` -> ``odom`` seen."""
        newest = self._tf.get()
        if newest is not None and newest is not self._tf_read:
            self._tf_read = newest
            for message in self._tf.newest_first():
                found = correction_of(message)
                if found is not None:
                    self._correction = found
                    break
        return self._correction

    @property
    def composing(self) -> bool:
        """Whether the pose is composed (the pose's ring let go), looking now."""
        self.get()
        return self._made is not None

    def get(self) -> PoseStamped | None:
        """The robot's newest pose in ``map``; None before one can be told."""
        correction = self.correction
        composed = None if correction is None else self._composed(correction)
        if composed is not None:
            if self._pose is not None:  # composing from now on
                self._pose.close()
                self._pose = None
            return composed
        return None if self._pose is None else self._pose.get()

    def _composed(self, correction: Correction) -> PoseStamped | None:
        """The newest odometry composed with ``correction`` (the module's rule); None
        before a pose could ever be composed."""
        newest = self._odom.get()
        made = self._made
        if newest is None:
            return None
        if made is not None and made[0] is newest and made[1] is correction:
            return made[2]
        for odom in self._odom.newest_first():
            if odom.header.stamp <= correction.stamp + self.tolerance:
                pose = self._compose(correction, odom)
                self._made = (newest, correction, pose)  # the answer until either changes
                return pose
        return None if made is None else made[2]  # none kept that early: where it stopped

    def newest_first(self) -> Iterator[PoseStamped]:
        """The kept poses, newest first: each kept odometry message composed with the
        newest correction (the same rule as :meth:`get`), or, until a pose is composed,
        the pose stream's kept ones."""
        self.get()  # settles which
        correction = self._correction
        if self._pose is not None or correction is None:
            if self._pose is not None:
                yield from self._pose.newest_first()
            return
        limit = correction.stamp + self.tolerance
        for odom in self._odom.newest_first():
            if odom.header.stamp <= limit:
                yield self._compose(correction, odom)

    @staticmethod
    def _compose(correction: Correction, odom: Odometry) -> PoseStamped:
        x, y, yaw = compose(correction.transform, odom.pose.position.x, odom.pose.position.y,
                            odom.pose.yaw)  # fmt: skip
        header = {"stamp": odom.header.stamp, "frame_id": MAP_FRAME}
        return PoseStamped.model_validate({"header": header, "pose": pose_fields(x, y, yaw)})

    async def settle(self, period: float = SETTLE_LOOK) -> None:
        """Read every ``period`` wall s, and return once a pose is composed (the pose's
        ring let go) or the pose is not read. For a reader read only now and then (a
        server between goals): without it, ``{ns}/pose`` stays subscribed, and
        localization composes it, until the reader's first read after a correction."""
        while self._pose is not None:
            self.get()
            if self._pose is not None:
                await asyncio.sleep(period)

    async def wait_latest(self, timeout: float | None = None) -> PoseStamped:  # noqa: ASYNC109
        """The newest pose in ``map``, waiting (at most ``timeout`` s) for one to be told
        (looking at the rings: :func:`~aiobt.transport.latest.first_read`)."""
        return await first_read(self.get, timeout)

    def close(self) -> None:
        self._odom.close()
        self._tf.close()
        if self._pose is not None:
            self._pose.close()
            self._pose = None
