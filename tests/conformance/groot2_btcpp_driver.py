"""BT.CPP's Groot2Publisher over the conformance tree, driven through stdin.

``python -m tests.conformance.groot2_btcpp_driver PORT [late]`` prints ``ready`` once
the publisher is up, then answers each ``tick`` line with the status the tick
returned; ``quit`` (or end of input) stops it. With ``late`` the tree is
ticked once before the publisher is created. It runs in its own process: a
BT.CPP breakpoint blocks the ticking thread while holding Python's GIL.
"""

from __future__ import annotations

import sys

import behaviortreepy as btcpp

from tests.conformance.groot2_tree import ENTRIES, XML


def main(port: int, late: bool) -> None:
    factory = btcpp.BehaviorTreeFactory()
    factory.register_simple_condition("Check", lambda node: btcpp.NodeStatus.FAILURE)
    running = lambda node: btcpp.NodeStatus.RUNNING  # noqa: E731
    factory.register_simple_stateful_action("Slow", running, running, lambda node: None)
    blackboard = btcpp.Blackboard.create()
    blackboard.set_int("count", ENTRIES["count"])
    blackboard.set_string("target", ENTRIES["target"])
    blackboard.set_double("speed", ENTRIES["speed"])
    tree = factory.create_tree_from_text(XML, blackboard)
    if late:  # attach to a tree already running
        tree.tick_exactly_once()
    publisher = btcpp.Groot2Publisher(tree, port)
    print("ready", flush=True)
    for line in sys.stdin:
        if line.strip() == "tick":
            print(tree.tick_exactly_once().name, flush=True)
        elif line.strip() == "quit":
            break
    del publisher


if __name__ == "__main__":
    main(int(sys.argv[1]), sys.argv[2:] == ["late"])
