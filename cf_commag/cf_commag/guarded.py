"""Every callback of a node catches at its boundary: an error is logged and answered, never fatal.

rclpy's executor re-raises what a callback raises, which ends ``spin`` and so the process:
one bad request must not take the ComMAg (or any component) down. ``GuardedNode`` wraps
the callback of every service, timer, subscription and guard condition a node creates;
a service that fails answers with its failure fields (``ok``/``accepted`` false, ``reason``).
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable

from rclpy.executors import ExternalShutdownException

# Failure fields of our services' responses, set when a callback fails.
_FAILED = (("ok", False), ("accepted", False), ("success", False))


class _Calls(threading.local):
    depth = 0  # guarded callbacks running on this thread (they may nest: a future's callback)
    when_idle: list[Callable[[], None]]

    def __init__(self):
        self.when_idle = []


_calls = _Calls()


def in_callback() -> bool:
    """Whether a guarded callback is running on this thread."""
    return _calls.depth > 0


def call_when_idle(fn: Callable[[], None]) -> None:
    """Run ``fn`` on this thread once the outermost guarded callback running on it has returned.

    How agents of one process hand messages to each other (host.py): after the sender's
    callback, never inside it.
    """
    _calls.when_idle.append(fn)


def guard(callback: Callable, logger, what: str, on_error: Callable | None = None) -> Callable:
    """``callback`` that logs (throttled) what it raises and returns ``on_error(*args, exc)`` instead."""

    @functools.wraps(callback)
    def guarded(*args):
        calls = _calls
        calls.depth += 1
        try:
            return callback(*args)
        except ExternalShutdownException:
            raise
        except Exception as exc:
            logger.error(f"{what} failed: {exc!r}", throttle_duration_sec=5.0)
            return on_error(*args, exc) if on_error is not None else None
        finally:
            calls.depth -= 1
            if calls.depth == 0 and calls.when_idle:
                _run_when_idle(calls, logger)

    return guarded


def _run_when_idle(calls: _Calls, logger) -> None:
    while calls.when_idle:
        fn = calls.when_idle.pop(0)
        try:
            fn()
        except Exception as exc:  # each runs guarded itself; this is the last line of defence
            logger.error(f"after a callback: {exc!r}", throttle_duration_sec=5.0)


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
