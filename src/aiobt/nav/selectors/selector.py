"""Nav2's selector leaves: which planner, controller, checker... to use, set at run time.

Each reads a latched topic ``{ns}/{topic_name}`` (std_msgs/String; plain text,
a JSON string or ``{"data": ...}`` all work, so ``zenoh put -k
robot/planner_selector -v GridBased`` switches it) and writes the last value
received, or its ``default_*`` port until a message came, to its output.
"""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.blackboard import Entry
from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import PortInfo, input_port, output_port
from aiobt.core.status import FAILURE, IDLE, SUCCESS, Status
from aiobt.msgs import String
from aiobt.nav.context import NavNode
from aiobt.nav.shared_topics import SharedTopic, shared_topics, topic_name


def selector_ports(what: str, topic: str, default: str, output: str) -> tuple[PortInfo, ...]:
    return (
        input_port(
            "topic_name",
            str,
            topic,
            f"The name of the topic used to receive {what} selection messages.",
        ),
        input_port(
            default,
            str,
            description=f"The {what} selected until a message is received on the topic.",
        ),
        output_port(output, str, description=f"The selected {what} id."),
    )


class Selector(NavNode, SyncActionNode):
    """Base of the selectors; subclasses name their ports.

    - SUCCESS, writing the last value received on ``topic_name`` (or the default
      port's value until one came) to the output port;
    - FAILURE when nothing was received and the default is empty (as Nav2).

    A blackboard-bound ``topic_name`` is read again whenever the node starts
    afresh (IDLE), so it may change between runs; a literal one is subscribed
    once, at construction.
    """

    __slots__ = ("_default", "_fixed_topic", "_output_key", "_topic", "_topic_name", "_written")
    DEFAULT_PORT: ClassVar[str] = ""
    OUTPUT_PORT: ClassVar[str] = ""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._topic: SharedTopic[String] | None = None
        self._topic_name = ""
        self._output_key = self.config.outputs.get(self.OUTPUT_PORT)
        self._written: Entry | None = None  # the output's entry, as last written or seen
        default = self.config.inputs.get(self.DEFAULT_PORT)
        self._default: str | None = "" if default is None else default.value
        if default is not None and default.key is not None:
            self._default = None
        binding = self.config.inputs.get("topic_name")
        literal = binding is None or binding.key is None
        self._fixed_topic = False  # a literal topic_name, once subscribed, never changes
        if self.nav.bus is not None and literal:
            self._subscribe()  # now: the latched value arrives before the first tick
            self._fixed_topic = True

    def _subscribe(self) -> SharedTopic[String]:
        name = topic_name(self.get_input("topic_name"), self.path, "topic_name")
        if self._topic is None or name != self._topic_name:
            self._topic = shared_topics(self.nav, self.path).topic(name, String, latched=True)
            self._topic_name = name
        return self._topic

    def on_tick(self) -> Status:
        topic = self._topic
        if topic is None or (self._status is IDLE and not self._fixed_topic):
            topic = self._subscribe()
        message = topic.latest
        selected: str = message.data if message is not None else ""
        if not selected:
            default = self._default
            # bound to the blackboard: read on each tick
            selected = self.get_input(self.DEFAULT_PORT, "") if default is None else default
            if not selected:
                return FAILURE
        key = self._output_key
        if key is None:  # not connected
            return SUCCESS
        # unchanged: not written again (Nav2 rewrites it on every tick). The entry is
        # kept between ticks: an unset entry says so (has_value False), so is looked up again
        written = self._written
        if written is not None and written.has_value and written.value == selected:
            return SUCCESS
        board = self.config.blackboard
        entry = board.entry(key)
        if entry is None or entry.value != selected or not entry.has_value:
            board.set(key, selected)
            entry = board.entry(key)
        self._written = entry
        return SUCCESS


class PlannerSelector(Selector):
    """``<PlannerSelector topic_name="planner_selector" default_planner="GridBased"
    selected_planner="{selected_planner}"/>`` (Nav2): the planner id for ComputePathToPose."""

    __slots__ = ()
    PORTS = selector_ports("planner", "planner_selector", "default_planner", "selected_planner")
    DEFAULT_PORT, OUTPUT_PORT = "default_planner", "selected_planner"


class ControllerSelector(Selector):
    """``<ControllerSelector topic_name="controller_selector" default_controller="FollowPath"
    selected_controller="{selected_controller}"/>`` (Nav2): the controller id for FollowPath."""

    __slots__ = ()
    PORTS = selector_ports(
        "controller", "controller_selector", "default_controller", "selected_controller"
    )
    DEFAULT_PORT, OUTPUT_PORT = "default_controller", "selected_controller"


class SmootherSelector(Selector):
    """``<SmootherSelector topic_name="smoother_selector" default_smoother="simple_smoother"
    selected_smoother="{selected_smoother}"/>`` (Nav2): the smoother id for SmoothPath."""

    __slots__ = ()
    PORTS = selector_ports("smoother", "smoother_selector", "default_smoother", "selected_smoother")
    DEFAULT_PORT, OUTPUT_PORT = "default_smoother", "selected_smoother"


class GoalCheckerSelector(Selector):
    """``<GoalCheckerSelector topic_name="goal_checker_selector"
    default_goal_checker="general_goal_checker" selected_goal_checker="{goal_checker}"/>``
    (Nav2): the goal checker id for FollowPath."""

    __slots__ = ()
    PORTS = selector_ports(
        "goal checker", "goal_checker_selector", "default_goal_checker", "selected_goal_checker"
    )
    DEFAULT_PORT, OUTPUT_PORT = "default_goal_checker", "selected_goal_checker"


class ProgressCheckerSelector(Selector):
    """``<ProgressCheckerSelector topic_name="progress_checker_selector"
    default_progress_checker="progress_checker" selected_progress_checker="{pc}"/>``
    (Nav2): the progress checker id for FollowPath."""

    __slots__ = ()
    PORTS = selector_ports(
        "progress checker",
        "progress_checker_selector",
        "default_progress_checker",
        "selected_progress_checker",
    )
    DEFAULT_PORT, OUTPUT_PORT = "default_progress_checker", "selected_progress_checker"


class PathHandlerSelector(Selector):
    """``<PathHandlerSelector topic_name="path_handler_selector"
    default_path_handler="PathHandler" selected_path_handler="{ph}"/>`` (Nav2): the path
    handler id for FollowPath."""

    __slots__ = ()
    PORTS = selector_ports(
        "path handler", "path_handler_selector", "default_path_handler", "selected_path_handler"
    )
    DEFAULT_PORT, OUTPUT_PORT = "default_path_handler", "selected_path_handler"
