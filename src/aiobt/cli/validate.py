"""``aiobt validate TREE.xml...``: load and check trees without ticking them.

    aiobt validate trees/nav2/*.xml
    aiobt validate mission.xml --plugin mypkg.nodes --nodes-model theirs.xml

Each file is loaded with every registered node (built-ins, Nav2's, and what
``--plugin`` / ``--nodes-model`` add) and every ``<BehaviorTree>`` in it is
built: node IDs, ports, port values, children counts, SubTree remapping. A
file with a ``<TreeNodesModel>`` and no tree (Nav2's ``nav2_tree_nodes.xml``)
is valid when its models read. No bus, no services, nothing ticks. Exit
status 0 only when every file is valid; each error names the file, line, node
and port.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from aiobt.cli import run as run_cli
from aiobt.core.blackboard import Blackboard
from aiobt.core.errors import BlackboardError, TreeLoadError
from aiobt.display import plural
from aiobt.xml.model import read_tree_nodes_model


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("files", nargs="+", metavar="TREE.xml", help="the XML files to check")
    run_cli.add_node_source_arguments(parser)
    parser.set_defaults(stub=[])


def validate_file(args: argparse.Namespace, path: str) -> str:
    """What ``path`` holds (its trees, each built once, or its node models);
    TreeLoadError on the first error."""
    factory = run_cli.build_factory(args)
    ids = factory.register_behavior_tree_from_file(path)
    if not ids:
        models = len(read_tree_nodes_model(Path(path)))
        if not models:
            raise TreeLoadError("no <BehaviorTree> and no <TreeNodesModel> in this file", file=path)
        return f"{plural(models, 'node model')}, no tree"
    for tree_id in ids:
        factory.create_tree(tree_id, blackboard=Blackboard.create())
    return ", ".join(ids)


def run(args: argparse.Namespace) -> int:
    failed = 0
    for path in args.files:
        try:
            holds = validate_file(args, path)
        except (TreeLoadError, BlackboardError, OSError) as exc:
            print(f"INVALID {run_cli.explain(exc)}", file=sys.stderr)
            failed += 1
            continue
        except ImportError as exc:
            print(f"aiobt validate: --plugin: {exc}", file=sys.stderr)
            return 2
        print(f"ok      {path} ({holds})")
    total = len(args.files)
    print(f"{total - failed} of {total} files valid", file=sys.stderr if failed else sys.stdout)
    return 1 if failed else 0
