"""What an idle rclpy node costs, by executor: why every node here runs in the EventsExecutor.

Starts one process per variant, side by side, each with one node that does nothing but what the
variant says, and measures each process's own CPU over the same seconds:

- ``single``: rclpy's SingleThreadedExecutor, no timer;
- ``single+timer``: the same with one 10 Hz timer (an agent's tick);
- ``events``: rclpy.experimental.EventsExecutor, no timer;
- ``events+timer``: the same with one 10 Hz timer.

    python bench/bench_idle.py [--seconds 10] [--rounds 3]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

VARIANT = r"""
import json, sys, threading, time, os
import rclpy
kind, seconds = sys.argv[1], float(sys.argv[2])
rclpy.init()
node = rclpy.create_node(f"idle_{os.getpid()}")
if kind.endswith("+timer"):
    node.create_timer(0.1, lambda: None)
if kind.startswith("events"):
    from rclpy.experimental import EventsExecutor
    executor = EventsExecutor()
else:
    from rclpy.executors import SingleThreadedExecutor
    executor = SingleThreadedExecutor()
executor.add_node(node)

def measure():
    time.sleep(2.0)  # past start-up and discovery
    t0 = time.process_time()
    time.sleep(seconds)
    print(json.dumps({"ms_per_s": 1000 * (time.process_time() - t0) / seconds}), flush=True)
    os._exit(0)

threading.Thread(target=measure, daemon=True).start()
while True:
    executor.spin_once(timeout_sec=0.1)
"""

VARIANTS = ("single", "single+timer", "events", "events+timer")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    results: dict[str, list[float]] = {v: [] for v in VARIANTS}
    for _ in range(args.rounds):
        procs = {
            v: subprocess.Popen(
                [sys.executable, "-c", VARIANT, v, str(args.seconds)], stdout=subprocess.PIPE, text=True
            )
            for v in VARIANTS
        }
        for v, proc in procs.items():
            out, _ = proc.communicate(timeout=args.seconds + 60)
            results[v].append(json.loads(out.strip().splitlines()[-1])["ms_per_s"])
    base = statistics.median(results["events+timer"])
    print(f"CPU of one idle node, ms per second (median of {args.rounds} rounds, all variants side by side)\n")
    print("| executor | ms of CPU per second | per 100 ms cycle | vs events+timer |")
    print("|---|---:|---:|---:|")
    for v in VARIANTS:
        m = statistics.median(results[v])
        print(f"| {v} | {m:.1f} | {m / 10:.2f} | {m / base:.1f}x |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
