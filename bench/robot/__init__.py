"""Benchmarks of the robot simulation."""
