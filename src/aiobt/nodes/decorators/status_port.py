"""Ports of type :class:`Status` (BT.CPP's ``NodeStatus``): ``else``, ``if_empty``.

Importing this module teaches port conversion to read ``SUCCESS``,
``FAILURE``, ``SKIPPED``, ``RUNNING`` and ``IDLE`` (case-insensitive).
"""

from __future__ import annotations

from aiobt.core.convert import register_converter
from aiobt.core.node import TreeNode
from aiobt.core.status import Status


def status_from_text(text: str) -> Status:
    word = text.strip().upper()
    try:
        return Status[word]
    except KeyError:
        names = ", ".join(s.name for s in Status)
        raise ValueError(f"{text!r} is not a node status ({names})") from None


def status_input(node: TreeNode, name: str) -> Status:
    """Input port ``name`` as a Status (a blackboard entry may hold a Status or its name)."""
    value = node.get_input(name)
    return value if isinstance(value, Status) else status_from_text(str(value))


register_converter(Status, status_from_text, "BT::NodeStatus")
