"""Localization: Nav2's AMCL (a particle filter on odometry and lidar) as a service."""
