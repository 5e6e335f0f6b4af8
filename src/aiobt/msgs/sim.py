"""Simulation time, published on ``{ns}/clock`` when services run on sim time."""

from __future__ import annotations

from pydantic import Field

from aiobt.msgs._base import Msg


class Clock(Msg):
    """The simulation's time in seconds (``rosgraph_msgs/Clock``)."""

    clock: float = Field(ge=0.0)
