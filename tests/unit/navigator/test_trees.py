"""Which tree a goal runs: registered IDs from the search directories, or a file."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import ManualClock
from aiobt.factory import BehaviorTreeFactory
from aiobt_services.navigator import TreeLibrary, TreeLoadFailure

from .harness import tree_xml, write_trees


def test_trees_by_id_and_by_file(tmp_path: Path) -> None:
    list(write_trees(tmp_path / "a", {"Alpha": "<AlwaysSuccess/>", "Beta": "<AlwaysFailure/>"}))
    library = TreeLibrary(BehaviorTreeFactory(), [tmp_path / "a"])
    tree = library.load("Beta", Blackboard.create(), ManualClock())
    assert tree.tree_id == "Beta"
    file = tmp_path / "own.xml"
    file.write_text(tree_xml("Own", '<SubTree ID="Alpha"/>'))  # may use registered trees
    assert library.load(str(file), Blackboard.create(), ManualClock()).tree_id == "Own"


def test_a_file_whose_id_is_taken_is_skipped(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    list(write_trees(tmp_path / "a", {"Alpha": "<AlwaysSuccess/>"}))
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "again.xml").write_text(tree_xml("Alpha", "<AlwaysFailure/>"))
    (tmp_path / "b" / "broken.xml").write_text("<root")
    with caplog.at_level(logging.WARNING, "aiobt_services.navigator.trees"):
        library = TreeLibrary(BehaviorTreeFactory(), [tmp_path / "a", tmp_path / "b"])
    assert "again.xml: ID(s) Alpha already registered" in caplog.text
    assert "broken.xml" in caplog.text
    assert library.load("Alpha", Blackboard.create(), ManualClock()).root.name == "AlwaysSuccess"


def test_unknown_names_are_refused_with_what_is_known(tmp_path: Path) -> None:
    list(write_trees(tmp_path, {"Alpha": "<AlwaysSuccess/>"}))
    library = TreeLibrary(BehaviorTreeFactory(), [tmp_path])
    with pytest.raises(TreeLoadFailure, match=r"ID 'Alpa' is not registered \(known IDs: Alpha\)"):
        library.check("Alpa")
    with pytest.raises(TreeLoadFailure, match=r"nowhere\.xml does not exist"):
        library.check(str(tmp_path / "nowhere.xml"))
    with pytest.raises(TreeLoadFailure, match="is not a directory"):
        TreeLibrary(BehaviorTreeFactory(), [tmp_path / "nowhere"])
