"""A patrol mission with example nodes: what ``aiobt demo`` runs.

A robot visits waypoints twice. Moving drains its battery; a reactive check
halts the move when the battery runs low, the robot charges, and the retry
sends it on again. It shows async leaves (cancelled mid-move), a reactive
parent, SubTrees with remapping, Retry/Repeat, Timeout and the injected clock,
without any transport.

Run it with ``aiobt demo`` or ``aiobt run <file> --plugin aiobt.examples.patrol``.
"""

from __future__ import annotations

import logging
import math

from aiobt.core.leaves import AsyncActionNode, ConditionNode
from aiobt.core.ports import inout_port, input_port
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory

log = logging.getLogger("aiobt.examples.patrol")

PATROL_XML = """\
<root BTCPP_format="4" main_tree_to_execute="Patrol">
  <BehaviorTree ID="Patrol">
    <Repeat name="two_laps" num_cycles="2">
      <Sequence name="lap">
        <SubTree ID="Visit" name="visit_a" goal="2.0;0.0"/>
        <SubTree ID="Visit" name="visit_b" goal="2.0;1.5"/>
        <SubTree ID="Visit" name="visit_home" goal="0.0;0.0"/>
      </Sequence>
    </Repeat>
  </BehaviorTree>

  <BehaviorTree ID="Visit">
    <RetryUntilSuccessful name="retry_visit" num_attempts="3">
      <Fallback name="go_or_charge">
        <ReactiveSequence name="go_while_charged">
          <BatteryOk name="battery_ok" level="{@battery}" min_level="0.25"/>
          <Timeout name="leg_timeout" msec="30000">
            <MoveTo name="move" goal="{goal}" pose="{@pose}" battery="{@battery}"/>
          </Timeout>
        </ReactiveSequence>
        <ForceFailure name="then_retry">
          <Charge name="charge" battery="{@battery}"/>
        </ForceFailure>
      </Fallback>
    </RetryUntilSuccessful>
  </BehaviorTree>
</root>
"""

# the blackboard the mission starts from
INITIAL_STATE: dict[str, object] = {"battery": 0.6, "pose": [0.0, 0.0]}


class BatteryOk(ConditionNode):
    """SUCCESS while the battery level is at least ``min_level``."""

    __slots__ = ()
    PORTS = (
        input_port("level", float, description="battery level, 0..1"),
        input_port("min_level", float, 0.2, "lowest acceptable level"),
    )

    def check(self) -> bool:
        level: float = self.get_input("level")
        minimum: float = self.get_input("min_level")
        return level >= minimum


class MoveTo(AsyncActionNode):
    """Drive in a straight line to ``goal`` at ``speed`` m/s of clock time,
    updating ``pose`` and draining ``battery`` (``drain`` per metre)."""

    __slots__ = ()
    PORTS = (
        input_port("goal", list[float], description="x;y in metres"),
        inout_port("pose", list[float], description="x;y, updated while moving"),
        inout_port("battery", float, description="battery level, drained while moving"),
        input_port("speed", float, 0.5, "m/s"),
        input_port("drain", float, 0.05, "battery per metre"),
        input_port("step", float, 0.1, "control period in seconds"),
    )

    async def run(self) -> Status:
        goal = self.get_input("goal")
        speed, drain, step = (
            self.get_input("speed"),
            self.get_input("drain"),
            self.get_input("step"),
        )
        if len(goal) != 2:
            raise ValueError(f"goal must be x;y, got {goal!r}")
        x, y = self.get_input("pose")
        try:
            while (remaining := math.hypot(goal[0] - x, goal[1] - y)) > 1e-6:
                await self.clock.sleep(step)
                moved = min(speed * step, remaining)
                x += (goal[0] - x) * moved / remaining
                y += (goal[1] - y) * moved / remaining
                self.set_output("pose", [x, y])
                self.set_output("battery", max(0.0, self.get_input("battery") - drain * moved))
        finally:
            log.debug("%s: at (%.2f, %.2f)", self.path, x, y)
        return Status.SUCCESS


class Charge(AsyncActionNode):
    """Charge ``battery`` at ``rate`` per second until it reaches ``target``."""

    __slots__ = ()
    PORTS = (
        inout_port("battery", float, description="battery level, 0..1"),
        input_port("rate", float, 0.2, "charge per second"),
        input_port("target", float, 1.0, "level to stop at"),
    )

    async def run(self) -> Status:
        rate, target = self.get_input("rate"), self.get_input("target")
        level: float = self.get_input("battery")
        while level < target:
            await self.clock.sleep(0.1)
            level = min(target, level + rate * 0.1)
            self.set_output("battery", level)
        return Status.SUCCESS


def register(factory: BehaviorTreeFactory) -> None:
    """Register the example nodes (the ``--plugin`` entry point)."""
    for node_class in (BatteryOk, MoveTo, Charge):
        factory.register_node_type(node_class)
