"""A service's start-up objects out of the garbage collector's full passes.

A service process imports its modules, builds its message models and validators
(and, for the robot, its world) before it serves: 60,000 objects and more that
live as long as the process. CPython's full collection walks every tracked object,
so each one took 20-60 ms of the event loop on this project's 2-core machine (the
planner's request behind it took 268 ms; the robot's steps stall and the
simulation catches up in a burst). :func:`settle` freezes what exists once the
service is up (``gc.freeze``): later collections look only at what came after.
"""

from __future__ import annotations

import gc


def settle() -> None:
    """Call once a service is up: its start-up objects are left out of collections."""
    gc.collect()  # what start-up left as garbage goes now, not frozen with the rest
    gc.freeze()
