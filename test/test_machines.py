"""Components on several machines: relaunched on their own machine by its launch agent.

1. Machines named by ``CF_MACHINE`` on one network: a component of machine B killed with kill -9
   is relaunched on B by B's launch agent (its new process is the agent's child, and says B);
   one of a machine without a launch agent cannot be relaunched and is withdrawn.
2. Two "hosts" as network namespaces joined by a virtual ethernet pair (10.77.0.0/24, made and
   removed by the test; needs root and iproute2, else skipped saying so): the ComMAg and one team
   on host A, the launch agent, the simulator and the other team on host B. They play a match over
   the veth; the team process on B is killed mid-match and relaunched on B; the match ends normally.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import subprocess
import time
import uuid

import pytest

from cf_system import executable, last_match_record, match_ended, match_lines, players_argv, start_commag


def start_on(procs, machine: str, argv: list[str], log_name: str):
    """A process that says it runs on ``machine`` (what CF_MACHINE tells every agent in it)."""
    log = open(procs.log_dir / f"{log_name}.log", "ab")  # noqa: SIM115 - closed with the process
    env = {**os.environ, "CF_MACHINE": machine}
    proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True, env=env)
    proc.log_file = log
    procs.procs.append(proc)
    return proc


def parent_of(pid: int) -> int:
    with open(f"/proc/{pid}/stat", "rb") as f:
        return int(f.read().rsplit(b")", 1)[1].split()[1])


def record_meta(probe, name: str) -> dict[str, str]:
    probe.spin_until(lambda: probe.snapshot and any(r.name == name for r in probe.snapshot.records), 30.0)
    record = next(r for r in probe.snapshot.records if r.name == name)
    return {kv.key: kv.value for kv in record.metadata}


def test_a_component_of_another_machine_is_relaunched_there_by_its_launch_agent(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path)
    agent = start_on(
        procs,
        f"b_{tag}",
        [
            executable("cf_commag", "launch_agent"),
            "--ros-args",
            "-p",
            f"commag:=/commag_{tag}",
            "-p",
            f"name:=launcher_b_{tag}",
            "-p",
            f"log_dir:={tmp_path / 'launched-on-b'}",
            "-p",
            "kill_on_exit:=true",
        ],
        "launch_agent",
    )
    probe.wait_kind(f"launcher_b_{tag}", "registered", timeout=60)
    assert probe.lookup("Launcher") == [f"launcher_b_{tag}"]
    demo = [executable("cf_commag", "demo_component"), "--commag", f"/commag_{tag}", "--lease", "0.5"]
    on_b = start_on(procs, f"b_{tag}", [*demo, "--name", f"kick_b_{tag}", "--service-class", "Kick"], "kick_b")
    on_c = start_on(procs, f"c_{tag}", [*demo, "--name", f"kick_c_{tag}", "--service-class", "Kick"], "kick_c")
    probe.wait_kind(f"kick_b_{tag}", "registered", timeout=60)
    probe.wait_kind(f"kick_c_{tag}", "registered", timeout=60)
    assert record_meta(probe, f"kick_b_{tag}")["machine_name"] == f"b_{tag}"

    os.killpg(on_b.pid, signal.SIGKILL)
    os.killpg(on_c.pid, signal.SIGKILL)
    probe.wait_kind(f"kick_b_{tag}", "relaunched", timeout=60)
    probe.spin_until(
        lambda: int(record_meta(probe, f"kick_b_{tag}")["pid"]) != on_b.pid, 30.0, "the relaunched process registered"
    )
    meta = record_meta(probe, f"kick_b_{tag}")
    assert meta["machine_name"] == f"b_{tag}"
    assert parent_of(int(meta["pid"])) == agent.pid  # started by B's launch agent, not by the ComMAg
    assert "started" in procs.log("launch_agent")
    # Machine C has no launch agent: nobody can start it there.
    withdrawn = probe.wait_kind(f"kick_c_{tag}", "withdrawn", timeout=60)
    failures = [e.reason for e in probe.events if e.record.name == f"kick_c_{tag}" and e.kind_name == "launch_failed"]
    assert failures and all(f"no launch agent on machine 'c_{tag}'" in r for r in failures), failures
    assert withdrawn.record.name == f"kick_c_{tag}"


# ---- two hosts as network namespaces ----------------------------------------------------------------


class Netns:
    """Two network namespaces joined by a veth pair: hosts A (10.77.0.1) and B (10.77.0.2)."""

    def __init__(self, tag: str):
        short = uuid.uuid4().hex[:6]
        self.a, self.b = f"cfa{short}", f"cfb{short}"
        self.veth = (f"cfva{short}", f"cfvb{short}")
        self.made: list[str] = []

    def ip(self, *args: str, ns: str | None = None) -> None:
        argv = ["ip", *(["-n", ns] if ns else []), *args]
        done = subprocess.run(argv, capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError(f"{' '.join(argv)}: {done.stderr.strip()}")

    def __enter__(self) -> Netns:
        for ns in (self.a, self.b):
            self.ip("netns", "add", ns)
            self.made.append(ns)
        self.ip("link", "add", self.veth[0], "type", "veth", "peer", "name", self.veth[1])
        for ns, dev, addr in ((self.a, self.veth[0], "10.77.0.1/24"), (self.b, self.veth[1], "10.77.0.2/24")):
            self.ip("link", "set", dev, "netns", ns)
            self.ip("addr", "add", addr, "dev", dev, ns=ns)
            self.ip("link", "set", dev, "up", ns=ns)
            self.ip("link", "set", "lo", "up", ns=ns)
        return self

    def __exit__(self, *exc) -> None:
        for ns in self.made:  # whatever still runs in a namespace (relaunched processes too), then it
            pids = subprocess.run(["ip", "netns", "pids", ns], capture_output=True, text=True).stdout.split()
            for pid in pids:
                with contextlib.suppress(ProcessLookupError, ValueError):
                    os.kill(int(pid), signal.SIGKILL)
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)

    def argv(self, ns: str, argv: list[str]) -> list[str]:
        return ["ip", "netns", "exec", ns, *argv]


def netns_or_skip() -> None:
    why = None
    if os.geteuid() != 0:
        why = "creating network namespaces needs root (CI runs as root)"
    elif shutil.which("ip") is None:
        why = "iproute2's ip is not installed (Debian: iproute2)"
    else:
        probe = subprocess.run(["ip", "netns", "add", f"cfprobe{uuid.uuid4().hex[:6]}"], capture_output=True, text=True)
        if probe.returncode != 0:
            why = f"this machine cannot create network namespaces: {probe.stderr.strip()}"
        else:
            name = probe.args[3]
            subprocess.run(["ip", "netns", "del", name], capture_output=True)
    if why:
        if os.environ.get("CF_REQUIRE_NETNS") == "1":
            pytest.fail(f"network namespaces are required here (CF_REQUIRE_NETNS=1): {why}")
        pytest.skip(why)


def in_ns_namespace(pid: int, ns: str) -> bool:
    """Whether process ``pid`` lives in network namespace ``ns``."""
    return os.stat(f"/proc/{pid}/ns/net").st_ino == os.stat(f"/run/netns/{ns}").st_ino


def test_a_match_across_two_hosts_with_a_process_on_host_b_killed_and_relaunched_on_b(procs, tag, tmp_path):
    netns_or_skip()
    with Netns(tag) as hosts:
        env = {
            **os.environ,
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET",
            "ROS_STATIC_PEERS": "10.77.0.1;10.77.0.2",
        }

        def start(ns: str, machine: str, argv: list[str], log: str):
            out = open(procs.log_dir / f"{log}.log", "ab")  # noqa: SIM115 - closed with the process
            proc = subprocess.Popen(
                hosts.argv(ns, argv),
                stdout=out,
                stderr=subprocess.STDOUT,
                start_new_session=True,
                env={**env, "CF_MACHINE": machine},
            )
            proc.log_file = out
            procs.procs.append(proc)
            return proc

        commag = [executable("cf_commag", "commag"), "--ros-args", "-r", f"__node:=commag_{tag}"]
        commag += ["-p", f"persistence_path:={tmp_path / 'registry.json'}", "-p", f"log_dir:={tmp_path / 'rl'}"]
        commag += ["-p", "startup_grace:=30.0"]
        start(hosts.a, "host_a", commag, "commag")
        agent = [executable("cf_commag", "launch_agent"), "--ros-args", "-p", f"commag:=/commag_{tag}"]
        agent += ["-p", "name:=launcher_host_b", "-p", f"log_dir:={tmp_path / 'launched-on-b'}"]
        start(hosts.b, "host_b", agent, "launch_agent")

        def players(side: str) -> list[str]:
            return players_argv(tag, side, f"players_{side}_{tag}", "team_size:=2", "lease:=2.0")

        start(hosts.a, "host_a", players("l"), "players_l")
        red = start(hosts.b, "host_b", players("r"), "players_r")
        sim = [executable("cf_sim_backend", "sim"), "--ros-args", "-r", f"__node:=sim_{tag}"]
        for param in (
            f"sim:=sim_{tag}",
            f"commag:=/commag_{tag}",
            "left_size:=2",
            "right_size:=2",
            "half_cycles:=400",
            "halves:=1",
            "cycle_period:=0.05",
            "auto_kick_off_cycles:=5",
            f"match_log:={tmp_path / 'match.jsonl'}",
            "exit_at_end:=true",
        ):
            sim += ["-p", param]
        log, registry, commag_log = tmp_path / "match.jsonl", tmp_path / "registry.json", procs.log_dir / "commag.log"

        def wait(predicate, timeout: float, what: str) -> None:
            deadline = time.monotonic() + timeout
            while not predicate():
                assert time.monotonic() < deadline, f"timed out after {timeout} s waiting for {what}"
                time.sleep(0.2)

        def registered() -> dict[str, dict]:
            try:
                records = json.loads(registry.read_text())
            except (OSError, ValueError):
                return {}
            items = records if isinstance(records, list) else records.get("components", [])
            return {r["record"]["name"]: r for r in items}

        everyone = {
            f"{c}_{n}_{role}" for c in ("blue", "red") for n in (1, 2) for role in ("perception", "action", "decision")
        }
        wait(lambda: everyone <= set(registered()), 120, "both teams registered with the ComMAg on host A")
        start(hosts.b, "host_b", sim, "sim")
        wait(lambda: len(match_lines(log)) > 150, 120, "play across the two hosts")

        os.killpg(red.pid, signal.SIGKILL)  # host B's team process: the ComMAg must have it started on B
        wait(lambda: commag_log.read_text().count("red_1_decision: relaunched") >= 1, 120, "the red team relaunched")
        assert "started by launcher_host_b on 'host_b'" in commag_log.read_text()

        def new_pid() -> int:
            record = registered().get("red_1_decision")
            return int(dict(record["record"]["metadata"])["pid"]) if record else red.pid

        # The registry file is written a moment after the event (its store thread): wait for the new record.
        wait(lambda: new_pid() != red.pid, 30, "the relaunched record in the persisted registry")
        assert in_ns_namespace(new_pid(), hosts.b)  # running on host B again
        wait(lambda: match_ended(log), 180, "the end of the match")
        end = last_match_record(log)
        assert end["stats"]["kicks"]["l"] + end["stats"]["kicks"]["r"] > 0
