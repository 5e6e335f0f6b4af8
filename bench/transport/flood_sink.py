"""The control of bench.transport.flood: a process that subscribes to ``flood_sink``
(latest value only), so that a flood can run on the machine without reaching the
service measured.

Run: ``python -m bench.transport.flood_sink --connect EP --namespace NS``
"""

from __future__ import annotations

import sys

from aiobt.msgs import PoseStamped
from aiobt.testing.bus import service_main

if __name__ == "__main__":
    sys.exit(service_main(lambda bus: bus.subscribe("flood_sink", PoseStamped, queue_size=1)))
