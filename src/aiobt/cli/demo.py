"""``aiobt demo``: the main job, the example patrol mission.

A robot patrols three waypoints twice on a clock running ``--speed`` times
faster than the wall; its battery drains while it moves, a reactive check
halts the move when the battery runs low, and it charges and goes on. See
:mod:`aiobt.examples.patrol`.
"""

from __future__ import annotations

import argparse
import sys

from aiobt.cli import run as run_cli
from aiobt.core.errors import BlackboardError, TreeLoadError
from aiobt.examples import patrol


def add_arguments(parser: argparse.ArgumentParser) -> None:
    run_cli.add_tree_arguments(parser)
    parser.set_defaults(speed=20.0, max_time=600.0)


def run(args: argparse.Namespace) -> int:
    if "aiobt.examples.patrol" not in args.plugin:
        args.plugin.insert(0, "aiobt.examples.patrol")
    try:
        factory = run_cli.build_factory(args)
        factory.register_behavior_tree_from_text(patrol.PATROL_XML, file=patrol.__file__)
        bb = run_cli.root_blackboard(args.entries, patrol.INITIAL_STATE)
        tree = factory.create_tree(args.tree, blackboard=bb, clock=run_cli.make_clock(args.speed))
    except (TreeLoadError, BlackboardError, ImportError) as exc:
        print(f"aiobt demo: {exc}", file=sys.stderr)
        return 2
    print(f"patrol mission: 3 waypoints, 2 laps, clock x{args.speed:g}, battery {bb['battery']}")
    code = run_cli.finish(tree, args)
    pose = bb["pose"]
    print(f"battery {bb['battery']:.2f}, robot at ({pose[0]:.2f}, {pose[1]:.2f})")
    return code
