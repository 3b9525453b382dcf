"""The rcssserver back-end: belief against ground truth over the recorded traces; with a real server,
how often each player's command goes out and is executed in synch and in real-time mode.

    python bench/bench_rcss.py [--server $RCSSSERVER] [--players 11] [--cycles 300]

Part 1 needs nothing: both recorded traces in cf_sim_backend/test/data/rcss/ are replayed into the
adapter's belief and compared with the trainer's see_global of the same cycle. Part 2 runs
tools/rcss_match.py twice (synch, then real time) when a server binary is given.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from cf_sim_backend.rcss.trace import belief_errors, localisation_errors

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tools"))
from proctree import run_passing_on  # (tools/ is not a package)

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "cf_sim_backend/test/data/rcss"
TRACES = ["player-trainer-150cycles.log", "player-trainer-opponents-1000cycles-synch.log.gz"]


def p95(values: list[float]) -> float:
    return sorted(values)[int(0.95 * len(values))]


def row(values: list[float], digits: int = 3) -> str:
    return f"{statistics.mean(values):.{digits}f} / {p95(values):.{digits}f} / {max(values):.{digits}f}"


def traces() -> None:
    print(
        "| trace | cycles | self, every cycle: mean / p95 / max m | self at a see | head at a see, deg "
        "| ball when seen, m | ball velocity, m/cycle |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in TRACES:
        e = belief_errors(DATA / name)
        _, heads = localisation_errors(DATA / name)
        print(
            f"| {name.split('.')[0]} | {len(e.me)} (+{e.unsure} unsure) | {row(e.me)} | {row(e.me_seen)} "
            f"| {row(heads, 2)} | {row(e.ball)} | {row(e.ball_velocity)} |"
        )


def match(server: str, players: int, cycles: int, realtime: bool) -> dict:
    out = Path(tempfile.mkdtemp(prefix="bench-rcss-"))
    argv = [sys.executable, str(ROOT / "tools/rcss_match.py"), "--server", server, "--players", str(players)]
    argv += ["--cycles", str(cycles), "--out", str(out)] + (["--realtime"] if realtime else [])
    done = run_passing_on(argv, timeout=3000, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise SystemExit(done.stderr[-2000:])
    return json.loads(done.stdout.strip().splitlines()[-1])


def matches(server: str, players: int, cycles: int) -> None:
    print(
        "\n| mode | players | cycles | wall s | cycles with a body command: median / min "
        "| commands executed by the server: median / min | kicks | score |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for realtime in (False, True):
        s = match(server, players, cycles, realtime)
        ps = s["players"]
        sent = [p["body_commands"] / max(1, p["cycles"]) for p in ps]
        executed = [p["executed"] / max(1, p["body_commands"]) for p in ps if p["body_commands"]]
        print(
            f"| {'real time' if realtime else 'synch'} | {len(ps)} | {cycles} | {s['seconds']} "
            f"| {statistics.median(sent):.1%} / {min(sent):.1%} | {statistics.median(executed):.1%} / "
            f"{min(executed):.1%} | {sum(p['kicks'] for p in ps)} | {ps[0]['score'][0]}:{ps[0]['score'][1]} |"
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--server", default=os.environ.get("RCSSSERVER", ""))
    ap.add_argument("--players", type=int, default=11)
    ap.add_argument("--cycles", type=int, default=300)
    args = ap.parse_args()
    traces()
    if args.server:
        matches(args.server, args.players, args.cycles)
    else:
        print("\n(no rcssserver: pass --server or set RCSSSERVER for the match figures)")


if __name__ == "__main__":
    main()
