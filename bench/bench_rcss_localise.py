"""Localisation from rcssserver's see messages against the trainer's ground truth, over the recorded trace.

python bench/bench_rcss_localise.py [TRACE]
"""

from __future__ import annotations

import statistics
import sys
from pathlib import Path

from cf_sim_backend.rcss_trace import localisation_errors

TRACE = Path(__file__).resolve().parent.parent / "cf_sim_backend/test/data/rcss/player-trainer-150cycles.log"


def main() -> None:
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else TRACE
    errors, heads = localisation_errors(path)
    print("| trace | sees localised | position error mean / p95 / max m | head error mean / p95 / max deg |")
    print("|---|---:|---:|---:|")
    p95 = lambda v: sorted(v)[int(0.95 * len(v))]  # noqa: E731
    print(
        f"| {path.name} | {len(errors)} | {statistics.mean(errors):.3f} / {p95(errors):.3f} / {max(errors):.3f} "
        f"| {statistics.mean(heads):.2f} / {p95(heads):.2f} / {max(heads):.2f} |"
    )


if __name__ == "__main__":
    main()
