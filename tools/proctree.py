"""The processes below a process, and the CPU they used (from /proc): what the demo and rcss_match measure;
and a child process run to its end that a SIGTERM or SIGINT to us reaches too."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess

CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def descendants(root: int) -> list[int]:
    """Every process below ``root``."""
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat", "rb") as f:
                    stat = f.read()
            except OSError:
                continue
            ppid = int(stat[stat.rfind(b")") + 2 :].split()[1])
            children.setdefault(ppid, []).append(int(entry))
    found, todo = [], [root]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def cpu_seconds(pids: list[int]) -> dict[int, float]:
    """User + system CPU of each process that still exists."""
    cpu = {}
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat", "rb") as f:
                fields = f.read().rsplit(b")", 1)[1].split()
        except OSError:
            continue
        cpu[pid] = (int(fields[11]) + int(fields[12])) / CLOCK_TICKS
    return cpu


def running(pid: int) -> bool:
    """Whether ``pid`` exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            return f.read().rsplit(b")", 1)[1].split()[0] not in (b"Z", b"X")
    except OSError:
        return False


class CpuMeter:
    """CPU used by a process tree between ``start()`` and now, counting processes that have exited since."""

    def __init__(self, root: int):
        self.root = root
        self.base: dict[int, float] = {}
        self.last: dict[int, float] = {}

    def start(self) -> None:
        self.base = cpu_seconds(descendants(self.root))
        self.last = dict(self.base)

    def sample(self) -> None:
        """Call now and then: a process that exits between samples loses what it used since the last one."""
        self.last.update(cpu_seconds(descendants(self.root)))

    def used(self) -> float:
        return sum(cpu - self.base.get(pid, 0.0) for pid, cpu in self.last.items())


PASSED_ON = (signal.SIGTERM, signal.SIGINT)
TERM_GRACE = 30.0  # s a child has to clean up after its time is over, before SIGKILL


def run_passing_on(argv: list[str], timeout: float | None = None, **popen: object) -> subprocess.CompletedProcess:
    """Run ``argv`` to its end as ``subprocess.run`` does, but a SIGTERM or SIGINT sent to us meanwhile
    is passed on to the child, and we wait for it to clean up before we stop (SystemExit 128 + signal).
    Past ``timeout`` it gets a SIGTERM, then TERM_GRACE seconds, then SIGKILL (TimeoutExpired).

    ``subprocess.run`` kills its child with SIGKILL when interrupted: a series of matches stopped so
    left the child's own children (rcssserver, the opponent's eleven players) running, and they took
    the CPU of whatever ran next.
    """
    child: subprocess.Popen | None = None
    received: list[int] = []

    def pass_on(signum: int, _frame: object) -> None:
        received.append(signum)
        if child is not None:
            with contextlib.suppress(ProcessLookupError):
                child.send_signal(signum)

    before = {s: signal.signal(s, pass_on) for s in PASSED_ON}
    try:
        child = subprocess.Popen(argv, **popen)
        if received:  # (a signal before the child existed)
            child.send_signal(received[0])
        try:
            out, err = child.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            child.terminate()
            try:
                child.communicate(timeout=TERM_GRACE)
            except subprocess.TimeoutExpired:
                child.kill()
                child.communicate()
            raise
    finally:
        for s, handler in before.items():
            signal.signal(s, handler)
    if received:
        raise SystemExit(128 + received[0])
    return subprocess.CompletedProcess(argv, child.returncode, out, err)
