"""Keep a process running: what ``respawn=True`` does in a ROS 2 launch file, for bare machines too.

    supervise [--delay 1.0] [--log FILE] -- <argv of the process>

(``install/cf_commag/lib/cf_commag/supervise -- install/cf_commag/lib/cf_commag/commag --ros-args ...``).
The ComMAg restores its registry when it starts again, so a ComMAg killed with ``kill -9``
comes back with every registration. ``tools/demo.py`` and ``rcss_team`` supervise their
ComMAg with :class:`Respawner`; the launch files set ``respawn``. SIGINT or SIGTERM to the
supervisor stops the process (the same signal, then SIGKILL after a timeout) and ends it.
"""

from __future__ import annotations

import argparse
import contextlib
import signal
import subprocess
import sys
import time
from pathlib import Path


class Respawner:
    """One process, started again ``delay`` seconds after each exit that nobody asked for."""

    def __init__(self, argv: list[str], *, log: Path | None = None, delay: float = 1.0, new_session: bool = True):
        self.argv = list(argv)
        self.log = log
        self.delay = delay
        self.new_session = new_session
        self.process: subprocess.Popen | None = None
        self.restarts = 0
        self.exits: list[int] = []  # return codes of the exits that were answered with a restart
        self._stopping = False
        self._due: float | None = None

    def start(self) -> subprocess.Popen:
        out = open(self.log, "ab") if self.log else None  # noqa: SIM115 - the child writes it
        try:
            self.process = subprocess.Popen(
                self.argv, stdout=out, stderr=subprocess.STDOUT if out else None, start_new_session=self.new_session
            )
        finally:
            if out:
                out.close()
        return self.process

    @property
    def pid(self) -> int | None:
        return self.process.pid if self.process else None

    def poll(self) -> bool:
        """Call often: True when the process was just started again."""
        if self._stopping or self.process is None or self.process.poll() is None:
            return False
        now = time.monotonic()
        if self._due is None:
            self._due = now + self.delay
            self.exits.append(self.process.returncode)
        if now < self._due:
            return False
        self._due = None
        self.restarts += 1
        self.start()
        return True

    def stop(self, sig: int = signal.SIGINT, timeout: float = 5.0) -> int | None:
        """Stop for good: ``sig``, then SIGKILL after ``timeout``; the exit code."""
        self._stopping = True
        proc = self.process
        if proc is None:
            return None
        if proc.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                proc.send_signal(sig)
            try:
                proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(timeout=timeout)
        return proc.returncode


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_commag supervise -- <argv>``."""
    args = sys.argv[1:] if argv is None else argv
    if "--" not in args:
        print("usage: supervise [--delay S] [--log FILE] -- <argv>", file=sys.stderr)
        return 2
    cut = args.index("--")
    ap = argparse.ArgumentParser(prog="supervise", description="start a process again whenever it exits")
    ap.add_argument("--delay", type=float, default=1.0, help="seconds before a restart")
    ap.add_argument("--log", default="", help="append the process's output here")
    opts = ap.parse_args(args[:cut])
    child = Respawner(args[cut + 1 :], log=Path(opts.log) if opts.log else None, delay=opts.delay, new_session=False)
    stop = {"signal": 0}

    def on_signal(signum, frame):
        stop["signal"] = signum

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    child.start()
    print(f"supervise: started pid {child.pid}", flush=True)
    while not stop["signal"]:
        if child.poll():
            print(f"supervise: exited with {child.exits[-1]}; started again as pid {child.pid}", flush=True)
        time.sleep(0.1)
    child.stop(stop["signal"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
