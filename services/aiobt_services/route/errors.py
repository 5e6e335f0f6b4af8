"""The route server's failures, named as Nav2's error codes name them."""

from __future__ import annotations

from aiobt.msgs.errors import ComputeRouteError


class RouteError(Exception):
    """A request that fails with Nav2's ``reason`` (a :class:`ComputeRouteError` name,
    e.g. ``NO_VALID_ROUTE``) and a message saying what and where."""

    def __init__(self, reason: str, message: str) -> None:
        if reason not in ComputeRouteError.__members__:
            raise ValueError(f"route error: unknown reason {reason!r}")
        super().__init__(message)
        self.reason = reason
        self.message = message

    @property
    def code(self) -> int:
        return int(ComputeRouteError[self.reason])


class GraphError(RouteError):
    """A graph file that cannot be used (NO_VALID_GRAPH), naming the file and the feature."""

    def __init__(self, path: str, where: str, problem: str) -> None:
        super().__init__("NO_VALID_GRAPH", f"route graph {path}: {where}: {problem}")
        self.path = path
        self.where = where
