"""The ComMAg over real ROS services and real processes.

1. Register/renew calls per second against the installed `commag`, 1 and 16 calls in flight.
2. Failure detection: kill -9 a component, time until the ComMAg reports it suspect
   (minus the lease: how late detection is), and from suspect until the relaunched
   process has re-registered.

    python bench/bench_commag_ros.py [--kills 5]
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import sys
import tempfile
import time
import uuid
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "test"))
from cf_interfaces.msg import ComponentRecord
from cf_interfaces.srv import Register
from cf_system import Probe, Processes, start_commag, start_component


def calls_per_second(probe: Probe, in_flight: int, seconds: float = 3.0) -> float:
    client = probe.register
    probe.spin_until(client.service_is_ready)
    requests = [
        Register.Request(component=ComponentRecord(name=f"bench_{i}", service_class="Kick", lease_period=60.0))
        for i in range(in_flight)
    ]
    pending = [client.call_async(r) for r in requests]
    done = 0
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        probe.executor.spin_once(timeout_sec=0.01)
        for i, fut in enumerate(pending):
            if fut.done():
                assert fut.result().accepted
                done += 1
                pending[i] = client.call_async(requests[i])
    return done / (time.monotonic() - start)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--kills", type=int, default=5)
    args = parser.parse_args()
    tag = "b" + uuid.uuid4().hex[:8]
    tmp = Path(tempfile.mkdtemp(prefix="cf-bench-"))
    procs = Processes(tag, tmp)
    try:
        start_commag(procs, tag, tmp)
        probe = Probe(f"/commag_{tag}", tag)
        print("| register/renew over ROS services | calls/s |\n|---|---:|")
        for n in (1, 16):
            print(f"| {n} in flight | {calls_per_second(probe, n):,.0f} |")

        print(
            "\n| lease | kills | detection after lease, median / max ms | suspect -> re-registered, median / max ms |"
        )
        print("|---:|---:|---:|---:|")
        for lease in (0.5, 1.0):
            name = f"bench_kick_{str(lease).replace('.', '_')}_{tag}"
            start_component(procs, tag, name, "--service-class", "Kick", "--lease", str(lease))
            probe.wait_kind(name, "registered")
            late, relaunch = [], []
            for k in range(args.kills):
                probe.spin_for(1.5 * lease)
                pids = [int(p) for p in os.popen(f"pgrep -f -- '--name {name} '").read().split()]
                assert pids, "component not running"
                killed_at = time.monotonic()
                for pid in pids:
                    os.kill(pid, signal.SIGKILL)
                probe.wait_kind(name, "suspect", count=k + 1)
                suspect_at = time.monotonic()
                probe.wait_kind(name, "relaunched", count=k + 1)
                back_at = time.monotonic()
                late.append((suspect_at - killed_at - lease) * 1000)
                relaunch.append((back_at - suspect_at) * 1000)
            print(
                f"| {lease} s | {args.kills} | {statistics.median(late):.0f} / {max(late):.0f} "
                f"| {statistics.median(relaunch):.0f} / {max(relaunch):.0f} |"
            )
        print("\n(detection after lease can be negative: the last renewal came up to lease/3 before the kill)")
        probe.close()
    finally:
        procs.kill_all()


if __name__ == "__main__":
    main()
