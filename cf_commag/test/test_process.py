"""Telling a running process from a dead one through /proc: real processes, no ROS."""

from __future__ import annotations

import os
import subprocess
import sys
import time

from cf_commag.process import process_identity, running, running_command


def test_this_process_is_running_and_a_killed_one_is_not():
    me = process_identity()
    assert running(me.items()) is True
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    ident = {**me, "pid": str(child.pid)}
    ident.pop("started")
    assert running(ident.items()) is True
    child.kill()
    child.wait()
    assert running(ident.items()) is False


def test_a_reused_pid_or_another_machine_is_not_taken_for_the_process():
    me = process_identity()
    assert running({**me, "started": str(int(me["started"]) + 1)}.items()) is False  # another process, same pid
    assert running({**me, "machine": "another-boot"}.items()) is None  # cannot tell from here
    assert running({"pid": str(os.getpid())}.items()) is None


def started_with_argv(pid: int, timeout: float = 10.0) -> None:
    """Wait until /proc shows the process's argv.

    Popen returns once the child's exec has begun, but the kernel sets the new argv a moment later:
    on a loaded machine /proc/PID/cmdline read at once was still empty (CI, session 54).
    """
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            if f.read():
                return
        time.sleep(0.01)


def test_only_a_process_running_the_launch_command_is_named_for_killing():
    script = "import time; time.sleep(60)"
    child = subprocess.Popen([sys.executable, "-c", script])
    try:
        started_with_argv(child.pid)
        ident = {**process_identity(), "pid": str(child.pid)}
        ident.pop("started")
        assert running_command(ident.items(), (sys.executable, "-c", script)) == child.pid
        assert running_command(ident.items(), (sys.executable, "-c", "something else")) is None
        assert running_command(ident.items(), ()) is None
    finally:
        child.kill()
        child.wait()
