"""`make demo`: a whole match of the framework at work, headless, with real processes.

Starts the ComMAg, the gateway, the simulator and two teams of 11 whose every player is three
components (perception, action, decision), each its own agent. By default each team's
components share one process (``--layout team``: a component container, see docs/hosting.md);
``--layout player`` gives each player a process, ``--layout process`` each component (66).
Midway it kill -9s the red team's process (the ComMAg relaunches it once and all its agents
come back; with ``--layout process``, one component) and takes away an action provider whose
relaunch keeps failing (the ComMAg withdraws it and the player's requests reroute to its
redundant twin). It prints the match time, score and registry events as they happen, a summary
at the end (with the CPU each player cost per cycle and the wall time of every 100 cycles),
writes an HTML match report with an animated replay, the match as an rcssserver game log (.rcg),
and leaves no process behind.

    python tools/demo.py [--players 11] [--half-cycles 600] [--layout team] [--cycle 0.1] [--out demo-output]

Full length: --half-cycles 3000.
"""

from __future__ import annotations

import argparse
import contextlib
import ctypes
import json
import os
import re
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import rclpy
from ament_index_python.packages import get_package_prefix
from proctree import cpu_seconds, descendants, running
from rclpy.executors import SingleThreadedExecutor
from std_msgs.msg import String

from cf_commag.respawn import Respawner
from cf_commag.transport.qos import EVENTS_QOS
from cf_interfaces.msg import RegistryEvent
from cf_sim_backend.embedded.rcg import export as export_rcg
from cf_sim_backend.embedded.report import write_report
from cf_sim_backend.embedded.topics import STATE_QOS

TEAMS = {"l": "blue", "r": "red"}
PR_SET_CHILD_SUBREAPER = 36


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
        self.launches = 0  # processes the ComMAg started (a host's agents share one)
        self.last_state: dict | None = None
        self.hundreds: list[tuple[int, float]] = []  # (match time, wall time) at every 100 cycles
        self.cpu_marks: list[tuple[int, float, dict[int, float]]] = []  # (match time, wall, CPU by pid)

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
                "cycle": (self.last_state or {}).get("t", 0),  # on the match clock, for the replay
                "name": ev.record.name,
                "kind": ev.kind_name,
                "state": ev.record.state,
                "reason": ev.reason,
            }
        )
        if ev.kind_name == "relaunching" and "with its host" not in ev.reason:
            self.launches += 1
        if ev.kind_name != "renewed" and not (self.quiet_registrations and ev.kind_name == "registered"):
            self.say(f"ComMAg: {ev.record.name:<22} {ev.kind_name:<13} {ev.reason}")

    def on_state(self, msg: String) -> None:
        snap = json.loads(msg.data)
        previous = self.last_state
        self.last_state = snap
        if previous is None or snap["t"] // 100 != previous["t"] // 100 or snap["score"] != previous["score"]:
            self.say(f"match time {snap['t']:5d}  {snap['mode']:<16} blue {snap['score'][0]} : {snap['score'][1]} red")
        if previous is not None and snap["t"] // 100 != previous["t"] // 100:
            self.hundreds.append((snap["t"], time.monotonic()))
        start, end = self.cpu_window  # CPU of every process but this monitor, for the per-player figure
        if (not self.cpu_marks and snap["t"] >= start) or (len(self.cpu_marks) == 1 and snap["t"] >= end):
            self.cpu_marks.append((snap["t"], time.monotonic(), cpu_seconds(descendants(os.getpid()))))

    def spin(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.05)
            if self.commag.poll():
                self.say(f">>> the ComMAg exited ({self.commag.exits[-1]}): started again, it restores its registry")

    # ---- the show -------------------------------------------------------------

    def start_players(self) -> None:
        """Both teams in the chosen layout; blue 2's failing action provider and its twin alone."""
        a = self.args
        for side in ("l", "r"):
            team = TEAMS[side]
            if a.layout == "process":
                # One after the other: a burst of Python processes on a small machine would starve
                # the ones already running of the CPU they need to renew their leases.
                for number in range(1, a.players + 1):
                    for role in ("perception", "action", "decision"):
                        if (side, number, role) != ("l", 2, "action") or not a.faults:
                            self.component(role, side, number)
                            self.spin(a.stagger)
                continue
            groups = [range(1, a.players + 1)] if a.layout == "team" else [[n] for n in range(1, a.players + 1)]
            for numbers in groups:
                label = f"{team}_players" if a.layout == "team" else f"{team}_{numbers[0]}_players"
                params = {
                    "side": side,
                    "team": team,
                    "team_size": a.players,
                    "numbers": "[" + ",".join(map(str, numbers)) + "]",
                    "lease": 2.0,
                    "name": label,
                    "skip": "[blue_2_action]" if self.args.faults else "['']",
                }
                argv = [exe("cf_sim_backend", "players"), "--ros-args", "-r", f"__node:={label}"]
                for key, value in params.items():
                    argv += ["-p", f"{key}:={value}"]
                self.start(label, argv)
                self.spin(a.stagger * (1 if a.layout == "team" else 2))
        if self.args.faults:
            self.component("action", "l", 2, "-p", "relaunch_fails:=true")  # its relaunch always fails
            self.component("action", "l", 2, name="blue_2_action_twin")  # blue 2's redundant action provider

    def kill_target(self) -> tuple[str, str]:
        """What the first fault kills, and what the ComMAg should do about it."""
        layout = self.args.layout
        if layout == "process":
            return "red_2_perception", "the ComMAg should detect it and relaunch it"
        name = "red_players" if layout == "team" else "red_2_players"
        agents = 3 * (self.args.players if layout == "team" else 1)
        return name, f"one process, {agents} agents: the ComMAg should relaunch it once and every agent come back"

    def run(self) -> int:
        a = self.args
        os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
        os.environ.setdefault("ROS_DOMAIN_ID", str(50 + os.getpid() % 40))
        # Orphans (what a killed ComMAg had launched) become our children, so none is left behind.
        ctypes.CDLL(None).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
        print(
            f"Common Framework demo: {a.players} v {a.players}, 2 x {a.half_cycles} cycles of {a.cycle * 1000:.0f} ms,"
            f" layout {a.layout} (ROS_DOMAIN_ID={os.environ['ROS_DOMAIN_ID']}); output in {self.out}\n"
        )
        self.quiet_registrations = a.players > 3
        self.cpu_window = (50, a.half_cycles // 2)  # before the first fault
        rclpy.init()
        self.node = rclpy.create_node("demo_monitor")
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.node.create_subscription(RegistryEvent, "/commag/events", self.on_event, EVENTS_QOS)
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
                "-p",
                "stop_launched_on_exit:=true",
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
        self.start_players()
        expected = 6 * a.players + (1 if a.faults else 0)
        self.say(f"started {expected} components ({len(self.procs) - 1} processes); waiting until each has registered")
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
            if not killed and snap["t"] >= kill_one_at and a.faults:
                killed = True
                target, expect = self.kill_target()
                self.say(f">>> kill -9 {target} ({expect})")
                os.killpg(self.procs[target].pid, signal.SIGKILL)
            if not failed and snap["t"] >= fail_one_at and a.faults:
                failed = True
                self.say(">>> kill -9 blue_2_action (its relaunch always fails): withdrawal, then its twin takes over")
                os.killpg(self.procs["blue_2_action"].pid, signal.SIGKILL)
            if (self.out / "match.jsonl").exists() and snap["mode"] == "time_over":
                self.spin(1.0)
                break
        return self.finish()

    def figures(self) -> dict:
        """CPU per player-cycle over the measured window, and the wall time of every 100 cycles."""
        a, figures = self.args, {}
        if len(self.cpu_marks) == 2:
            (t0, w0, c0), (t1, w1, c1) = self.cpu_marks
            kinds: Counter[str] = Counter()
            label = {proc.pid: name for name, proc in self.procs.items()} | {self.commag.pid: "commag"}
            for pid, cpu in c1.items():
                used = cpu - c0.get(pid, 0.0)
                name = label.get(pid, "relaunched")
                kind = name if name in ("commag", "gateway", "sim") else "players"
                kinds[kind] += used
            player_cycles = (t1 - t0) * 2 * a.players
            figures["cpu"] = {
                "cycles": [t0, t1],
                "cores": sum(kinds.values()) / max(1e-9, w1 - w0),
                "ms_per_player_cycle": 1000 * sum(kinds.values()) / player_cycles,
                "by_kind_ms_per_player_cycle": {k: 1000 * v / player_cycles for k, v in sorted(kinds.items())},
            }
        walls = [
            w1 - w0
            for (t0, w0), (t1, w1) in zip(self.hundreds, self.hundreds[1:], strict=False)
            if t1 - t0 == 100 and (t0 - 1) // a.half_cycles == (t1 - 1) // a.half_cycles  # not across half time
        ]
        if walls:
            figures["wall_per_100_cycles"] = {
                "windows": len(walls),
                "max": max(walls),
                "median": sorted(walls)[len(walls) // 2],
            }
        return figures

    def from_logs(self) -> dict:
        """What the components said on the way out: decisions' cycles and requests, messages sent."""
        totals: Counter[str] = Counter()
        for log in (self.out / "logs").rglob("*.log"):
            last: dict[str, tuple[int, ...]] = {}  # decisions log their counts every 30 s and at exit
            for line in log.read_text(errors="replace").splitlines():
                m = re.search(r"\[(\w+)\]: requests: (\d+) cycles \((\d+) missed\), (\d+) requests", line)
                if m:
                    last[m[1]] = (int(m[2]), int(m[3]), int(m[4]))
                m = re.search(r": (\d+) messages sent, (\d+) received", line)
                if m:
                    totals["sent"] += int(m[1])
            for cycles, missed, requests in last.values():
                totals["decision_logs"] += 1
                totals["cycles"] += cycles
                totals["missed"] += missed
                totals["requests"] += requests
        return dict(totals)

    def finish(self) -> int:
        lines = (self.out / "match.jsonl").read_text().splitlines()
        end = json.loads(lines[-1]) if lines and '"end"' in lines[-1] else {}
        (self.out / "registry-events.json").write_text(json.dumps(self.events, indent=1))
        report = write_report(self.out / "match.jsonl", self.events, self.out / "report.html")
        rcg = export_rcg(self.out / "match.jsonl", self.out / "match.rcg")
        figures = self.figures()
        left = self.stop()
        said = self.from_logs()
        figures["left_behind"] = left
        (self.out / "figures.json").write_text(json.dumps(figures | {"logs": said}, indent=1))
        stats = end.get("stats", {})
        poss = stats.get("possession", {"l": 0, "r": 0})
        total = max(1, poss.get("l", 0) + poss.get("r", 0))
        print("\n==================== summary ====================")
        print(f"score        blue {end.get('score', ['?', '?'])[0]} : {end.get('score', ['?', '?'])[1]} red")
        print(f"shots        blue {stats.get('shots', {}).get('l')}  red {stats.get('shots', {}).get('r')}")
        print(f"possession   blue {poss.get('l', 0) / total:.0%}  red {poss.get('r', 0) / total:.0%}")
        print(
            f"relaunches   {self.launches} process launches; {self.counts['relaunched']} agents back"
            f" (launch attempts {self.counts['relaunching']})"
        )
        print(f"withdrawals  {self.counts['withdrawn']}")
        cpu = figures.get("cpu")
        if cpu:
            kinds = ", ".join(f"{k} {v:.2f}" for k, v in cpu["by_kind_ms_per_player_cycle"].items())
            print(
                f"CPU          {cpu['ms_per_player_cycle']:.2f} ms per player-cycle, everything included"
                f" (cycles {cpu['cycles'][0]}-{cpu['cycles'][1]}, {cpu['cores']:.2f} cores: {kinds})"
            )
        wall = figures.get("wall_per_100_cycles")
        if wall:
            print(
                f"real time    every 100 cycles took {wall['median']:.2f} s (median), {wall['max']:.2f} s at most"
                f" ({wall['windows']} windows; real time is 100 x {self.args.cycle:.3f} s)"
            )
        if said.get("decision_logs"):
            print(
                f"decisions    {said['cycles']} player-cycles decided, {said['missed']} missed;"
                f" {said['requests']} action requests ({said['requests'] / max(1, said['cycles']):.2f} per cycle)"
            )
        print(f"ACL messages sent  {said.get('sent', 0)}")
        print(f"processes    {'none left behind' if not left else f'{left} left behind and killed'}")
        print(f"report       {report}")
        print(f"match log    {self.out / 'match.jsonl'}  (format: docs/simulator.md)")
        print(f"game log     {rcg}  (rcssserver's .rcg: replay it in rcssmonitor or soccerwindow2)")
        print("=================================================")
        shown = (self.counts["relaunched"] >= 1 and self.counts["withdrawn"] >= 1) or not self.args.faults
        return 0 if end and shown and not left else 1

    def stop(self) -> int:
        """Stop everything: the ComMAg first (it must not relaunch what is being torn down), then the rest.

        Returns how many processes did not stop when asked and had to be killed.
        """
        self.commag.stop(timeout=10.0)  # it kills what it launched (stop_launched_on_exit)
        self.executor.shutdown()
        self.node.destroy_node()
        rclpy.try_shutdown()
        for proc in self.procs.values():
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGTERM)
        deadline = time.monotonic() + 15.0
        while time.monotonic() < deadline and any(p.poll() is None for p in self.procs.values()):
            time.sleep(0.2)
        stragglers = [p for p in descendants(os.getpid()) if running(p)]
        for pid in stragglers:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        time.sleep(0.5)
        while True:  # reap what we inherited as subreaper
            try:
                pid, _ = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                break
            if pid == 0:
                break
        if stragglers:
            self.say(f"killed {len(stragglers)} process(es) that did not stop: {stragglers}")
        return len(stragglers)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--players", type=int, default=11, help="players a side (2..11)")
    parser.add_argument("--half-cycles", type=int, default=600, help="cycles per half (full length: 3000)")
    parser.add_argument(
        "--layout",
        choices=("team", "player", "process"),
        default="team",
        help="team: a process per team; player: a process per player; process: a process per component",
    )
    parser.add_argument("--cycle", type=float, default=0.1, help="seconds per cycle (0.1 = real time)")
    parser.add_argument("--stagger", type=float, default=0.6, help="seconds between process starts")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", default="demo-output")
    parser.add_argument(
        "--no-faults", dest="faults", action="store_false", help="no kills (for measuring: bench/bench_realtime.py)"
    )
    args = parser.parse_args()
    if not (2 if args.faults else 1) <= args.players <= 11:
        parser.error("--players must be 2..11 (blue 2 has the redundant action provider), 1..11 with --no-faults")
    return Demo(args).run()


if __name__ == "__main__":
    sys.exit(main())
