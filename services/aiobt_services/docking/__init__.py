"""The docking server, as Nav2's ``opennav_docking``: a dock database, dock plugins
(SimpleChargingDock: the dock found by a detection of its marker, with Nav2's pose
filter), the staging pose, the approach with the graceful control law, DockRobot and
UndockRobot with Nav2's error codes (pure logic here; Zenoh only in ``main``,
``service`` and ``navigator``)."""
