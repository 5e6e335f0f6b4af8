"""The action protocol over Zenoh: server, client, errors (see ``protocol``)."""

from aiobt.transport.actions.client import ActionClient
from aiobt.transport.actions.client_goal import ClientGoal
from aiobt.transport.actions.goals import GoalHandle
from aiobt.transport.actions.protocol import (
    ActionError,
    GoalLost,
    GoalRejected,
    ServerUnavailable,
)
from aiobt.transport.actions.runner import Execute
from aiobt.transport.actions.server import ActionServer

__all__ = [
    "ActionClient",
    "ActionError",
    "ActionServer",
    "ClientGoal",
    "Execute",
    "GoalHandle",
    "GoalLost",
    "GoalRejected",
    "ServerUnavailable",
]
