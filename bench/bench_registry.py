"""The registry core with 10,000 components: lookup latency and renewals per second.

python bench/bench_registry.py [--components 10000] [--lookups 20000]
"""

from __future__ import annotations

import argparse
import random
import statistics
import time

from cf_commag.records import Query, Record
from cf_commag.registry import Registry, RegistryConfig
from cf_lang.taxonomy import SERVICES, Direction


def percentile(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--components", type=int, default=10_000)
    parser.add_argument("--lookups", type=int, default=20_000)
    args = parser.parse_args()
    rng = random.Random(1)
    classes = [c for c in SERVICES.classes if c != "Service"]
    reg = Registry(RegistryConfig(max_components=args.components + 1))
    records = [
        Record(
            name=f"c{i}",
            service_class=rng.choice(classes),
            team=f"team{i % 50}",
            player_number=i % 11 + 1,
            launch_command=("/ws/install/x/lib/x/comp", f"--id={i}"),
        )
        for i in range(args.components)
    ]
    for r in records:
        reg.register(r, now=0.0)

    queries = {
        "class only (GENERAL)": lambda: Query(rng.choice(classes)),
        "class + team + player (GENERAL)": lambda: Query(
            rng.choice(classes), team=f"team{rng.randrange(50)}", player_number=rng.randrange(1, 12)
        ),
        "class, BOTH directions, top 5": lambda: Query(rng.choice(classes), Direction.BOTH, max_results=5),
        "root 'Service', SPECIFIC (all 10k)": lambda: Query("Service", Direction.SPECIFIC, max_results=10),
    }
    print(f"registry with {len(reg.directory)} components\n")
    print("| lookup | p50 µs | p99 µs | results (median) |")
    print("|---|---:|---:|---:|")
    for label, make in queries.items():
        lat, sizes = [], []
        for _ in range(args.lookups if "all 10k" not in label else 200):
            q = make()
            t0 = time.perf_counter()
            found = reg.lookup(q)
            lat.append((time.perf_counter() - t0) * 1e6)
            sizes.append(len(found))
        print(
            f"| {label} | {percentile(lat, 0.5):.0f} | {percentile(lat, 0.99):.0f} | {statistics.median(sizes):.0f} |"
        )

    rounds = []
    for k in range(5):
        t0 = time.perf_counter()
        for r in records:
            reg.register(r, now=1.0 + k)
        rounds.append(len(records) / (time.perf_counter() - t0))
    t0 = time.perf_counter()
    reg.tick(3.0)
    tick_ms = (time.perf_counter() - t0) * 1e3
    print(f"\nrenewals: {statistics.median(rounds):,.0f} per second (median of 5 rounds of {len(records)})")
    print(f"one tick over {len(records)} healthy components: {tick_ms:.1f} ms")


if __name__ == "__main__":
    main()
