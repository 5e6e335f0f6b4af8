"""The navigator's default trees, shipped with the package (read via importlib.resources).

A copy of the repository's ``trees/nav2/*.xml`` (the documented copy, see its
NOTICE.md); ``tests/unit/navigator/test_packaged_trees.py`` checks the two are
identical. Nav2's XML files are from https://github.com/ros-navigation/navigation2
(``nav2_bt_navigator/behavior_trees``, ``nav2_behavior_tree/nav2_tree_nodes.xml``),
Apache License 2.0, copyright the Nav2 contributors; except
``navigate_through_poses_w_replanning_and_recovery.xml``, written for aiobt.
"""
