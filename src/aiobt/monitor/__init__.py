"""A live view of the navigator's tree from its status stream (``aiobt monitor``)."""

from aiobt.monitor.view import TreeView

__all__ = ["TreeView"]
