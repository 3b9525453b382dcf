"""Which process an agent runs in, and whether it still runs: what tells a starved component from a dead one. ROS-free.

Every agent's record carries metadata naming its process (``pid``, ``started``: its start time
in clock ticks after boot, ``machine``: the kernel's boot id). The ComMAg, on the same machine,
reads ``/proc`` to see whether that process still runs: a component that misses its lease
while its process runs is starved or hung, not dead, and is given time before it is relaunched.
Elsewhere (another machine, another pid namespace) it cannot tell, and goes by the lease alone.

Each record also names its machine (``machine_name``: ``$CF_MACHINE``, else the host name). A
component of another machine is relaunched there, by that machine's launch agent
(launch_agent.py), since a ComMAg can start processes only on its own.
"""

from __future__ import annotations

import os
import socket
from collections.abc import Iterable

HOST_KEY = "host"  # the host process's name: agents of one host are relaunched together
PID_KEY = "pid"
STARTED_KEY = "started"
MACHINE_KEY = "machine"
MACHINE_NAME_KEY = "machine_name"


def machine_name() -> str:
    """The name of the machine this process runs on: ``$CF_MACHINE``, else the host name."""
    return os.environ.get("CF_MACHINE") or socket.gethostname()


def machine_of(metadata: Iterable[tuple[str, str]]) -> str:
    """The machine a record's metadata names ("" if none: taken to be the ComMAg's own)."""
    return dict(metadata).get(MACHINE_NAME_KEY, "")


def on_this_machine(metadata: Iterable[tuple[str, str]]) -> bool:
    """Whether the record's process runs on this machine (a record that names none is taken to)."""
    name = machine_of(metadata)
    return not name or name == machine_name()


def machine_id() -> str:
    """The kernel's boot id: a pid names a process only on the machine (and boot) it ran on."""
    try:
        with open("/proc/sys/kernel/random/boot_id") as f:
            return f.read().strip()
    except OSError:
        return ""


def process_start(pid: int) -> int | None:
    """When process ``pid`` started (clock ticks after boot); None if it does not run (or is a zombie)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            stat = f.read()
    except OSError:
        return None
    fields = stat[stat.rfind(b")") + 2 :].split()  # after the command name, which may hold spaces
    if fields[0] in (b"Z", b"X"):
        return None
    return int(fields[19])


def process_identity() -> dict[str, str]:
    """Metadata naming this process."""
    pid = os.getpid()
    ident = {PID_KEY: str(pid), MACHINE_NAME_KEY: machine_name()}
    started = process_start(pid)
    if started is not None:
        ident[STARTED_KEY] = str(started)
    machine = machine_id()
    if machine:
        ident[MACHINE_KEY] = machine
    return ident


def running(metadata: Iterable[tuple[str, str]]) -> bool | None:
    """Whether the process the metadata names still runs: True, False, or None (cannot tell from here)."""
    meta = dict(metadata)
    pid, machine = meta.get(PID_KEY, ""), meta.get(MACHINE_KEY, "")
    if not pid.isdigit() or not machine or machine != machine_id() or not on_this_machine(meta.items()):
        return None
    started = process_start(int(pid))
    if started is None:
        return False
    return STARTED_KEY not in meta or meta[STARTED_KEY] == str(started)  # else the pid was reused


def running_command(metadata: Iterable[tuple[str, str]], launch_command: tuple[str, ...]) -> int | None:
    """The pid of the process the metadata names if it runs ``launch_command``, else None.

    What the ComMAg may kill before it relaunches a hung component: only a process that runs
    exactly the command it was going to start in its place (an allowed one).
    """
    if not launch_command or running(metadata) is not True:
        return None
    pid = int(dict(metadata)[PID_KEY])
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            argv = [a.decode(errors="replace") for a in f.read().split(b"\0")[:-1]]
    except OSError:
        return None
    n = len(launch_command)
    tail = argv[-n:] if len(argv) >= n else []
    if len(argv) > n + 1 or not tail:  # the command itself, or an interpreter running it
        return None
    if tail[1:] != list(launch_command[1:]) or os.path.realpath(tail[0]) != os.path.realpath(launch_command[0]):
        return None
    return pid
