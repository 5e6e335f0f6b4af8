"""One MCAP recording of the bridged channels, opened and closed in code (no server).

The navigator's ``--mcap-dir`` records each navigation to its own file with it;
``aiobt foxglove --mcap`` records a whole run through :func:`running_bridge`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import foxglove

from aiobt.foxglove.bridge import DEFAULT_COSTMAP_PERIOD, DEFAULT_FOOTPRINT_RADIUS, FoxgloveBridge
from aiobt.transport import Bus


def open_mcap(path: Path, context: foxglove.Context, overwrite: bool = False) -> Any:
    """The SDK's MCAP writer of ``context``'s channels to ``path``; ``OSError`` naming
    the file if it cannot be written."""
    try:
        return foxglove.open_mcap(path, allow_overwrite=overwrite, context=context)
    except (OSError, RuntimeError) as exc:  # the SDK's FoxgloveError is a RuntimeError
        raise OSError(f"{path}: cannot record: {exc}") from None


class McapRecording:
    """Records every channel of a :class:`FoxgloveBridge` on ``bus`` to ``path`` from
    construction until :meth:`close` (idempotent). It only records: no goal is
    forwarded, nothing is announced, and the simulation's truth is not read (the
    navigator records with it: no navigation service subscribes to the truth).
    ``OSError`` naming the file if it cannot be written."""

    def __init__(
        self,
        bus: Bus,
        path: Path,
        footprint_radius: float = DEFAULT_FOOTPRINT_RADIUS,
        costmap_period: float = DEFAULT_COSTMAP_PERIOD,
    ) -> None:
        context = self._context = foxglove.Context()  # its channels close when it goes
        self._writer: foxglove.mcap.MCAPWriter | None = open_mcap(path, context)
        self.path = path
        self._bridge = FoxgloveBridge(
            bus, context, footprint_radius, costmap_period, forwards_goals=False, truth=False
        )
        self._bridge.start()

    def close(self) -> None:
        """Stop recording and finish the file."""
        writer, self._writer = self._writer, None
        if writer is None:
            return
        self._bridge.close()
        writer.close()
