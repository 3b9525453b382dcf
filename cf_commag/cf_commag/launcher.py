"""Starts components from their registered launch commands, safely. ROS-free.

Whoever can register a launch command could make the ComMAg run a program,
so the launcher runs a command only if its executable is allowed by the
ComMAg's own configuration:

- ``allowed_roots``: directories; an executable inside one (after resolving
  symlinks) is allowed. The default is this workspace's install space.
- ``allowed_commands``: exact executables (absolute paths) also allowed.

Commands run as argv lists, never through a shell, with stdin closed and
output appended to ``<log_dir>/<component>.log``. Each child gets its own
session (so a ComMAg crash does not take components down with it) and is
reaped by :meth:`Launcher.poll` (no zombies). Allowing an interpreter such as
``python3`` allows any code: do not.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from .registry import LaunchError


@dataclass(frozen=True)
class LaunchPolicy:
    allowed_roots: tuple[str, ...] = ()
    allowed_commands: tuple[str, ...] = ()

    def resolve(self, argv: tuple[str, ...]) -> tuple[str | None, str | None]:
        """The real path of argv[0] if allowed, else None and the reason."""
        if not argv:
            return None, "empty launch command"
        exe = argv[0]
        found = exe if os.sep in exe else shutil.which(exe)
        if not found or not os.path.isfile(found) or not os.access(found, os.X_OK):
            return None, f"{exe!r} is not an executable file"
        real = os.path.realpath(found)
        allowed_exact = {os.path.realpath(c) for c in self.allowed_commands}
        if real in allowed_exact:
            return real, None
        for root in self.allowed_roots:
            root_real = os.path.realpath(root)
            if os.path.commonpath([real, root_real]) == root_real:
                return real, None
        return None, f"{exe!r} ({real}) is not in the ComMAg's allowlist"

    def check(self, argv: tuple[str, ...]) -> str | None:
        """None if the command may run, else why not."""
        return self.resolve(argv)[1]


@dataclass
class _Child:
    proc: subprocess.Popen
    log: Path


@dataclass
class Launcher:
    policy: LaunchPolicy
    log_dir: Path
    env: dict[str, str] | None = None
    _children: dict[str, _Child] = field(default_factory=dict)
    _dying: list[subprocess.Popen] = field(default_factory=list)  # killed, not reaped yet

    def launch(self, name: str, argv: tuple[str, ...]) -> int:
        """Start ``argv`` for component ``name``; return its pid or raise LaunchError."""
        real, reason = self.policy.resolve(tuple(argv))
        if real is None:
            raise LaunchError(reason)
        self.kill(name)  # a hung previous instance must not linger beside the new one
        self.log_dir.mkdir(parents=True, exist_ok=True)
        log_path = self.log_dir / f"{name}.log"
        try:
            with open(log_path, "ab") as log:
                proc = subprocess.Popen(
                    [real, *argv[1:]],
                    stdin=subprocess.DEVNULL,
                    stdout=log,
                    stderr=subprocess.STDOUT,
                    start_new_session=True,
                    close_fds=True,
                    env=self.env,
                )
        except OSError as exc:
            raise LaunchError(f"could not start {argv[0]!r}: {exc}") from exc
        self._children[name] = _Child(proc, log_path)
        return proc.pid

    def poll(self) -> list[tuple[str, int]]:
        """Reap children that exited; return (component name, return code) for each."""
        self._dying = [proc for proc in self._dying if proc.poll() is None]
        exited = []
        for name, child in list(self._children.items()):
            code = child.proc.poll()
            if code is not None:
                del self._children[name]
                exited.append((name, code))
        return exited

    def pid(self, name: str) -> int | None:
        child = self._children.get(name)
        return child.proc.pid if child else None

    def kill(self, name: str) -> None:
        """Kill a child we started (its whole process group) and reap it."""
        child = self._children.pop(name, None)
        if child is None or child.proc.poll() is not None:
            return
        with contextlib.suppress(ProcessLookupError):
            os.killpg(child.proc.pid, signal.SIGKILL)
        # Reaped by poll(), not waited for here: the ComMAg must not stall while the kernel tears it down.
        self._dying.append(child.proc)

    def stop_all(self) -> None:
        for name in list(self._children):
            self.kill(name)
        for proc in self._dying:
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=5)
        self._dying = []


def workspace_roots(module: str = __file__) -> tuple[str, ...]:
    """The install space this package runs from: where the workspace's executables live.

    With colcon's isolated layout (``install/<pkg>/``) that is ``install/``;
    with a merged or system install, the prefix itself. The path is looked at as
    imported first: ``colcon build --symlink-install`` links the module to the
    source tree, which has no install space above it.
    """
    for here in (Path(os.path.abspath(module)), Path(module).resolve()):
        for parent in here.parents:
            if parent.name == "cf_commag" and (parent / "share" / "cf_commag").is_dir():
                return (str(parent.parent),)
            if (parent / "share" / "cf_commag" / "package.xml").is_file():
                return (str(parent),)
    return ()
