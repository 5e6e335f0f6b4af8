"""Nav2's stall detection (``SimpleChargingDock::jointStateCallback``): docked when the
wheels have stopped while their motors still push, read from ``joint_states``.

The mean absolute velocity and effort over ``stall_joint_names`` (a name the message
does not carry counts as 0, and the mean is over all the names, as Nav2's): stalled
when the velocity is under ``stall_velocity_threshold`` and the effort over
``stall_effort_threshold``.
"""

from __future__ import annotations

from collections.abc import Sequence

from aiobt.msgs.joint_state import JointState


def is_stalled(state: JointState | None, names: Sequence[str], velocity_threshold: float,
               effort_threshold: float) -> bool:  # fmt: skip
    if state is None or not names:
        return False
    velocity = sum(abs(state.of("velocity", n) or 0.0) for n in names) / len(names)
    effort = sum(abs(state.of("effort", n) or 0.0) for n in names) / len(names)
    return velocity < velocity_threshold and effort > effort_threshold
