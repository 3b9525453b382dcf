"""Every callback of a node catches at its boundary: an error is logged and answered, never fatal.

rclpy's executor re-raises what a callback raises, which ends ``spin`` and so the process:
one bad request must not take the ComMAg (or any component) down. ``GuardedNode`` wraps
the callback of every service, timer, subscription and guard condition a node creates;
a service that fails answers with its failure fields (``ok``/``accepted`` false, ``reason``).
"""

from __future__ import annotations

import functools
from collections.abc import Callable

from rclpy.executors import ExternalShutdownException

# Failure fields of our services' responses, set when a callback fails.
_FAILED = (("ok", False), ("accepted", False), ("success", False))


def guard(callback: Callable, logger, what: str, on_error: Callable | None = None) -> Callable:
    """``callback`` that logs (throttled) what it raises and returns ``on_error(*args, exc)`` instead."""

    @functools.wraps(callback)
    def guarded(*args):
        try:
            return callback(*args)
        except ExternalShutdownException:
            raise
        except Exception as exc:
            logger.error(f"{what} failed: {exc!r}", throttle_duration_sec=5.0)
            return on_error(*args, exc) if on_error is not None else None

    return guarded


def failed_response(request, response, exc: Exception):
    """The response of a service callback that raised: its failure fields say why."""
    for field, value in _FAILED:
        if hasattr(response, field):
            setattr(response, field, value)
    if hasattr(response, "reason"):
        response.reason = f"internal error: {type(exc).__name__}: {exc}"[:500]
    return response


class GuardedNode:
    """Mixin before rclpy's Node or LifecycleNode: every callback the node creates is guarded."""

    def create_service(self, srv_type, srv_name, callback, **kwargs):
        wrapped = guard(callback, self.get_logger(), f"service {srv_name}", failed_response)
        return super().create_service(srv_type, srv_name, wrapped, **kwargs)

    def create_subscription(self, msg_type, topic, callback, qos_profile, **kwargs):
        wrapped = guard(callback, self.get_logger(), f"subscription to {topic}")
        return super().create_subscription(msg_type, topic, wrapped, qos_profile, **kwargs)

    def create_timer(self, timer_period_sec, callback, *args, **kwargs):
        if callback is not None:
            callback = guard(callback, self.get_logger(), getattr(callback, "__qualname__", "timer"))
        return super().create_timer(timer_period_sec, callback, *args, **kwargs)

    def create_guard_condition(self, callback, *args, **kwargs):
        callback = guard(callback, self.get_logger(), getattr(callback, "__qualname__", "guard condition"))
        return super().create_guard_condition(callback, *args, **kwargs)
