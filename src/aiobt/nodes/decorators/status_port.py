"""Ports of type :class:`Status` (BT.CPP's ``NodeStatus``): ``else``, ``if_empty``.

Importing this module teaches port conversion to read ``SUCCESS``,
``FAILURE``, ``SKIPPED``, ``RUNNING`` and ``IDLE`` (case-insensitive).
"""

from __future__ import annotations

from aiobt.core.convert import register_converter
from aiobt.core.status import Status


def status_from_text(text: str) -> Status:
    word = text.strip().upper()
    try:
        return Status[word]
    except KeyError:
        names = ", ".join(s.name for s in Status)
        raise ValueError(f"{text!r} is not a node status ({names})") from None


register_converter(Status, status_from_text, "BT::NodeStatus")
