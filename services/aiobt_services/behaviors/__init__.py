"""Recovery behaviors (Nav2's behavior server): spin, back up, drive on heading, wait,
assisted teleop, as pure state machines plus a thin Zenoh service."""

from .assisted_teleop import AssistedTeleop, TeleopParams
from .base import BehaviorInputError, BehaviorStep, Inputs, Outcome, Safety, TimedBehavior
from .drive import DriveOnHeading, back_up
from .spin import SpinBehavior, SpinParams
from .wait import WaitBehavior

__all__ = [
    "AssistedTeleop",
    "BehaviorInputError",
    "BehaviorStep",
    "DriveOnHeading",
    "Inputs",
    "Outcome",
    "Safety",
    "SpinBehavior",
    "SpinParams",
    "TeleopParams",
    "TimedBehavior",
    "WaitBehavior",
    "back_up",
]
