"""IsBatteryLow and IsBatteryCharging (Nav2): the battery on ``battery_topic``."""

from __future__ import annotations

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.msgs import BatteryState, PowerSupplyStatus
from aiobt.nav.robot_state import BATTERY, RobotStateNode
from aiobt.nav.shared_topics import topic_name

NAV2_BATTERY_TOPIC = "/battery_status"  # Nav2's default, read as the robot's {ns}/battery

TOPIC_PORT = input_port(
    "battery_topic",
    str,
    NAV2_BATTERY_TOPIC,
    "Topic for battery info (Nav2's default /battery_status reads {ns}/battery).",
)


class _BatteryCondition(RobotStateNode, ConditionNode):
    READS = ()

    def battery(self) -> BatteryState | None:
        text: str = self.get_input("battery_topic")
        name = (
            BATTERY if text == NAV2_BATTERY_TOPIC else topic_name(text, self.path, "battery_topic")
        )
        return self.robot.battery(name)


class IsBatteryLow(_BatteryCondition):
    """``<IsBatteryLow min_battery="0.2" is_voltage="false"/>`` (Nav2).

    SUCCESS when the last battery message's ``percentage`` (0..1), or its
    ``voltage`` if ``is_voltage``, is at most ``min_battery``; FAILURE
    otherwise and before any message.
    """

    PORTS = (
        input_port("min_battery", float, description="Min battery percentage or voltage."),
        TOPIC_PORT,
        input_port(
            "is_voltage", bool, False, "If true voltage will be used to check for low battery."
        ),
    )

    def check(self) -> bool:
        battery = self.battery()
        if battery is None:
            return False
        level = battery.voltage if self.get_input("is_voltage") else battery.percentage
        return bool(level <= self.get_input("min_battery"))


class IsBatteryCharging(_BatteryCondition):
    """``<IsBatteryCharging/>`` (Nav2): SUCCESS while the last battery message says
    CHARGING; FAILURE otherwise and before any message."""

    PORTS = (TOPIC_PORT,)

    def check(self) -> bool:
        battery = self.battery()
        return battery is not None and battery.power_supply_status == PowerSupplyStatus.CHARGING
