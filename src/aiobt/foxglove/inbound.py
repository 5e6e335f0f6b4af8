"""What a Foxglove client publishes -> aiobt messages: goals (``/goal_pose``) and pose
estimates (``/initialpose``), in aiobt's, ROS's or Foxglove's JSON forms."""

from __future__ import annotations

import json
from typing import Any

from aiobt.msgs import PoseStamped, PoseWithCovarianceStamped, decode


def goal_from_json(payload: bytes) -> PoseStamped:
    """A goal from a Foxglove client: aiobt's PoseStamped JSON (also its short form
    ``{"x", "y", "yaw"}``), ROS's ``geometry_msgs/PoseStamped`` JSON (stamp as
    ``{sec, nanosec}``) or Foxglove's ``PoseInFrame`` (``frame_id`` and ``pose``).
    A bad payload is a :class:`~aiobt.msgs.MessageError` naming the field."""
    return decode(PoseStamped, json.dumps(_aiobt_form(payload, "goal")), key="goal")


def initialpose_from_json(payload: bytes) -> PoseWithCovarianceStamped:
    """A pose estimate from a Foxglove client (the 3D panel's tool): ROS's
    ``geometry_msgs/PoseWithCovarianceStamped`` JSON, or any form :func:`goal_from_json`
    takes (then with Nav2's default covariance). A bad payload is a
    :class:`~aiobt.msgs.MessageError` naming the field."""
    data = _aiobt_form(payload, "initialpose")
    return decode(PoseWithCovarianceStamped, json.dumps(data), key="initialpose")


def _aiobt_form(payload: bytes, what: str) -> Any:
    """A client's JSON with Foxglove's ``PoseInFrame`` and ROS's header (stamp as
    ``{sec, nanosec}``, dropped: the receiver stamps it) in aiobt's shape."""
    try:
        data = json.loads(payload)
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ValueError(f"{what} is not JSON: {exc}") from None
    if isinstance(data, dict) and "pose" in data and "header" not in data:
        return {"header": {"frame_id": data.get("frame_id") or "map"}, "pose": data["pose"]}
    if isinstance(data, dict) and isinstance(data.get("header"), dict):
        header = dict(data["header"])
        if isinstance(header.get("stamp"), dict):
            header.pop("stamp")
        header["frame_id"] = header.get("frame_id") or "map"
        return {**data, "header": header}
    return data
