"""A command's failure says what to do next when that is known."""

from __future__ import annotations

from aiobt.cli.failure import failure
from aiobt.transport import BusUnavailable, ServerUnavailable


def test_no_router_and_no_navigator_each_get_their_next_step() -> None:
    no_router = BusUnavailable("cannot open the Zenoh session: no router at tcp/127.0.0.1:7447")
    assert failure("navigate", no_router).endswith(
        "no router at tcp/127.0.0.1:7447; start it with `aiobt up`, or point at one with "
        "--connect ENDPOINT"
    )
    no_server = ServerUnavailable("action server robot/action/navigate_to_pose: not present")
    assert failure("navigate", no_server).endswith("; is the navigator up? `aiobt status` lists "
                                                   "what is, `aiobt up` starts it")  # fmt: skip
    assert failure("goal", ValueError("goal x must be a finite number")) == (
        "aiobt goal: goal x must be a finite number"
    )
