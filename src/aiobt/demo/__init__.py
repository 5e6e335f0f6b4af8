"""``aiobt demo``: the real system at a speed-up, a patrol through the navigator, a picture."""
