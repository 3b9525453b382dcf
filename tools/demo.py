"""`make demo`: a whole match of the framework at work, headless, with real processes.

Starts the ComMAg, the gateway, the simulator and two teams whose every player
is three components (perception, action, decision), each its own process.
Midway it kill -9s a component (the ComMAg detects it and relaunches it) and
takes away an action provider whose relaunch keeps failing (the ComMAg
withdraws it and the player's requests reroute to its redundant twin). It
prints the match time, score and registry events as they happen, a summary
at the end, and writes an HTML match report.

    python tools/demo.py [--players 3] [--half-cycles 600] [--cycle 0.1] [--out demo-output]

Full 11 v 11 in real time: --players 11 --half-cycles 3000 --cycle 0.1 (66 component processes).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import rclpy
from ament_index_python.packages import get_package_prefix
from rclpy.executors import SingleThreadedExecutor
from std_msgs.msg import String

from cf_commag.respawn import Respawner
from cf_commag.transport.outbox import inbox_topic
from cf_commag.transport.qos import EVENTS_QOS, INBOX_QOS, SNAPSHOT_QOS
from cf_commag.transport.samples import sample_messages
from cf_interfaces.msg import Registry, RegistryEvent
from cf_sim_backend.embedded.report import write_report
from cf_sim_backend.embedded.topics import STATE_QOS

TEAMS = {"l": "blue", "r": "red"}


def exe(package: str, name: str) -> str:
    return str(Path(get_package_prefix(package)) / "lib" / package / name)


class Demo:
    def __init__(self, args: argparse.Namespace):
        self.args = args
        self.out = Path(args.out).resolve()
        self.out.mkdir(parents=True, exist_ok=True)
        (self.out / "logs").mkdir(exist_ok=True)
        self.procs: dict[str, subprocess.Popen] = {}
        self.t0 = time.monotonic()
        self.events: list[dict] = []
        self.counts: Counter[str] = Counter()
        self.messages = 0
        self.requests = 0  # fipa-request openings: the decisions asking their action components
        self.inboxes: dict[str, object] = {}
        self.last_state: dict | None = None

    def say(self, text: str) -> None:
        print(f"[{time.monotonic() - self.t0:6.1f} s] {text}", flush=True)

    def start(self, name: str, argv: list[str]) -> subprocess.Popen:
        log = open(self.out / "logs" / f"{name}.log", "ab")  # noqa: SIM115 - lives as long as the process
        proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.procs[name] = proc
        return proc

    def component(self, role: str, side: str, number: int, *extra: str, name: str = "") -> None:
        team = TEAMS[side]
        params = ["-p", f"side:={side}", "-p", f"number:={number}", "-p", f"team:={team}", "-p", "lease:=2.0"]
        if role == "decision":
            params = [
                "-p",
                f"number:={number}",
                "-p",
                f"team:={team}",
                "-p",
                f"team_size:={self.args.players}",
                "-p",
                "lease:=2.0",
            ]
        if name:
            params += ["-p", f"name:={name}"]
        package = "cf_decision" if role == "decision" else "cf_sim_backend"
        label = name or f"{team}_{number}_{role}"
        self.start(label, [exe(package, role), "--ros-args", "-r", f"__node:={label}", *params, *extra])

    # ---- ROS side -------------------------------------------------------------

    def on_event(self, ev: RegistryEvent) -> None:
        self.counts[ev.kind_name] += 1
        self.events.append(
            {
                "t": time.monotonic() - self.t0,
                "name": ev.record.name,
                "kind": ev.kind_name,
                "state": ev.record.state,
                "reason": ev.reason,
            }
        )
        if ev.kind_name != "renewed":
            self.say(f"ComMAg: {ev.record.name:<22} {ev.kind_name:<13} {ev.reason}")

    def on_registry(self, msg: Registry) -> None:
        for rec in msg.records:  # count every ACL message on every agent's inbox
            if rec.name not in self.inboxes:
                self.inboxes[rec.name] = self.node.create_subscription(
                    String, inbox_topic(rec.name), self._count, INBOX_QOS
                )

    def _count(self, msg: String) -> None:
        texts = sample_messages(msg.data)  # a sample may carry several
        self.messages += len(texts)
        self.requests += sum(t.startswith("(request") for t in texts)

    def on_state(self, msg: String) -> None:
        snap = json.loads(msg.data)
        previous = self.last_state
        self.last_state = snap
        if previous is None or snap["t"] // 100 != previous["t"] // 100 or snap["score"] != previous["score"]:
            self.say(f"match time {snap['t']:5d}  {snap['mode']:<16} blue {snap['score'][0]} : {snap['score'][1]} red")

    def spin(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.05)
            if self.commag.poll():
                self.say(f">>> the ComMAg exited ({self.commag.exits[-1]}): started again, it restores its registry")

    # ---- the show -------------------------------------------------------------

    def run(self) -> int:
        a = self.args
        os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
        os.environ.setdefault("ROS_DOMAIN_ID", str(50 + os.getpid() % 40))
        print(
            f"Common Framework demo: {a.players} v {a.players}, 2 x {a.half_cycles} cycles of {a.cycle * 1000:.0f} ms"
            f" (ROS_DOMAIN_ID={os.environ['ROS_DOMAIN_ID']}); output in {self.out}\n"
        )
        rclpy.init()
        self.node = rclpy.create_node("demo_monitor")
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.node.create_subscription(RegistryEvent, "/commag/events", self.on_event, EVENTS_QOS)
        self.node.create_subscription(Registry, "/commag/registry", self.on_registry, SNAPSHOT_QOS)
        self.node.create_subscription(String, "/cf_sim/state", self.on_state, STATE_QOS)

        # Supervised like launch's respawn=True: a ComMAg that dies comes back with every registration.
        self.commag = Respawner(
            [
                exe("cf_commag", "commag"),
                "--ros-args",
                "-p",
                f"persistence_path:={self.out / 'registry.json'}",
                "-p",
                f"log_dir:={self.out / 'logs' / 'relaunched'}",
                "-p",
                "backoff_initial:=0.3",
                "-p",
                "startup_grace:=15.0",
            ],
            log=self.out / "logs" / "commag.log",
        )
        self.commag.start()
        self.start(
            "gateway",
            [
                exe("cf_commag", "gateway"),
                "--ros-args",
                "-p",
                "port:=0",
                "-p",
                f"port_file:={self.out / 'gateway.port'}",
            ],
        )
        # Start the components one after the other: a burst of Python processes on a small machine
        # would starve the ones already running of the CPU they need to renew their leases.
        for side in ("l", "r"):
            for number in range(1, a.players + 1):
                for role in ("perception", "action", "decision"):
                    extra = ["-p", "relaunch_fails:=true"] if (side, number, role) == ("l", 2, "action") else []
                    self.component(role, side, number, *extra)
                    self.spin(a.stagger)
        # Blue 2 has a redundant action provider.
        self.component("action", "l", 2, name="blue_2_action_twin")
        expected = len(self.procs) - 2
        self.say(f"started {expected} components; waiting until each has registered ...")
        deadline = time.monotonic() + 120
        while self.counts["registered"] < expected and time.monotonic() < deadline:
            self.spin(0.2)
        self.say(f"{self.counts['registered']} components registered; starting the simulator")
        self.start(
            "sim",
            [
                exe("cf_sim_backend", "sim"),
                "--ros-args",
                "-p",
                f"left_size:={a.players}",
                "-p",
                f"right_size:={a.players}",
                "-p",
                f"half_cycles:={a.half_cycles}",
                "-p",
                f"cycle_period:={a.cycle}",
                "-p",
                "auto_kick_off_cycles:=30",
                "-p",
                f"match_log:={self.out / 'match.jsonl'}",
                "-p",
                f"seed:={a.seed}",
            ],
        )

        kill_one_at = a.half_cycles // 2
        fail_one_at = a.half_cycles + a.half_cycles // 3
        killed = failed = False
        while True:
            self.spin(0.2)
            snap = self.last_state
            if snap is None:
                continue
            if not killed and snap["t"] >= kill_one_at:
                killed = True
                self.say(">>> kill -9 red_2_perception: the ComMAg should detect it and relaunch it")
                os.killpg(self.procs["red_2_perception"].pid, signal.SIGKILL)
            if not failed and snap["t"] >= fail_one_at:
                failed = True
                self.say(">>> kill -9 blue_2_action (its relaunch always fails): withdrawal, then its twin takes over")
                os.killpg(self.procs["blue_2_action"].pid, signal.SIGKILL)
            if (self.out / "match.jsonl").exists() and snap["mode"] == "time_over":
                self.spin(1.0)
                break
        return self.finish()

    def finish(self) -> int:
        lines = (self.out / "match.jsonl").read_text().splitlines()
        end = json.loads(lines[-1]) if lines and '"end"' in lines[-1] else {}
        (self.out / "registry-events.json").write_text(json.dumps(self.events, indent=1))
        report = write_report(self.out / "match.jsonl", self.events, self.out / "report.html")
        stats = end.get("stats", {})
        poss = stats.get("possession", {"l": 0, "r": 0})
        total = max(1, poss.get("l", 0) + poss.get("r", 0))
        print("\n==================== summary ====================")
        print(f"score        blue {end.get('score', ['?', '?'])[0]} : {end.get('score', ['?', '?'])[1]} red")
        print(f"shots        blue {stats.get('shots', {}).get('l')}  red {stats.get('shots', {}).get('r')}")
        print(f"possession   blue {poss.get('l', 0) / total:.0%}  red {poss.get('r', 0) / total:.0%}")
        print(f"relaunches   {self.counts['relaunched']}  (launch attempts {self.counts['relaunching']})")
        print(f"withdrawals  {self.counts['withdrawn']}")
        print(f"ACL messages exchanged  {self.messages}")
        played = max(1, (self.last_state or {}).get("t", 0) * 2 * self.args.players)
        print(f"action requests  {self.requests}  ({self.requests / played:.2f} per player-cycle)")
        print(f"report       {report}")
        print(f"match log    {self.out / 'match.jsonl'}  (format: docs/simulator.md)")
        print("=================================================")
        self.stop()
        return 0 if end and self.counts["relaunched"] >= 1 and self.counts["withdrawn"] >= 1 else 1

    def stop(self) -> None:
        self.commag.stop()  # first: it must not relaunch what is being torn down
        self.executor.shutdown()
        self.node.destroy_node()
        rclpy.try_shutdown()
        for proc in self.procs.values():
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGTERM)
        time.sleep(1.5)
        for name in self.procs:  # relaunched components are the ComMAg's children, not ours
            subprocess.run(["pkill", "-9", "-f", f"__node:={name}( |$)"], check=False)
        for proc in self.procs.values():
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--players", type=int, default=3)
    parser.add_argument("--half-cycles", type=int, default=600)
    parser.add_argument("--cycle", type=float, default=0.1, help="seconds per cycle (0.1 = real time)")
    parser.add_argument("--stagger", type=float, default=0.6, help="seconds between component starts")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", default="demo-output")
    return Demo(parser.parse_args()).run()


if __name__ == "__main__":
    sys.exit(main())
