"""`make demo`: the framework's most complete real flow, end to end, with real processes.

Starts the installed ComMAg and five components (two players' kick providers,
a redundant twin, a perception and a flaky one), then a decision agent that
finds its kick provider through the ComMAg by service class and keeps sending
it FIPA requests. Midway it kill -9s a component (the ComMAg detects it and
relaunches it) and makes another fail on every relaunch (the ComMAg withdraws
it and requests reroute to the twin). Prints every registry event as it
happens and a summary at the end.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import rclpy
from ament_index_python.packages import get_package_prefix
from rclpy.executors import SingleThreadedExecutor

from cf_commag.client import Agent
from cf_commag.commag_node import EVENTS_QOS
from cf_interfaces.msg import RegistryEvent

COMMAG = "/commag"


def exe(name: str) -> str:
    return str(Path(get_package_prefix("cf_commag")) / "lib" / "cf_commag" / name)


def say(t0: float, text: str) -> None:
    print(f"[{time.monotonic() - t0:6.2f} s] {text}", flush=True)


def main() -> int:
    work = Path(tempfile.mkdtemp(prefix="cf-demo-"))
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    os.environ.setdefault("ROS_DOMAIN_ID", str(50 + os.getpid() % 40))
    procs: list[subprocess.Popen] = []

    def start(argv: list[str], log: str) -> subprocess.Popen:
        out = open(work / f"{log}.log", "ab")  # noqa: SIM115 - lives as long as the process
        proc = subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
        procs.append(proc)
        return proc

    t0 = time.monotonic()
    print(f"Common Framework demo (ROS_DOMAIN_ID={os.environ['ROS_DOMAIN_ID']}, logs in {work})\n")
    start(
        [
            exe("commag"),
            "--ros-args",
            "-p",
            f"persistence_path:={work / 'registry.json'}",
            "-p",
            f"log_dir:={work / 'components'}",
            "-p",
            "backoff_initial:=0.3",
        ],
        "commag",
    )
    components = {
        "blue_7_kick": ["--service-class", "Kick", "--team", "blue", "--player", "7"],
        "blue_7_action": ["--service-class", "Action", "--team", "blue", "--player", "7"],
        "blue_7_perception": ["--service-class", "WorldModel", "--team", "blue", "--player", "7"],
        "red_4_kick": ["--service-class", "Kick", "--team", "red", "--player", "4", "--relaunch-fails"],
        "red_4_action": ["--service-class", "Action", "--team", "red", "--player", "4"],
    }
    started = {n: start([exe("demo_component"), "--name", n, "--lease", "0.5", *a], n) for n, a in components.items()}

    rclpy.init()
    node = rclpy.create_node("demo_decision")
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    counts: Counter[str] = Counter()

    def on_event(ev: RegistryEvent) -> None:
        counts[ev.kind_name] += 1
        say(t0, f"ComMAg event: {ev.record.name:<18} {ev.kind_name:<13} {ev.reason}")

    node.create_subscription(RegistryEvent, f"{COMMAG}/events", on_event, EVENTS_QOS)
    decision = Agent(node, name="demo_decision", service_class="PlayerDecision", commag=COMMAG)
    served: Counter[str] = Counter()
    replies: Counter[str] = Counter()

    def spin(seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            executor.spin_once(timeout_sec=0.02)

    def play(seconds: float) -> None:
        """Each player's decision asks its best Kick provider to kick, twice a second."""
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            for team, number in (("blue", 7), ("red", 4)):
                provider = decision.provider("Kick", team=team, player_number=number)
                if provider is None:
                    continue
                future = decision.request(
                    provider, f"(exec Player kick :playerNumber {number} :whichTeam our :power 80 :direction 0)"
                )
                spin_until = time.monotonic() + 1.0
                while not future.done() and time.monotonic() < spin_until:
                    executor.spin_once(timeout_sec=0.02)
                state = future.result().state if future.done() else "no answer"
                served[provider] += 1
                replies[state] += 1
            spin(0.5)

    try:
        say(t0, "waiting for every component to register ...")
        while not (decision.registered and len(decision.providers("Service", direction=1)) >= 6):
            spin(0.1)
        for team, number in (("blue", 7), ("red", 4)):
            names = [e.name for e in decision.providers("Kick", team=team, player_number=number)]
            say(t0, f"lookup Kick for {team} {number}: {names}  (an Action provider can serve Kick)")
        play(3.0)
        say(t0, f">>> kill -9 blue_7_kick (pid {started['blue_7_kick'].pid}): the ComMAg should relaunch it")
        os.kill(started["blue_7_kick"].pid, signal.SIGKILL)
        play(4.0)
        say(t0, f">>> kill -9 red_4_kick (pid {started['red_4_kick'].pid}): every relaunch of it fails")
        os.kill(started["red_4_kick"].pid, signal.SIGKILL)
        play(6.0)
        names = [e.name for e in decision.providers("Kick", team="red", player_number=4)]
        say(t0, f"lookup Kick for red 4 now: {names}  (withdrawn provider gone, rerouted to the twin)")
        play(2.0)
    finally:
        print("\n================ summary ================")
        print("registry events: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
        print("requests answered by: " + ", ".join(f"{k} {v}" for k, v in sorted(served.items())))
        print("request outcomes: " + ", ".join(f"{k} {v}" for k, v in sorted(replies.items())))
        print(f"messages sent {decision.counters['sent']}, received {decision.counters['received']}")
        print(f"logs: {work}")
        print("==========================================")
        decision.close()
        node.destroy_node()
        rclpy.try_shutdown()
        for proc in procs:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGTERM)
        time.sleep(1.0)
        for name in components:  # relaunched components are the ComMAg's children, not ours
            subprocess.run(["pkill", "-9", "-f", "--", f"--name {name} "], check=False)
        for proc in procs:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
    return 0 if counts["relaunched"] >= 1 and counts["withdrawn"] >= 1 else 1


if __name__ == "__main__":
    sys.exit(main())
