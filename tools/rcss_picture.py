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
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, game_log, match_parser, reason
from rcss_series import player_words

_AIMED = re.compile(r"\[(\w+?)_(\d+)_decision\]: t=(\d+) \w+: (.*?) @ target \S+ \S+ ball \S+ \S+ opp ?(.*)")


def picture(match: Path, team: str = "CF", near: float = 25.0, within: float = 3.0) -> dict[str, list[int]]:
    """Reason -> [decisions, opponents truly within ``near`` of the ball, of them not believed within ``within``]."""
    frames, side, forward = game(match, team)
    at = {frame[0]: frame for frame in frames}
    out: dict[str, list[int]] = defaultdict(lambda: [0, 0, 0])
    for log in sorted(match.glob(f"logs-{team}/*.log")):
        for line in log.read_text(errors="replace").splitlines():
            m = _AIMED.search(line)
            if not m or m.group(1) != team or int(m.group(3)) not in at:
                continue
            _, mode, ball, players = at[int(m.group(3))]
            why = reason(m.group(4))
            if mode != "play_on" and not why.startswith("set piece"):
                continue
            believed = [tuple(map(float, entry.split()[:2])) for entry in m.group(5).split(",") if entry.strip()]
            # The game log's frame into ours: x towards their goal, y mirrored as the decision's own frame is.
            ball_ours = (forward * ball[0], -forward * ball[1])
            truth = [(forward * x, -forward * y) for s, _, x, y, _ in players if s != side]
            close = [p for p in truth if math.dist(p, ball_ours) <= near]
            row = out[why]
            row[0] += 1
            row[1] += len(close)
            row[2] += sum(1 for p in close if all(math.dist(p, b) > within for b in believed))
    return out


def bodies(match: Path, side: str) -> dict[tuple[int, int], tuple[float, float, float]]:
    """(time, number) -> (x, y, body direction in degrees) of each of ``side``'s players, from the game log."""
    out = {}
    for line in game_log(match).read_text(errors="replace").splitlines():
        if line.startswith("(show "):
            head, _, rest = line.partition(" ((b) ")
            t = int(head.split()[1])
            for w in player_words(rest):
                if w[0] == side and len(w) >= 9:
                    out[(t, int(w[1]))] = (float(w[4]), float(w[5]), float(w[8]))
    return out


def by_body(match: Path, team: str = "CF", near: float = 25.0, within: float = 3.0) -> dict[tuple[int, str], list[int]]:
    """(degrees off the decider's body, 30 a band; "under 10 m" | "10-20 m" | "20 m or more" from him)
    -> [opponents truly within ``near`` of the ball, of them not believed within ``within``], decisions in play."""
    frames, side, forward = game(match, team)
    at = {frame[0]: frame for frame in frames}
    body = bodies(match, side)
    out: dict[tuple[int, str], list[int]] = defaultdict(lambda: [0, 0])
    for log in sorted(match.glob(f"logs-{team}/*.log")):
        for line in log.read_text(errors="replace").splitlines():
            m = _AIMED.search(line)
            if not m or m.group(1) != team or int(m.group(3)) not in at:
                continue
            t, number = int(m.group(3)), int(m.group(2))
            _, mode, ball, players = at[t]
            me = body.get((t, number))
            if mode != "play_on" or me is None:
                continue
            believed = [tuple(map(float, entry.split()[:2])) for entry in m.group(5).split(",") if entry.strip()]
            ball_ours = (forward * ball[0], -forward * ball[1])
            for s, _, x, y, _ in players:
                ours = (forward * x, -forward * y)
                if s == side or math.dist(ours, ball_ours) > near:
                    continue
                off = abs(math.remainder(math.degrees(math.atan2(y - me[1], x - me[0])) - me[2], 360.0))
                d = math.dist((x, y), me[:2])
                key = (
                    min(int(off // 30) * 30, 150),
                    "under 10 m" if d < 10 else "10-20 m" if d < 20 else "20 m or more",
                )
                out[key][0] += 1
                out[key][1] += all(math.dist(ours, b) > within for b in believed)
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
