"""Dock databases shipped for the bundled worlds (``--dock-database office``)."""
