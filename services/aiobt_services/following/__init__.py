"""The following server, as Nav2's ``nav2_following`` (``opennav_following``): follow a
detected object's pose stream at a desired distance, search when it is lost (pure
logic here; Zenoh only in ``main`` and ``service``)."""
