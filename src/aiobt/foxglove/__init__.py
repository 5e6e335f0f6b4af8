"""Foxglove: the robot's topics live over Foxglove's WebSocket protocol and in MCAP.

:func:`running_bridge` runs :class:`FoxgloveBridge` with a server and/or a
recording; :mod:`aiobt.foxglove.convert` holds the message conversions and
:mod:`aiobt.foxglove.channels` the topic list. ``LAYOUT`` is the shipped
Foxglove layout (docs/foxglove.md).
"""

from pathlib import Path

from aiobt.foxglove.bridge import FoxgloveBridge
from aiobt.foxglove.server import DEFAULT_PORT, LOCAL_HOST, BridgeOptions, running_bridge

LAYOUT = Path(__file__).parent / "layouts" / "aiobt.json"

__all__ = [
    "DEFAULT_PORT",
    "LAYOUT",
    "LOCAL_HOST",
    "BridgeOptions",
    "FoxgloveBridge",
    "running_bridge",
]
