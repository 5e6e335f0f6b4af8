"""The key layout of the wire contract (docs/architecture.md), in one place.

``{ns}/{topic}`` for topics, ``{ns}/srv/{service}`` for services and
``{ns}/action/{server}/...`` for actions. A server's liveliness token sits on
its service or action base key. The simulation's own keys follow the same rule in
the namespace ``{ns}/sim`` (:func:`sim_namespace`).
"""

from __future__ import annotations

import re

_FORBIDDEN = re.compile(r"[*$?#\s]|//")


def check_name(name: str, what: str) -> str:
    """``name`` if it is a usable key chunk path (no wildcards, no empty chunks)."""
    if not name or name.startswith("/") or name.endswith("/") or _FORBIDDEN.search(name):
        raise ValueError(
            f"{what} {name!r} is not a valid key: no wildcards (* $ ? #), spaces, "
            "empty or leading/trailing '/' chunks"
        )
    return name


# The simulation's own keys live in a namespace of their own inside the robot's,
# ``{ns}/sim``: its truth (``{ns}/sim/pose``, ``{ns}/sim/target``) and its services
# (``{ns}/sim/srv/{service}``: teleport, obstacles, snapshot, step, the followed box),
# for tests, benchmarks and pictures only. No navigation service reads or calls them (a
# real robot has none). ``{ns}/clock`` is not one of them: a real robot on sim time
# has it too, as ROS has ``/clock``.
SIM_PREFIX = "sim"


def sim_namespace(namespace: str) -> str:
    """The simulation's namespace inside robot ``namespace``: ``{ns}/sim``. Its topics
    are ``{ns}/sim/{topic}`` and its services ``{ns}/sim/srv/{service}``, by the
    :class:`Keys` rule (``bus.serve(..., namespace=sim_namespace(bus.namespace))``,
    ``bus.call(..., namespace=...)``)."""
    return f"{check_name(namespace, 'namespace')}/{SIM_PREFIX}"


def sim_topic(name: str) -> str:
    """The topic name relative to the robot's namespace (for :meth:`Keys.topic` and the
    bus) of the simulation's ``name``: ``sim/{name}``, the topic ``name`` of
    :func:`sim_namespace`."""
    return f"{SIM_PREFIX}/{check_name(name, 'sim topic')}"


SIM_POSE = sim_topic("pose")  # the simulation's truth: PoseStamped of the robot in map


class Keys:
    """Key expressions of one robot namespace."""

    __slots__ = ("namespace",)

    def __init__(self, namespace: str) -> None:
        self.namespace = check_name(namespace, "namespace")

    def topic(self, name: str) -> str:
        return f"{self.namespace}/{check_name(name, 'topic')}"

    def service(self, name: str) -> str:
        return f"{self.namespace}/srv/{check_name(name, 'service')}"

    def action(self, server: str) -> ActionKeys:
        return ActionKeys(f"{self.namespace}/action/{check_name(server, 'action server')}")

    @property
    def sim(self) -> Keys:
        """The keys of the simulation's namespace, ``{ns}/sim`` (:func:`sim_namespace`)."""
        return Keys(sim_namespace(self.namespace))


class ActionKeys:
    """Keys of one action server under ``{ns}/action/{server}``.

    - ``goal?id={id}``: queryable on ``goal``; the send_goal query, whose reply
      stream carries accepted/rejected, feedback and finally the result (the id
      is a selector parameter, so every goal shares one cached route)
    - ``cancel``: queryable; cancel one goal (``goal_id``) or all (empty id)
    - ``status/{id}``, ``feedback/{id}``, ``result/{id}``: published for
      observers; ``result/{id}`` is also a queryable answering the result
    - the base key itself: the server's liveliness token
    """

    __slots__ = ("base",)

    def __init__(self, base: str) -> None:
        self.base = base

    @property
    def goal(self) -> str:
        return f"{self.base}/goal"

    def goal_selector(self, goal_id: str) -> str:
        return f"{self.base}/goal?id={goal_id}"

    @property
    def cancel(self) -> str:
        return f"{self.base}/cancel"

    @property
    def any_status(self) -> str:
        return f"{self.base}/status/*"

    @property
    def any_feedback(self) -> str:
        return f"{self.base}/feedback/*"

    @property
    def any_result(self) -> str:
        return f"{self.base}/result/*"

    def status(self, goal_id: str) -> str:
        return f"{self.base}/status/{goal_id}"

    def feedback(self, goal_id: str) -> str:
        return f"{self.base}/feedback/{goal_id}"

    def result(self, goal_id: str) -> str:
        return f"{self.base}/result/{goal_id}"

    @property
    def alive(self) -> str:
        return self.base
