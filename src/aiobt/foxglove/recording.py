"""One MCAP recording of the bridged channels, opened and closed in code (no server).

The navigator's ``--mcap-dir`` records each navigation to its own file with it;
``aiobt foxglove --mcap`` records a whole run through :func:`running_bridge`.
"""

from __future__ import annotations

from pathlib import Path

import foxglove

from aiobt.foxglove.bridge import DEFAULT_COSTMAP_PERIOD, DEFAULT_FOOTPRINT_RADIUS, FoxgloveBridge
from aiobt.transport import Bus


class McapRecording:
    """Records every channel of a :class:`FoxgloveBridge` on ``bus`` to ``path`` from
    construction until :meth:`close` (idempotent). It only records: no goal is
    forwarded, nothing is announced. ``OSError`` naming the file if it cannot be written."""

    def __init__(
        self,
        bus: Bus,
        path: Path,
        footprint_radius: float = DEFAULT_FOOTPRINT_RADIUS,
        costmap_period: float = DEFAULT_COSTMAP_PERIOD,
    ) -> None:
        context = self._context = foxglove.Context()  # its channels close when it goes
        try:
            self._writer: foxglove.mcap.MCAPWriter | None = foxglove.open_mcap(
                path, allow_overwrite=False, context=context
            )
        except (OSError, RuntimeError) as exc:  # the SDK's FoxgloveError is a RuntimeError
            raise OSError(f"{path}: cannot record: {exc}") from None
        self.path = path
        self._bridge = FoxgloveBridge(
            bus, context, footprint_radius, costmap_period, forwards_goals=False
        )
        self._bridge.start()

    def close(self) -> None:
        """Stop recording and finish the file."""
        writer, self._writer = self._writer, None
        if writer is None:
            return
        self._bridge.close()
        writer.close()
