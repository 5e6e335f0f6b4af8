"""The robot as the controller and behavior services see it: the newest state per
frame (:mod:`.tracker`), when a pose is stale (:mod:`.freshness`), how late a command
acts (:mod:`.latency`)."""
