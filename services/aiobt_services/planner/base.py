"""The planner server's plugin contracts: Nav2's ``nav2_core::GlobalPlanner`` and
``nav2_core::Smoother``, in Python.

A planner plugin searches a :class:`~.traversal.Traversal` (the global costmap's
search weights) between two cells; the server turns the cells into poses. A
smoother plugin moves a path's poses off the obstacles' edges within a time budget.
Each server keeps its plugins in a registry by Nav2's plugin id (``GridBased``,
``simple_smoother``, ...), typed on these protocols (see docs/architecture.md,
"A planner algorithm").
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

from aiobt.costmap import CostGrid
from aiobt.geometry import XYYaw

if TYPE_CHECKING:
    from .smoother import SmoothResult
    from .traversal import Budget, Traversal


class GlobalPlanner(Protocol):
    """Finds a path of cell indices from ``start`` to ``goal`` on ``traversal``.

    Raises :class:`~.errors.PlanningError` with Nav2's reason (NO_VALID_PATH, ...) or
    :class:`~.errors.PlanningCancelled` when ``budget`` runs out or is cancelled.
    """

    def create_plan(
        self, traversal: Traversal, start: int, goal: int, budget: Budget | None = None
    ) -> list[int]: ...


class Smoother(Protocol):
    """Smooths ``poses`` on ``grid`` within ``max_duration`` seconds."""

    def smooth(
        self, grid: CostGrid, poses: Sequence[XYYaw], max_duration: float
    ) -> SmoothResult: ...
