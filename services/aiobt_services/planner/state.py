"""The planner's world model: the global costmap (:mod:`aiobt.costmap.world`) and the
search graph kept up to date with it."""

from __future__ import annotations

from dataclasses import dataclass, field

from aiobt.costmap.world import MAP_FRAMES, POSES_KEPT, FedCostmap, WorldOptions

from .traversal import SearchParams, Traversal

__all__ = ["MAP_FRAMES", "POSES_KEPT", "CostmapOptions", "GlobalCostmap"]


@dataclass(frozen=True, slots=True)
class CostmapOptions(WorldOptions):
    search: SearchParams = field(default_factory=lambda: SearchParams(downsample=2))


class GlobalCostmap(FedCostmap):
    """:class:`FedCostmap` plus the search graph on it, updated with each fold so that
    a plan request takes the costmap and traversal as they are, as Nav2's planner reads
    its global costmap, and does no costmap work of its own."""

    __slots__ = ("_traversal",)
    options: CostmapOptions

    def __init__(self, options: CostmapOptions | None = None) -> None:
        super().__init__(options or CostmapOptions())
        self._traversal: tuple[int, Traversal] | None = None

    def _map_changed(self) -> None:
        traversal = self.traversal()  # inflated and built now, not by the first request
        if traversal is not None:
            traversal.graph()

    def _folded_scan(self) -> None:
        self.traversal()  # ready before a request reads it

    def traversal(self) -> Traversal | None:
        """Search weights for the current snapshot: the last traversal updated in the
        window the costmap changed, or built anew after a new map or a clearing."""
        grid = self.snapshot()
        if grid is None or self.costmap is None:
            return None
        version, cached = self.costmap.version, self._traversal
        if cached is not None and cached[0] == version:
            return cached[1]
        window = None if cached is None else self.costmap.changed_since(cached[0])
        if cached is not None and window is not None and cached[1].fine.geometry == grid.geometry:
            traversal = cached[1].updated(grid, window)
        else:
            traversal = Traversal(grid, self.options.search)
        self._traversal = (version, traversal)
        return traversal
