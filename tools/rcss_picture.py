"""How well our player on the ball knew where the opponents were: one table row per reason.

    python tools/rcss_picture.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--near 25] [--within 3] [--by-body]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``). A decision that aims the ball at a point logs the opponents it believed within 30 m
of the ball (``... @ target X Y ball X Y opp X Y S, ...``, our frame). Each such decision in play
(or at our set piece) is set against the game log's truth of that cycle: of the opponents truly
within ``--near`` metres of the ball, how many the decision had nowhere within ``--within`` metres
of where they stood. This is how docs/performance.md counts what the passer had not seen.
``--by-body``: the same opponents by where they stood from the decider, degrees off his body and
metres away (the head turns 90 degrees each way: a man behind him is seen only as he turns).
"""

from __future__ import annotations

import math
import re
import sys
from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, game_log, logged, match_parser, reason
from rcss_series import Body, show_bodies

_AIMED = re.compile(r"\[(\w+?)_(\d+)_decision\]: t=(\d+) \w+: (.*?) @ target \S+ \S+ ball \S+ \S+ opp ?(.*)")


@dataclass(frozen=True)
class Aimed:
    """A decision that logged its aim, beside the game log's truth of its cycle (our frame: x towards
    their goal, y mirrored as the decision's own frame is)."""

    time: int
    number: int
    why: str  # its reason
    mode: str  # the play mode
    ball: tuple[float, float]
    theirs: list[tuple[tuple[float, float], tuple[float, float]]]  # each opponent: (server frame, ours)
    believed: list[tuple[float, float]]  # the opponents the decision believed in


def aimed(match: Path, team: str) -> Iterator[Aimed]:
    """Each decision of ``team``'s players in ``match`` that logged its aim, in a cycle the game log has."""
    frames, side, forward = game(match, team)
    at = {frame[0]: frame for frame in frames}
    for m in logged(match, team, _AIMED, at):
        t = int(m.group(3))
        _, mode, ball, players = at[t]
        theirs = [((x, y), (forward * x, -forward * y)) for s, _, x, y, _ in players if s != side]
        believed = [tuple(map(float, entry.split()[:2])) for entry in m.group(5).split(",") if entry.strip()]
        ball_ours = (forward * ball[0], -forward * ball[1])
        yield Aimed(t, int(m.group(2)), reason(m.group(4)), mode, ball_ours, theirs, believed)


def picture(match: Path, team: str = "CF", near: float = 25.0, within: float = 3.0) -> dict[str, list[int]]:
    """Reason -> [decisions, opponents truly within ``near`` of the ball, of them not believed within ``within``]."""
    out: dict[str, list[int]] = defaultdict(lambda: [0, 0, 0])
    for a in aimed(match, team):
        if a.mode != "play_on" and not a.why.startswith("set piece"):
            continue
        close = [ours for _, ours in a.theirs if math.dist(ours, a.ball) <= near]
        row = out[a.why]
        row[0] += 1
        row[1] += len(close)
        row[2] += sum(1 for p in close if all(math.dist(p, b) > within for b in a.believed))
    return out


def bodies(match: Path, side: str) -> dict[tuple[int, int], Body]:
    """(time, number) -> each of ``side``'s players as a game log's show lines have him."""
    out = {}
    for line in game_log(match).read_text(errors="replace").splitlines():
        if line.startswith("(show "):
            t = int(line.split()[1])
            out.update(((t, n), b) for (s, n), b in show_bodies(line)[1].items() if s == side)
    return out


def by_body(match: Path, team: str = "CF", near: float = 25.0, within: float = 3.0) -> dict[tuple[int, str], list[int]]:
    """(degrees off the decider's body, 30 a band; "under 10 m" | "10-20 m" | "20 m or more" from him)
    -> [opponents truly within ``near`` of the ball, of them not believed within ``within``], decisions in play."""
    body = bodies(match, game(match, team)[1])
    out: dict[tuple[int, str], list[int]] = defaultdict(lambda: [0, 0])
    for a in aimed(match, team):
        me = body.get((a.time, a.number))
        if a.mode != "play_on" or me is None:
            continue
        for (x, y), ours in a.theirs:
            if math.dist(ours, a.ball) > near:
                continue
            off = abs(math.remainder(math.degrees(math.atan2(y - me.y, x - me.x)) - me.body, 360.0))
            d = math.hypot(x - me.x, y - me.y)
            key = (min(int(off // 30) * 30, 150), "under 10 m" if d < 10 else "10-20 m" if d < 20 else "20 m or more")
            out[key][0] += 1
            out[key][1] += all(math.dist(ours, b) > within for b in a.believed)
    return out


def body_table(rows: dict[tuple[int, str], list[int]], within: float) -> str:
    bands = ("under 10 m", "10-20 m", "20 m or more")
    lines = [
        "| off his body (degrees) | " + " | ".join(f"{b}: not believed within {within:g} m" for b in bands) + " |",
        "|---|" + "---:|" * len(bands),
    ]
    for sector in range(0, 180, 30):
        cells = []
        for band in bands:
            n, missed = rows.get((sector, band), (0, 0))
            cells.append(f"{missed} of {n} ({missed / n:.0%})" if n else "-")
        lines.append(f"| {sector}-{sector + 30} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def table(rows: dict[str, list[int]], near: float, within: float) -> str:
    lines = [
        f"| reason | decisions | opponents within {near:g} m of the ball | not believed within {within:g} m | share |",
        "|---|---:|---:|---:|---:|",
    ]
    for why, (n, close, missed) in sorted(rows.items(), key=lambda kv: -kv[1][0]):
        lines.append(f"| {why} | {n} | {close} | {missed} | {missed / close if close else 0.0:.0%} |")
    return "\n".join(lines)


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--near", type=float, default=25.0, help="m from the ball: the opponents counted")
    ap.add_argument("--within", type=float, default=3.0, help="m: believed this close to the truth counts as known")
    ap.add_argument("--by-body", action="store_true", help="by where they stood from the decider's body instead")
    args = ap.parse_args()
    if args.by_body:
        around: dict[tuple[int, str], list[int]] = defaultdict(lambda: [0, 0])
        for match in args.matches:
            for key, row in by_body(match, args.team, args.near, args.within).items():
                around[key] = [a + b for a, b in zip(around[key], row, strict=True)]
        print(body_table(around, args.within))
        return 0
    total: dict[str, list[int]] = defaultdict(lambda: [0, 0, 0])
    for match in args.matches:
        for why, row in picture(match, args.team, args.near, args.within).items():
            total[why] = [a + b for a, b in zip(total[why], row, strict=True)]
    print(table(total, args.near, args.within))
    return 0


if __name__ == "__main__":
    sys.exit(main())
