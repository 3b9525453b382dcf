"""The process around components: init, spin until a signal, deregister cleanly, the executor, own launch command."""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Callable, Iterable

from rclpy._rclpy_pybind11 import InvalidHandle, RCLError
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from .agent import Agent


def spin(
    node: Node,
    agents: Iterable[Agent] = (),
    *,
    executor=None,
    until: Callable[[], bool] | None = None,
    on_exit: Callable[[], None] | None = None,
) -> None:
    """Spin until SIGINT or SIGTERM (or ``until()``), then deregister the agents cleanly and shut down.

    ``on_exit`` runs first on the way out (the node's own clean-up). Call
    ``rclpy.init(signal_handler_options=SignalHandlerOptions.NO)`` first (as :func:`init` does),
    so the context is still alive to deregister.
    """
    import signal

    import rclpy

    def _stop(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, _stop)
    signal.signal(signal.SIGINT, _stop)
    # spin_once in a loop: EventsExecutor.spin() was seen to hang on shutdown.
    spin_once = (
        executor.spin_once
        if executor is not None
        else lambda timeout_sec: rclpy.spin_once(node, timeout_sec=timeout_sec)
    )
    try:
        while rclpy.ok() and not (until is not None and until()):
            try:
                spin_once(timeout_sec=0.1)
            except InvalidHandle as exc:
                # rclpy's race between an entity's destruction and its pending work (an event of a
                # publisher or subscription destroyed meanwhile: ros2/rclpy#1142; the EventsExecutor
                # of Jazzy does not catch it). The entity is gone; the process must go on.
                node.get_logger().warning(f"work of a destroyed entity skipped: {exc}", throttle_duration_sec=5.0)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        if on_exit is not None:
            on_exit()
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
            c = agent.counters
            node.get_logger().info(f"{agent.me.name}: {c['sent']} messages sent, {c['received']} received")
        if executor is not None:
            executor.shutdown()
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


def default_executor(node: Node):
    """The executor every node runs in unless it says otherwise: ``CF_EXECUTOR`` (default ``events``).

    rclpy's SingleThreadedExecutor rebuilds its wait set in Python at every wake-up: an idle node
    with one 10 Hz timer costs 2.5-3x the CPU it costs in the EventsExecutor (bench/bench_idle.py),
    and a component with its subscriptions, clients and timers more (bench/bench_realtime.py).
    """
    executor = make_executor(os.environ.get("CF_EXECUTOR", "events"))
    executor.add_node(node)
    return executor


def init(args: list[str] | None = None) -> None:
    """rclpy.init without rclpy's signal handlers, for use with :func:`spin`."""
    import rclpy
    from rclpy.signals import SignalHandlerOptions

    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)


def own_launch_command() -> list[str]:
    """How to start this very process again: what a component registers as its launch command."""
    return [os.path.realpath(sys.argv[0]), *sys.argv[1:]]


def run(
    make_node: Callable[[], Node],
    *,
    agents: Callable[[Node], Iterable[Agent]] | None = None,
    executor: Callable[[Node], object] | None = None,
    until: Callable[[Node], bool] | None = None,
    on_exit: Callable[[Node], None] | None = None,
    args: list[str] | None = None,
) -> int:
    """The body of every node's ``main()``: init, build the node, spin, deregister, clean up; the exit code.

    ``agents(node)`` are deregistered on the way out (default: ``node.agent`` if it has one);
    ``executor(node)`` gives an executor holding the node (default: :func:`default_executor`);
    ``until(node)`` ends the spin early, with the exit code in ``node.exit_code`` if it has one
    (end a process that way, not by raising SystemExit in a callback: the events executor is
    left unable to serve the deregistrations); ``on_exit(node)`` is the node's own clean-up. Invalid parameters
    (ValueError while the node is built) end the process with code 2 and the reason;
    SystemExit, from the constructor or a callback, with its code.
    """
    import rclpy

    init(args=sys.argv if args is None else args)
    try:
        node = make_node()
    except ValueError as exc:
        print(f"{os.path.basename(sys.argv[0])}: {exc}", file=sys.stderr)
        rclpy.try_shutdown()
        return 2
    except SystemExit as exc:
        rclpy.try_shutdown()
        return int(exc.code or 0)
    held = agents(node) if agents is not None else [a for a in [getattr(node, "agent", None)] if a is not None]
    try:
        spin(
            node,
            held,
            executor=executor(node) if executor is not None else default_executor(node),
            until=(lambda: until(node)) if until is not None else None,
            on_exit=(lambda: on_exit(node)) if on_exit is not None else None,
        )
    except SystemExit as exc:  # a callback decided the process is done (e.g. the match is over)
        return int(exc.code or 0)
    return int(getattr(node, "exit_code", None) or 0)
