"""Helpers of the system tests: the installed executables, real processes, a probe node on real DDS."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from ament_index_python.packages import get_package_prefix

from cf_commag.testing import Ros
from cf_commag.transport.qos import EVENTS_QOS, SNAPSHOT_QOS
from cf_interfaces.msg import Registry, RegistryEvent
from cf_interfaces.srv import Deregister, Lookup, Register

HELPERS = Path(__file__).parent / "helpers"


def executable(package: str, name: str) -> str:
    """The path colcon installed an executable at (what `ros2 run` runs)."""
    path = Path(get_package_prefix(package)) / "lib" / package / name
    assert path.is_file(), f"{path} is not installed: run colcon build"
    return str(path)


class Processes:
    """Real processes started by a test; all killed at the end, with whatever they launched."""

    def __init__(self, tag: str, log_dir: Path):
        self.tag = tag
        self.log_dir = log_dir
        self.procs: list[subprocess.Popen] = []

    def start(self, argv: list[str], log_name: str) -> subprocess.Popen:
        log = open(self.log_dir / f"{log_name}.log", "ab")  # noqa: SIM115 - closed with the process
        proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        proc.log_file = log
        self.procs.append(proc)
        return proc

    def log(self, log_name: str) -> str:
        path = self.log_dir / f"{log_name}.log"
        return path.read_text(errors="replace") if path.exists() else ""

    def kill_all(self) -> None:
        for proc in self.procs:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait(timeout=10)
            proc.log_file.close()
        # Components the ComMAg relaunched are not our children: find them by the test's tag.
        subprocess.run(["pkill", "-9", "-f", self.tag], check=False)


class Probe(Ros):
    """An in-process node that watches and calls a ComMAg over real DDS."""

    def __init__(self, commag: str, tag: str):
        super().__init__()
        self.node = super().node(f"probe_{tag}")  # tests use probe.node as the node itself
        self.events: list[RegistryEvent] = []
        self.snapshot: Registry | None = None
        self.node.create_subscription(RegistryEvent, f"{commag}/events", self.events.append, EVENTS_QOS)
        self.node.create_subscription(Registry, f"{commag}/registry", self._on_snapshot, SNAPSHOT_QOS)
        self.register = self.node.create_client(Register, f"{commag}/register")
        self.deregister = self.node.create_client(Deregister, f"{commag}/deregister")
        self.lookup_client = self.node.create_client(Lookup, f"{commag}/lookup")

    def _on_snapshot(self, msg: Registry) -> None:
        self.snapshot = msg

    def call(self, client, request, timeout: float = 30.0, attempt: float = 2.0):
        """Call a service; ask again if unanswered (a restarted server may miss the first request)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            self.spin_until(client.service_is_ready, timeout, f"service {client.srv_name}")
            future = client.call_async(request)
            try:
                self.spin_until(future.done, attempt, f"answer from {client.srv_name}")
                return future.result()
            except AssertionError:
                client.remove_pending_request(future)
        raise AssertionError(f"no answer from {client.srv_name} within {timeout} s")

    def lookup(self, service_class: str, **fields) -> list[str]:
        res = self.call(self.lookup_client, Lookup.Request(service_class=service_class, **fields))
        assert res.ok, res.reason
        return [p.name for p in res.providers]

    def kinds(self, name: str) -> list[str]:
        return [e.kind_name for e in self.events if e.record.name == name]

    def wait_kind(self, name: str, kind: str, count: int = 1, timeout: float = 30.0) -> RegistryEvent:
        self.spin_until(lambda: self.kinds(name).count(kind) >= count, timeout, f"{count} x {kind} of {name}")
        return [e for e in self.events if e.record.name == name and e.kind_name == kind][count - 1]


def match_lines(log: Path) -> list[str]:
    """The match log's complete lines: the simulator may be mid-line when a test reads it."""
    if not log.exists():
        return []
    return log.read_text().split("\n")[:-1]


def last_match_record(log: Path) -> dict:
    """The last complete record of a match log (the end record once the match is over)."""
    return json.loads(match_lines(log)[-1])


def match_ended(log: Path) -> bool:
    lines = match_lines(log)
    return bool(lines) and '"end"' in lines[-1]


def start_commag(procs: Processes, tag: str, tmp_path: Path, *params: str, log_name: str = "commag"):
    """Start the installed ComMAg under the name commag_<tag>; return its process."""
    argv = [
        executable("cf_commag", "commag"),
        "--ros-args",
        "-r",
        f"__node:=commag_{tag}",
        "-p",
        f"persistence_path:={tmp_path / 'registry.json'}",
        "-p",
        f"log_dir:={tmp_path / 'component-logs'}",
        *[x for p in params for x in ("-p", p)],
    ]
    return procs.start(argv, log_name)


def start_gateway(procs: Processes, tag: str, port_file: Path, *params: str) -> subprocess.Popen:
    """Start the installed gateway for the ComMAg commag_<tag> on a free port, written to port_file."""
    argv = [
        executable("cf_commag", "gateway"),
        "--ros-args",
        "-r",
        f"__node:=gateway_{tag}",
        "-p",
        "port:=0",
        "-p",
        f"port_file:={port_file}",
        "-p",
        f"commag:=/commag_{tag}",
        *[x for p in params for x in ("-p", p)],
    ]
    return procs.start(argv, "gateway")


def players_argv(tag: str, side: str, name: str, *params: str) -> list[str]:
    """The players container for side ``side`` of the simulation sim_<tag>, as host ``name``."""
    argv = [executable("cf_sim_backend", "players"), "--ros-args", "-r", f"__node:={name}"]
    for param in (f"commag:=/commag_{tag}", f"sim:=sim_{tag}", f"side:={side}", f"name:={name}", *params):
        argv += ["-p", param]
    return argv


def start_component(procs: Processes, tag: str, name: str, *args: str) -> subprocess.Popen:
    argv = [executable("cf_commag", "demo_component"), "--name", name, "--commag", f"/commag_{tag}", *args]
    return procs.start(argv, name)


def python_helper(procs: Processes, script: str, *args: str, log_name: str) -> subprocess.Popen:
    return procs.start([sys.executable, str(HELPERS / script), *args], log_name)
