"""Fixtures for in-process ROS tests (they live in cf_commag.testing)."""

from cf_commag.testing import ros, unique

__all__ = ["ros", "unique"]
