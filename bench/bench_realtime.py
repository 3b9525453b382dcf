"""What a player costs per cycle in a real-time match, with every process of the framework running.

Plays the demo's match (tools/demo.py, without its faults) for 1, 3 and 11 players a side, in
each layout: ``process-single`` (each component its own process in rclpy's SingleThreadedExecutor:
the framework before hosting), ``process`` (the same processes in the EventsExecutor, today's
default) and ``team`` (a process per team: agents co-located in a component container), one after
the other in this run.
For each: CPU of every process (components, simulator, ComMAg, gateway) over a window of play,
in ms per player per cycle; the cores used; the wall time of every 100 cycles (real time is
10.0 s); and the cycles the decisions missed.

    python bench/bench_realtime.py [--sizes 1 3 11] [--layouts process-single process team] [--half-cycles 400]
                                   [--rcss $RCSSSERVER] [--rcss-cycles 600] [--rcss-runs 1]

With ``--rcss`` (default: $RCSSSERVER) it also plays our 11 players in real time on rcssserver
(tools/rcss_match.py --realtime) with each decision in its own process and hosted by its
player's adapter, and prints the share of body commands the server executed (those it did not, by
kind: a kick the server refused because the ball was out of reach, a command that came too late),
and our CPU.

Slow by nature (real time): about 1.5 min per run, more with the process layout at 11 a side.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tools"))
from proctree import run_passing_on  # noqa: E402 (tools/ is not a package)

DEMO = HERE.parent / "tools" / "demo.py"


def run(players: int, layout: str, half_cycles: int, seed: int) -> dict:
    with tempfile.TemporaryDirectory(prefix="cf-bench-rt-") as out:
        process_layout, _, executor = layout.partition("-")
        env = {**os.environ, "CF_EXECUTOR": executor or "events"}
        argv = [sys.executable, str(DEMO), "--no-faults", "--players", str(players), "--layout", process_layout]
        argv += ["--half-cycles", str(half_cycles), "--seed", str(seed), "--out", out]
        t0 = time.monotonic()
        done = subprocess.run(argv, capture_output=True, text=True, timeout=1800, env=env)
        took = time.monotonic() - t0
        path = Path(out) / "figures.json"
        if not path.exists():
            return {"error": f"exit {done.returncode}: {done.stdout[-500:]} {done.stderr[-500:]}"}
        figures = json.loads(path.read_text())
        figures["took"] = took
        return figures


def rcss(server: str, layout: str, cycles: int) -> dict:
    argv = [sys.executable, str(HERE.parent / "tools" / "rcss_match.py"), "--server", server, "--realtime"]
    argv += ["--players", "11", "--cycles", str(cycles), "--layout", layout]
    done = run_passing_on(argv, timeout=1800, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        summary = json.loads(done.stdout.strip().splitlines()[-1])
    except (IndexError, ValueError):
        return {"error": f"exit {done.returncode}: {done.stderr[-300:]}"}
    return summary


def row(players: int, layout: str, f: dict) -> str:
    if "error" in f or "cpu" not in f:
        return f"| {players} | {layout} | failed: {f.get('error', 'no CPU window')[:80]} | | | | |"
    cpu, wall, logs = f["cpu"], f.get("wall_per_100_cycles", {}), f.get("logs", {})
    kinds = ", ".join(f"{k} {v:.2f}" for k, v in cpu["by_kind_ms_per_player_cycle"].items())
    return (
        f"| {players} | {layout} | **{cpu['ms_per_player_cycle']:.2f}** | {cpu['cores']:.2f} | {kinds} |"
        f" {wall.get('median', float('nan')):.2f} / {wall.get('max', float('nan')):.2f} |"
        f" {logs.get('missed', '?')} of {logs.get('cycles', '?')} |"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1, 3, 11])
    parser.add_argument("--layouts", nargs="+", default=["process-single", "process", "team"])
    parser.add_argument("--half-cycles", type=int, default=400)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--rcss", default=os.environ.get("RCSSSERVER", ""), help="rcssserver binary")
    parser.add_argument("--rcss-cycles", type=int, default=600)
    parser.add_argument("--rcss-runs", type=int, default=1, help="rcssserver matches per layout")
    args = parser.parse_args()
    window = f"cycles 50-{args.half_cycles // 2}"
    print(f"CPU per player-cycle, everything included ({window} of a 2 x {args.half_cycles} match, real time)\n")
    print(
        "| players a side | layout | CPU ms per player-cycle | cores | of which (ms) | wall s per 100 cycles, median / max | decision cycles missed |"
    )
    print("|---:|---|---:|---:|---|---:|---:|")
    results = {}
    for players in args.sizes:
        for layout in args.layouts:
            figures = run(players, layout, args.half_cycles, args.seed)
            results[(players, layout)] = figures
            print(row(players, layout, figures), flush=True)
    if args.rcss:
        print(f"\nrcssserver, 11 players in real time, {args.rcss_cycles} cycles (tools/rcss_match.py --realtime)\n")
        print(
            "| decisions | body commands executed by the server | not executed, by kind | sent > 50 ms into the cycle"
            " | our CPU ms per cycle | per player-cycle |"
        )
        print("|---|---:|---|---:|---:|---:|")
        for _ in range(args.rcss_runs):
            for layout, what in (("process", "a process each"), ("player", "hosted by the adapter")):
                r = rcss(args.rcss, layout, args.rcss_cycles)
                if "error" in r:
                    print(f"| {what} | failed: {r['error'][:80]} | | | | |")
                    continue
                lost = ", ".join(f"{k} {n}" for k, n in sorted(r.get("unexecuted", {}).items())) or "none"
                print(
                    f"| {what} | {r['executed_share']:.1%} ({r['executed']} of {r['sent']}) | {lost} |"
                    f" {r.get('acts_after_50ms', '?')} | {r.get('our_cpu_ms_per_cycle', float('nan')):.1f} |"
                    f" {r.get('our_cpu_ms_per_player_cycle', float('nan')):.2f} |",
                    flush=True,
                )
    print()
    for players in args.sizes:
        new = results.get((players, "team"), {})
        for layout in ("process-single", "process"):
            old = results.get((players, layout), {})
            if "cpu" in old and "cpu" in new:
                ratio = old["cpu"]["ms_per_player_cycle"] / new["cpu"]["ms_per_player_cycle"]
                print(f"{players} a side: team costs {ratio:.1f}x less CPU per player-cycle than {layout}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
