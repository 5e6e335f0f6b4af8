"""When a physics step may be left out: nothing in the world can move.

The robot's body is kinematic (its velocity set before each step, its pose read and
laid flat after it), gravity is off, and walls, obstacles and the dock are static
bodies. A step with the robot's velocity zero, no obstacle moving and nothing touching
the robot leaves pybullet as it was: the pose after it is the pose before, bit for bit
(a step that did so is what settles the gate). :class:`RestGate` says when that holds,
so the simulation leaves the pybullet calls out of a robot standing still (at 1x a
hundred steps a second); the rest of each step (time, odometry and its noise, wheels,
battery, the dock's contacts) runs as before.
"""

from __future__ import annotations


class RestGate:
    """Settled once a physics step at zero velocity moved nothing and touched nothing;
    unsettled by any motion, command or change to the world (:meth:`disturb`)."""

    __slots__ = ("enabled", "settled")

    def __init__(self, enabled: bool = True) -> None:
        self.enabled = enabled  # False: step the physics always (the tests compare the two)
        self.settled = False

    def holds(self, linear: float, angular: float) -> bool:
        """Whether the next step, at this velocity, may be left out of the physics."""
        return self.enabled and self.settled and linear == 0.0 and angular == 0.0

    def stepped(self, still: bool) -> None:
        """A physics step ran: ``still`` if at zero velocity it moved and touched nothing."""
        self.settled = still

    def disturb(self) -> None:
        """The world changed outside a step (a teleport, an obstacle spawned, moved or
        removed): the next step runs the physics."""
        self.settled = False
