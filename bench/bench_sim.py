"""The simulator core's speed (11 v 11) and, with real processes, the cycle budget of one player.

1. Core: cycles per second of a full 11 v 11 match of naive chasers (commands included), and how
   many times faster than real time (100 ms cycles) that is. Target: at least 20x.
2. Budget: the installed simulator, one player's perception and action components and a decision
   agent here. Each cycle: state published -> perception informs the decision (fipa-subscribe) ->
   the decision requests a dash -> the action component agrees. Times are from the state's arrival.

    python bench/bench_sim.py [--cycles 6000] [--budget-cycles 200]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
import uuid
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "test"))

from cf_sim_backend.embedded.chaser import chase_commands  # noqa: E402
from cf_sim_backend.embedded.sim import Simulator  # noqa: E402
from cf_sim_backend.world import Params, Side  # noqa: E402


def core(cycles: int) -> None:
    rates = []
    for seed in range(3):
        sim = Simulator(Params(half_cycles=cycles // 2, auto_kick_off_cycles=1), team_sizes=(11, 11), seed=seed)
        t0 = time.perf_counter()
        while not sim.finished:
            chase_commands(sim, Side.LEFT)
            chase_commands(sim, Side.RIGHT)
            sim.step()
        rates.append(sim.world.time / (time.perf_counter() - t0))
    rate = statistics.median(rates)
    print("| simulator core, 11 v 11 chasers | cycles/s | x real time (100 ms cycles) |\n|---|---:|---:|")
    print(f"| median of 3 matches of {cycles} cycles | {rate:,.0f} | **{rate / 10:,.0f}x** |")


def budget(cycles: int) -> None:
    import rclpy
    from std_msgs.msg import String

    from cf_commag.client import Agent
    from cf_sim_backend.embedded.topics import STATE_QOS, state_topic
    from cf_system import Processes, executable, start_commag

    tag = "s" + uuid.uuid4().hex[:8]
    tmp = Path(tempfile.mkdtemp(prefix="cf-bench-sim-"))
    procs = Processes(tag, tmp)
    rclpy.init()
    try:
        start_commag(procs, tag, tmp)
        sim = f"sim_{tag}"
        procs.start(
            [
                executable("cf_sim_backend", "sim"),
                "--ros-args",
                "-r",
                f"__node:={sim}",
                "-p",
                f"sim:={sim}",
                "-p",
                f"commag:=/commag_{tag}",
                "-p",
                "left_size:=11",
                "-p",
                "right_size:=11",
                "-p",
                "auto_kick_off_cycles:=5",
            ],
            "sim",
        )
        for role in ("perception", "action"):
            procs.start(
                [
                    executable("cf_sim_backend", role),
                    "--ros-args",
                    "-r",
                    f"__node:={role}_{tag}",
                    "-p",
                    f"sim:={sim}",
                    "-p",
                    f"commag:=/commag_{tag}",
                    "-p",
                    "number:=7",
                    "-p",
                    f"team:=blue{tag}",
                ],
                role,
            )
        node = rclpy.create_node(f"bench_decision_{tag}")
        arrived: dict[int, float] = {}
        import json

        node.create_subscription(
            String,
            state_topic(sim),
            lambda m: arrived.setdefault(json.loads(m.data)["t"], time.perf_counter()),
            STATE_QOS,
        )
        agent = Agent(node, name=f"decision_{tag}", service_class="PlayerDecision", commag=f"/commag_{tag}")
        deadline = time.monotonic() + 60
        while not (agent.provider("Action", team=f"blue{tag}") and agent.provider("WorldModel", team=f"blue{tag}")):
            rclpy.spin_once(node, timeout_sec=0.05)
            assert time.monotonic() < deadline, "components did not register"
        action = agent.provider("Action", team=f"blue{tag}")
        perceived, agreed = [], []
        pending: dict[str, tuple[int, float]] = {}

        def on_inform(msg) -> None:
            if msg.performative.value != "inform" or not msg.content or not msg.content.startswith("(Game"):
                return
            t = int(msg.content.split(":time ")[1].split()[0].rstrip(")"))
            now = time.perf_counter()
            if t in arrived:
                perceived.append((now - arrived[t]) * 1000)
                req = agent.request(
                    action,
                    "(exec Player dash :playerNumber 7 :whichTeam our :power 30)",
                    on_update=lambda m, t=t: agreed.append((time.perf_counter() - arrived[t]) * 1000),
                )
                pending[req.conversation_id] = (t, now)

        perception = agent.provider("WorldModel", team=f"blue{tag}")
        agent.request(perception, "(val Game)", protocol="fipa-subscribe", timeout=None, on_update=on_inform)
        while len(agreed) < cycles:
            rclpy.spin_once(node, timeout_sec=0.1)
        print("\n| one player's cycle, 11 v 11 running | p50 ms | p95 ms | share of a 100 ms cycle (p50) |")
        print("|---|---:|---:|---:|")
        for label, values in (
            ("state -> perception informs the decision", perceived),
            ("state -> action agreed to the decision's request", agreed),
        ):
            values.sort()
            p50, p95 = values[len(values) // 2], values[int(len(values) * 0.95)]
            print(f"| {label} | {p50:.1f} | {p95:.1f} | {p50:.0f}% |")
    finally:
        rclpy.try_shutdown()
        procs.kill_all()


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--cycles", type=int, default=6000)
    parser.add_argument("--budget-cycles", type=int, default=200)
    args = parser.parse_args()
    core(args.cycles)
    budget(args.budget_cycles)


if __name__ == "__main__":
    main()
