"""The localization service's own reply models (the rest are in ``aiobt.msgs``)."""

from __future__ import annotations

from aiobt.msgs import Msg


class LocalizationStats(Msg):
    """``srv/localization/stats``: what the filter did since it started."""

    scans: int = 0  # scans received and read
    dropped: int = 0  # scans dropped unread because the filter was still busy
    skipped_no_odom: int = 0  # scans without odometry at their stamp
    updates: int = 0  # filter updates (motion + weighing [+ resampling])
    update_ms_p50: float = 0.0  # CPU time of one update, ms
    update_ms_p99: float = 0.0
    update_ms_max: float = 0.0
    latency_ms_p50: float = 0.0  # wall time from reading a scan to its outputs sent, ms
    latency_ms_p99: float = 0.0
    particles: int = 0
