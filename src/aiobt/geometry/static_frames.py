"""Static transforms as tf2 keeps ``/tf_static``: the fixed links of a robot's frames
(``base_link`` -> ``camera_link`` -> ``camera_optical_frame``), in 3D.

A robot's driver publishes them once, latched, on ``{ns}/tf_static`` (``TFMessage``,
ROS's ``/tf_static``); several publishers may each publish their own. tf2 keeps every
static transform for good, the newest per child frame; so does :class:`StaticFrames`,
and it walks from a frame up its parents to the first frame its reader knows (the
robot's own, ``odom``, ``map``), which is how a detection given in a camera's frame
reaches the frames the servers work in.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from aiobt.msgs import TFMessage

from .pose import Pose2D
from .pose_filter import StampedPose3D
from .quaternion import Quat, quat_mul, quat_yaw

MAX_DEPTH = 32  # links walked before a chain counts as a loop


def quat_rotate(q: Quat, v: np.ndarray) -> np.ndarray:
    """The vector ``v`` (3,) turned by the unit quaternion ``q`` (x, y, z, w)."""
    u, w = q[:3], q[3]
    uv = np.cross(u, v)
    turned: np.ndarray = v + 2.0 * (w * uv + np.cross(u, uv))
    return turned


@dataclass(slots=True, frozen=True)
class Rigid3D:
    """A frame's pose in its parent: translation ``t`` (3,) and rotation ``q``."""

    t: np.ndarray
    q: Quat

    @classmethod
    def identity(cls) -> Rigid3D:
        return cls(np.zeros(3), np.array([0.0, 0.0, 0.0, 1.0]))

    def compose(self, inner: Rigid3D) -> Rigid3D:
        """``inner`` (given in this frame) in this frame's parent."""
        return Rigid3D(self.t + quat_rotate(self.q, inner.t), quat_mul(self.q, inner.q))

    def inverse(self) -> Rigid3D:
        """The parent's pose in this frame."""
        q = self.q * np.array([-1.0, -1.0, -1.0, 1.0])
        return Rigid3D(-quat_rotate(q, self.t), q)

    def planar(self) -> Pose2D:
        """x, y and the yaw: the frame as a planar pose."""
        return Pose2D(float(self.t[0]), float(self.t[1]), quat_yaw(self.q))


class StaticFrames:
    """``add(msg)`` as ``{ns}/tf_static`` arrives; :meth:`up_to` a known frame."""

    def __init__(self) -> None:
        self._links: dict[str, tuple[str, Rigid3D]] = {}  # child: parent, child in parent

    def add(self, msg: TFMessage) -> None:
        for link in msg.transforms:
            if link.child_frame_id and link.header.frame_id:
                t, r = link.transform.translation, link.transform.rotation
                q = np.array([r.x, r.y, r.z, r.w], dtype=np.float64)  # unit (the model's)
                at = Rigid3D(np.array([t.x, t.y, t.z]), q / np.linalg.norm(q))
                self._links[link.child_frame_id] = (link.header.frame_id, at)

    def up_to(self, frame: str, known: Callable[[str], bool]) -> tuple[str, Rigid3D]:
        """The first known frame up ``frame``'s chain and ``frame``'s pose in it;
        LookupError naming the missing link when no chain leads there."""
        pose, at = Rigid3D.identity(), frame
        for _ in range(MAX_DEPTH):
            if known(at):
                return at, pose
            link = self._links.get(at)
            if link is None:
                whose = "" if at == frame else f" (a parent of '{frame}')"
                raise LookupError(f"no transform to frame '{at}'{whose} on tf_static")
            at, pose = link[0], link[1].compose(pose)
        raise LookupError(f"frame '{frame}': no known frame within {MAX_DEPTH} links (a loop?)")

    def lift(self, seen: StampedPose3D, known: Callable[[str], bool]) -> StampedPose3D:
        """A detection given in any frame, expressed in the first known frame up its
        chain (unchanged when its own frame is known)."""
        frame, link = self.up_to(seen.frame, known)
        if frame == seen.frame:
            return seen
        placed = link.compose(Rigid3D(np.array([seen.x, seen.y, seen.z]), seen.q))
        x, y, z = (float(c) for c in placed.t)
        return replace(seen, x=x, y=y, z=z, q=placed.q, frame=frame)
