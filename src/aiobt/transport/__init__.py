"""Everything Zenoh: the bus (one session per process), topics, services, actions.

    parser = argparse.ArgumentParser(); add_bus_arguments(parser)
    async with open_bus(BusSettings.from_args(parser.parse_args())) as bus:
        bus.publisher("odom", Odometry).put(msg)                 # {ns}/odom
        bus.latched_publisher("map", OccupancyGrid).put(grid)    # late joiners get it
        sub = bus.subscribe("cmd_vel", Twist)                    # async for / sub.latest
        pose = bus.latest("pose", PoseStamped)                   # pose.get(): no loop wake-up
        bus.subscribe("map", OccupancyGrid, on_map, latched=True)
        bus.serve("is_path_valid", IsPathValid.Request, IsPathValid.Response, handler)
        resp = await bus.call("is_path_valid", req, IsPathValid.Response, timeout=2.0)
        bus.action_server("follow_path", FollowPath, execute, preemption="replace")
        client = bus.action_client("follow_path", FollowPath)
        goal = await client.send_goal(FollowPath.Goal(path=path), server_timeout=1.0)
        result = await goal.result()        # goal.status: SUCCEEDED / ABORTED / CANCELED
        await goal.cancel()

See docs/transport.md for the wire format and the action protocol.
"""

from aiobt.transport.actions import (
    ActionClient,
    ActionError,
    ActionServer,
    ClientGoal,
    Execute,
    GoalHandle,
    GoalLost,
    GoalRejected,
    ServerUnavailable,
)
from aiobt.transport.bridge import PayloadTooLarge
from aiobt.transport.bus import Bus, open_bus
from aiobt.transport.keys import ActionKeys, Keys
from aiobt.transport.latest import Latest
from aiobt.transport.presence import Presence
from aiobt.transport.publishers import Publisher
from aiobt.transport.services import ServiceError, ServiceServer, ServiceUnavailable
from aiobt.transport.session import BusUnavailable, open_session
from aiobt.transport.settings import (
    DEFAULT_NAMESPACE,
    DEFAULT_ROUTER,
    BusConfigError,
    BusSettings,
    add_bus_arguments,
)
from aiobt.transport.simclock import SimClockFollower
from aiobt.transport.topics import Subscription

__all__ = [
    "DEFAULT_NAMESPACE",
    "DEFAULT_ROUTER",
    "ActionClient",
    "ActionError",
    "ActionKeys",
    "ActionServer",
    "Bus",
    "BusConfigError",
    "BusSettings",
    "BusUnavailable",
    "ClientGoal",
    "Execute",
    "GoalHandle",
    "GoalLost",
    "GoalRejected",
    "Keys",
    "Latest",
    "PayloadTooLarge",
    "Presence",
    "Publisher",
    "ServerUnavailable",
    "ServiceError",
    "ServiceServer",
    "ServiceUnavailable",
    "SimClockFollower",
    "Subscription",
    "add_bus_arguments",
    "open_bus",
    "open_session",
]
