"""Example nodes and trees: the mission ``aiobt demo`` runs."""
