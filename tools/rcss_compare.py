"""Two codes' drills or series side by side, and how far apart chance alone puts them.

    python tools/rcss_compare.py --a DIR [DIR ...] --b DIR [DIR ...] [--resamples 10000] [--seed 0]

Each DIR is what ``tools/rcss_drill.py --out`` (its ``drill.json``) or ``tools/rcss_series.py --out``
(its ``series.json``) wrote; A's and B's must be of one kind. A drill is measured per try taken
(into their third, beyond 30 m, with a shot, the furthest the ball got while ours, how long we kept
it), a series per match (goals and shots each way, possession, the ball ours in their third, our offsides).

For each measure: A's and B's values (a share, a mean or a median over the tries or matches), B
minus A, a 95% interval for that difference (bootstrap: each side's tries or matches drawn again
with replacement), and p: how often the pooled tries or matches, dealt out at random to two sides
of A's and B's sizes, differ at least as much (two-sided permutation test). Thirty tries a side
tell 10 of 30 from 19 of 30 only just (p about 0.04): a change within the interval of main
against main is not shown to be one.
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

THIRD = 17.5  # m from the halfway line: the edge of their third (rcss_drill's THIRD)


def share(xs: Sequence[float]) -> float:
    return sum(xs) / len(xs)


# name -> (what of a try (drill) or a match (series) is measured, how the values are summed up, format)
DRILL = {
    "into their third": (lambda t: float(t["furthest"] > THIRD), share, "{:.0%}"),
    "beyond 30 m": (lambda t: float(t["furthest"] > 30.0), share, "{:.0%}"),
    "with a shot": (lambda t: float(t["shots"] > 0), share, "{:.0%}"),
    "furthest (m)": (lambda t: t["furthest"], statistics.median, "{:.1f}"),
    "kept (cycles)": (lambda t: t["kept"], statistics.median, "{:.0f}"),
    "goals for": (lambda t: t["goals_for"], share, "{:.2f}"),
}
SERIES = {
    "goals for": (lambda m: m["score"][0], statistics.mean, "{:.2f}"),
    "goals against": (lambda m: m["score"][1], statistics.mean, "{:.2f}"),
    "shots for": (lambda m: m["shots"][0], statistics.mean, "{:.1f}"),
    "shots against": (lambda m: m["shots"][1], statistics.mean, "{:.1f}"),
    "possession": (lambda m: m["possession"][0], statistics.mean, "{:.0%}"),
    "ours in their third": (lambda m: m["attacking"][0], statistics.mean, "{:.1%}"),
    "our offsides": (lambda m: m["offsides"][0], statistics.mean, "{:.1f}"),
}


def load(dirs: Sequence[Path]) -> tuple[str, list[dict]]:
    """("drill" or "series", the tries taken or the matches played) of the output directories."""
    kinds, items = set(), []
    for d in dirs:
        if (d / "drill.json").is_file():
            kinds.add("drill")
            items += [t for t in json.loads((d / "drill.json").read_text())["tries"] if t.get("taken")]
        elif (d / "series.json").is_file():
            kinds.add("series")
            items += [m for m in json.loads((d / "series.json").read_text()) if m.get("score") is not None]
        else:
            raise ValueError(f"{d}: neither drill.json nor series.json")
    if len(kinds) != 1:
        raise ValueError("drills and series cannot be compared with each other")
    return kinds.pop(), items


def compare(
    a: Sequence[float], b: Sequence[float], stat: Callable, resamples: int, rng: random.Random
) -> tuple[float, tuple[float, float], float]:
    """B's stat minus A's, its 95% bootstrap interval, and the permutation test's two-sided p."""
    diff = stat(b) - stat(a)
    boot = sorted(stat(rng.choices(b, k=len(b))) - stat(rng.choices(a, k=len(a))) for _ in range(resamples))
    interval = (boot[int(0.025 * resamples)], boot[min(resamples - 1, int(0.975 * resamples))])
    pooled, as_far = list(a) + list(b), 0
    for _ in range(resamples):
        rng.shuffle(pooled)
        as_far += abs(stat(pooled[len(a) :]) - stat(pooled[: len(a)])) >= abs(diff) - 1e-12
    return diff, interval, (as_far + 1) / (resamples + 1)


def table(kind: str, a: list[dict], b: list[dict], resamples: int = 10000, seed: int = 0) -> str:
    """The side-by-side table of the two sides' tries or matches."""
    measures = DRILL if kind == "drill" else SERIES
    unit = "tries" if kind == "drill" else "matches"
    rng = random.Random(seed)
    rows = [
        f"A: {len(a)} {unit}, B: {len(b)} {unit}",
        "",
        "| measure | A | B | B - A | 95% interval | p |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for name, (of, stat, fmt) in measures.items():
        try:
            xa, xb = [float(of(i)) for i in a], [float(of(i)) for i in b]
        except (KeyError, IndexError, TypeError):
            continue  # (a measure an older tool did not write)
        diff, (lo, hi), p = compare(xa, xb, stat, resamples, rng)
        pct = fmt.endswith("%}")
        signed = "{:+.0%}" if pct else fmt.replace("{:", "{:+")
        rows.append(
            f"| {name} | {fmt.format(stat(xa))} | {fmt.format(stat(xb))} | {signed.format(diff)}"
            f" | {signed.format(lo)} .. {signed.format(hi)} | {p:.2f} |"
        )
    return "\n".join(rows)


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--a", type=Path, nargs="+", required=True, help="output directories of one code")
    ap.add_argument("--b", type=Path, nargs="+", required=True, help="output directories of the other")
    ap.add_argument("--resamples", type=int, default=10000)
    ap.add_argument("--seed", type=int, default=0, help="of the resampling (the same seed, the same table)")
    args = ap.parse_args(argv)
    if args.resamples < 1:
        ap.error("--resamples must be 1 or more")
    try:
        kind_a, a = load(args.a)
        kind_b, b = load(args.b)
    except (OSError, ValueError, KeyError) as exc:
        print(f"rcss_compare: {exc}", file=sys.stderr)
        return 2
    if kind_a != kind_b:
        print("rcss_compare: A and B must both be drills or both series", file=sys.stderr)
        return 2
    if not a or not b:
        print("rcss_compare: a side has no try taken or match played", file=sys.stderr)
        return 2
    print(table(kind_a, a, b, args.resamples, args.seed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
