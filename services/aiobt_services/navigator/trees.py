"""Which tree a goal runs: a file path or a registered tree ID, as bt_navigator.

The library registers every ``*.xml`` of its search directories once, so a
goal may name a tree by its ID (``NavigateToPoseWReplanningAndRecovery``); a
file that declares an ID registered earlier is skipped with a warning, as
Nav2 skips conflicting files. A ``behavior_tree`` ending in ``.xml`` is a file
path, read anew for every navigation (an edited file is picked up).
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from importlib import resources
from pathlib import Path

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import Clock
from aiobt.core.errors import BehaviorTreeError
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.xml.document import parse_file

log = logging.getLogger("aiobt_services.navigator.trees")


class TreeLoadFailure(Exception):
    """A goal's tree could not be loaded; the message names the tree and the cause."""


def packaged_trees_dir() -> Path:
    """Nav2's trees shipped with the library (``aiobt.trees``, the repository's
    ``trees/nav2`` as package data), found by an editable or a normal install."""
    folder = resources.files("aiobt.trees").joinpath("nav2")
    if not isinstance(folder, Path):  # e.g. imported from a zip archive
        raise TreeLoadFailure(f"the packaged trees ({folder}) are not a directory on disk")
    return folder


TREES_DIR = packaged_trees_dir()
DEFAULT_TO_POSE_TREE = TREES_DIR / "navigate_to_pose_w_replanning_and_recovery.xml"
DEFAULT_THROUGH_POSES_TREE = TREES_DIR / "navigate_through_poses_w_replanning_and_recovery.xml"


def is_tree_file(file_or_id: str) -> bool:
    """Nav2's rule: a name ending in ``.xml`` is a file, anything else a tree ID."""
    return file_or_id.endswith(".xml")


class TreeLibrary:
    """Loads the tree a goal asks for with one factory (nodes registered once)."""

    def __init__(self, factory: BehaviorTreeFactory, search_dirs: Iterable[Path] = ()) -> None:
        self.factory = factory
        for directory in search_dirs:
            self._register_directory(Path(directory))

    def _register_directory(self, directory: Path) -> None:
        if not directory.is_dir():
            raise TreeLoadFailure(f"tree search directory {directory} is not a directory")
        for file in sorted(directory.glob("*.xml")):
            self._register_file(file)

    def _register_file(self, file: Path) -> None:
        try:
            ids = [tree.tree_id for tree in parse_file(file).trees]
        except BehaviorTreeError as exc:
            log.warning("skipping tree file %s: %s", file, exc)
            return
        if not ids:  # e.g. a <TreeNodesModel> file
            log.debug("skipping %s: no BehaviorTree", file)
            return
        taken = [tree_id for tree_id in ids if tree_id in self.factory.definitions]
        if taken:
            log.warning(
                "skipping tree file %s: ID(s) %s already registered", file, ", ".join(taken)
            )
            return
        self.factory.register_behavior_tree_from_file(file)

    def check(self, file_or_id: str) -> None:
        """Raise :class:`TreeLoadFailure` if ``file_or_id`` names no file or known tree ID."""
        if is_tree_file(file_or_id):
            if not Path(file_or_id).is_file():
                raise TreeLoadFailure(f"behavior tree file {file_or_id} does not exist")
        elif file_or_id not in self.factory.definitions:
            known = ", ".join(sorted(self.factory.definitions)) or "none"
            raise TreeLoadFailure(
                f"behavior tree ID {file_or_id!r} is not registered (known IDs: {known}); "
                "give a file path ending in .xml or a registered ID"
            )

    def load(self, file_or_id: str, blackboard: Blackboard, clock: Clock) -> Tree:
        """Instantiate the tree on ``blackboard``; :class:`TreeLoadFailure` says why not."""
        self.check(file_or_id)
        try:
            if is_tree_file(file_or_id):
                return self.factory.create_tree_from_file(
                    file_or_id, blackboard=blackboard, clock=clock
                )
            return self.factory.create_tree(file_or_id, blackboard=blackboard, clock=clock)
        except BehaviorTreeError as exc:
            raise TreeLoadFailure(f"behavior tree {file_or_id} failed to load: {exc}") from exc
