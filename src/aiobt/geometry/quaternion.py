"""Unit quaternions ``(x, y, z, w)`` as tf2 uses them, for what a detector reports in
3D (a fiducial's full orientation): the product, tf2's ``setRPY``, the yaw, slerp."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from aiobt.msgs.geometry import quaternion_to_yaw

Quat = npt.NDArray[np.float64]  # x, y, z, w


def quat_mul(a: Quat, b: Quat) -> Quat:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ])  # fmt: skip


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> Quat:
    """tf2's ``setRPY``: about the fixed x, then y, then z axes."""

    def axis(i: int, angle: float) -> Quat:
        q = np.zeros(4)
        q[i], q[3] = math.sin(0.5 * angle), math.cos(0.5 * angle)
        return q

    return quat_mul(axis(2, yaw), quat_mul(axis(1, pitch), axis(0, roll)))


def quat_from_yaw(yaw: float) -> Quat:
    return np.array([0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw)])


def quat_yaw(q: Quat) -> float:
    return quaternion_to_yaw(*(float(c) for c in q))


def slerp(a: Quat, b: Quat, t: float) -> Quat:
    """tf2's ``slerp``: ``t`` of the way from ``a`` to ``b``, along the shorter arc."""
    dot = float(np.dot(a, b))
    if dot < 0.0:
        b, dot = -b, -dot
    if dot > 0.9995:
        q = a + t * (b - a)
        return np.asarray(q / np.linalg.norm(q), dtype=np.float64)
    theta = math.acos(dot)
    q = (math.sin((1.0 - t) * theta) * a + math.sin(t * theta) * b) / math.sin(theta)
    return np.asarray(q, dtype=np.float64)
