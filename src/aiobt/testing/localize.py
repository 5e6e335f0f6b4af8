"""Telling localization where the robot is, as a user does with RViz's "2D Pose
Estimate": after a test teleports the robot through the simulation (which the filter
is not told of), or to seed it.

    await set_estimate(bus, 2.0, 9.75, 0.0)   # initialpose, then amcl_pose there (bounded)
"""

from __future__ import annotations

import asyncio
import contextlib
import math

from aiobt.msgs import PoseWithCovarianceStamped
from aiobt.transport import Bus

# standard deviations of a pose a test knows exactly: x, y (m) and yaw (rad); small,
# not zero (the filter draws its particles from them), well inside the goal tolerances
KNOWN_POSE_STD = (0.02, 0.02, 0.02)
NEAR = 0.1  # m: an amcl_pose this near the pose set is the filter having taken it
LATCHED_WAIT = 2.0  # wall s for the latched amcl_pose, when the filter has published one


def covariance(std_x: float, std_y: float, std_yaw: float) -> list[float]:
    """The row-major 6x6 covariance (x, y, z, roll, pitch, yaw) of independent x, y, yaw."""
    return [{0: std_x**2, 7: std_y**2, 35: std_yaw**2}.get(i, 0.0) for i in range(36)]


class EstimateError(AssertionError):
    """Localization did not take the pose in time; the message says what it did."""


async def set_estimate(
    bus: Bus,
    x: float,
    y: float,
    yaw: float,
    std: tuple[float, float, float] = KNOWN_POSE_STD,
    timeout: float = 20.0,  # noqa: ASYNC109
) -> PoseWithCovarianceStamped:
    """Publish ``initialpose`` at (x, y, yaw) and wait (``timeout`` wall s at most) for
    an ``amcl_pose`` within :data:`NEAR` of it, stamped after the one latched before:
    the filter's first estimate from that pose (it comes with the next scan)."""
    amcl = bus.subscribe("amcl_pose", PoseWithCovarianceStamped, latched=True, queue_size=8)
    pub = bus.publisher("initialpose", PoseWithCovarianceStamped)
    try:
        if not await pub.wait_for_subscribers(timeout):
            raise EstimateError(f"nothing reads {pub.key}: is the localization service up?")
        before = -math.inf
        with contextlib.suppress(TimeoutError):  # none yet: the filter has no pose
            before = (await amcl.wait_latest(LATCHED_WAIT)).header.stamp
        pub.put(PoseWithCovarianceStamped.from_xy_yaw(x, y, yaw, covariance(*std)))
        try:
            async with asyncio.timeout(timeout):
                async for msg in amcl:
                    if msg.header.stamp > before and math.hypot(msg.x - x, msg.y - y) < NEAR:
                        return msg
        except TimeoutError:
            pass
        last = amcl.latest
        seen = f"({last.x:.2f}, {last.y:.2f}) at {last.header.stamp:.2f}" if last else "none"
        raise EstimateError(
            f"no amcl_pose near the initialpose ({x:.2f}, {y:.2f}) within {timeout} s; "
            f"the last: {seen}"
        )
    finally:
        amcl.close()
