"""Saves and restores the registry atomically (write a temp file, fsync, rename). ROS-free."""

from __future__ import annotations

import json
import os
import tempfile
import threading
from pathlib import Path

FORMAT_VERSION = 1


def save(path: Path, entries: list[dict]) -> None:
    """Write the registry so that a crash at any moment leaves the old or the new file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    data = json.dumps({"version": FORMAT_VERSION, "components": entries}, indent=1)
    fd, tmp = tempfile.mkstemp(prefix=path.name, suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            out.write(data)
            out.flush()
            os.fsync(out.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    dir_fd = os.open(path.parent, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def load(path: Path) -> list[dict]:
    """The saved components, or [] if there is no file. Raises ValueError if it is corrupt."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return []
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}: not valid JSON ({exc})") from exc
    if not isinstance(data, dict) or data.get("version") != FORMAT_VERSION:
        raise ValueError(f"{path}: unknown registry format")
    return list(data.get("components", []))


class Saver:
    """Saves in a thread of its own, so a slow disk never holds up the ComMAg's answers.

    :meth:`save` only hands over the latest state; the thread writes the newest one it has (states
    handed over while it writes are merged into one write). :meth:`close` writes what is left
    and waits. Errors go to ``on_error``.
    """

    def __init__(self, path: Path, on_error=None):
        self.path = path
        self._on_error = on_error or (lambda exc: None)
        self._latest: list[dict] | None = None
        self._cond = threading.Condition()
        self._closed = False
        self.writes = 0
        self._thread = threading.Thread(target=self._run, name="registry-saver", daemon=True)
        self._thread.start()

    def save(self, entries: list[dict]) -> None:
        with self._cond:
            self._latest = entries
            self._cond.notify()

    def _run(self) -> None:
        while True:
            with self._cond:
                while self._latest is None and not self._closed:
                    self._cond.wait()
                entries, self._latest = self._latest, None
                if entries is None:
                    return  # closed with nothing left to write
            try:
                save(self.path, entries)
                self.writes += 1
            except OSError as exc:
                self._on_error(exc)

    def close(self, timeout: float = 5.0) -> None:
        """Write what is pending, then stop the thread."""
        with self._cond:
            self._closed = True
            self._cond.notify()
        self._thread.join(timeout)
