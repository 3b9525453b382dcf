"""Wake the executor from another thread: a guard condition that every rclpy executor serves.

rclpy's EventsExecutor (the default here, see runtime.py) does not serve guard conditions. A
cancelled timer that another thread resets does the same: it fires at once on the executor's
thread, once per ring or for several rings together.

    bell = Doorbell(node, drain)     # drain() runs on the executor
    bell.ring()                      # from any thread
"""

from __future__ import annotations

from collections.abc import Callable

from rclpy.node import Node


class Doorbell:
    def __init__(self, node: Node, callback: Callable[[], None]):
        self._callback = callback
        self._timer = node.create_timer(1e-6, self._on_ring)
        self._timer.cancel()

    def ring(self) -> None:
        """Have the callback run soon on the executor's thread (thread-safe)."""
        self._timer.reset()

    def _on_ring(self) -> None:
        # Cancel before the callback: a ring that comes while it runs sets the timer going again.
        self._timer.cancel()
        self._callback()
