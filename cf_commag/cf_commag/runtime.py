"""The process around components: init, spin until a signal, deregister cleanly, the executor, own launch command."""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterable

from rclpy._rclpy_pybind11 import RCLError
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from .agent import Agent


def spin(node: Node, agents: Iterable[Agent] = (), *, executor=None) -> None:
    """Spin until SIGINT or SIGTERM, then deregister the agents cleanly and shut down.

    Call ``rclpy.init(signal_handler_options=SignalHandlerOptions.NO)`` first
    (as :func:`init` does), so the context is still alive to deregister.
    """
    import signal

    import rclpy

    def _stop(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, _stop)
    signal.signal(signal.SIGINT, _stop)
    try:
        if executor is None:
            rclpy.spin(node)
        else:
            while rclpy.ok():  # spin_once in a loop: EventsExecutor.spin() was seen to hang on shutdown
                executor.spin_once(timeout_sec=0.1)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        for agent in agents:
            future = agent.close()
            if future is not None:
                with contextlib.suppress(Exception):  # shutting down anyway
                    if executor is None:
                        rclpy.spin_until_future_complete(node, future, timeout_sec=1.0)
                    else:
                        executor.spin_until_future_complete(future, timeout_sec=1.0)
        for agent in agents:
            with contextlib.suppress(RCLError):
                agent.flush(timeout=2.0)
        node.destroy_node()
        rclpy.try_shutdown()


def make_executor(kind: str):
    """The executor a node asked for: ``events`` (faster, experimental in Jazzy) or ``single``."""
    if kind == "events":
        from rclpy.experimental import EventsExecutor

        return EventsExecutor()
    if kind == "single":
        from rclpy.executors import SingleThreadedExecutor

        return SingleThreadedExecutor()
    raise ValueError(f"executor must be 'events' or 'single', not {kind!r}")


def init(args: list[str] | None = None) -> None:
    """rclpy.init without rclpy's signal handlers, for use with :func:`spin`."""
    import rclpy
    from rclpy.signals import SignalHandlerOptions

    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)


def own_launch_command() -> list[str]:
    """How to start this very process again: what a component registers as its launch command."""
    return [os.path.realpath(sys.argv[0]), *sys.argv[1:]]


def run(make_node) -> int:
    """Entry point body of a component: init, build the node (it has ``.agent``), spin, deregister."""
    init(args=sys.argv)
    node = make_node()
    spin(node, [node.agent])
    return 0
