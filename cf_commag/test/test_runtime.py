"""The process loop around a component: pending work of a destroyed entity must not end it."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent(
    """
    import faulthandler
    import sys
    import rclpy
    from rclpy._rclpy_pybind11 import InvalidHandle
    from cf_commag.runtime import init, make_executor, spin

    # A hang (seen once in CI, never reproduced) dumps every thread's stack and ends the probe,
    # so the failure says where it hung.
    faulthandler.dump_traceback_later(45, exit=True)
    init()
    node = rclpy.create_node("runtime_probe")
    executor = make_executor(sys.argv[1])
    executor.add_node(node)
    calls = []

    def tick():
        calls.append(1)
        if len(calls) == 1:  # what rclpy raises for an event of a publisher destroyed meanwhile
            raise InvalidHandle("cannot use Destroyable because destruction was requested")

    node.create_timer(0.01, tick)
    spin(node, executor=executor, until=lambda: len(calls) >= 3)
    print("ticks", len(calls), flush=True)
    """
)


@pytest.mark.parametrize("kind", ["events", "single"])
def test_work_of_a_destroyed_entity_is_skipped_and_the_process_goes_on(kind):
    done = subprocess.run([sys.executable, "-c", SCRIPT, kind], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, f"exit {done.returncode}\nstdout:\n{done.stdout}\nstderr:\n{done.stderr}"
    assert "ticks 3" in done.stdout
    assert "work of a destroyed entity skipped" in done.stderr
