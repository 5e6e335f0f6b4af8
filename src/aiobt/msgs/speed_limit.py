"""``nav2_msgs/SpeedLimit``: a speed limit for the controller, as a percentage or in m/s."""

from __future__ import annotations

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header


class SpeedLimit(Msg):
    """``percentage`` true: ``speed_limit`` is a share (0-100] of the maximum speed;
    false: m/s. 0 means no limit, as in Nav2."""

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    percentage: bool = True
    speed_limit: float = Field(default=0.0, ge=0.0)
