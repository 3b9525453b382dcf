"""How well our player on the ball knew where the opponents were: one table row per reason.

    python tools/rcss_picture.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--near 25] [--within 3]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``). A decision that aims the ball at a point logs the opponents it believed within 30 m
of the ball (``... @ target X Y ball X Y opp X Y S, ...``, our frame). Each such decision in play
(or at our set piece) is set against the game log's truth of that cycle: of the opponents truly
within ``--near`` metres of the ball, how many the decision had nowhere within ``--within`` metres
of where they stood. This is how docs/performance.md counts what the passer had not seen.
"""

from __future__ import annotations

import math
import re
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, match_parser, reason

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
    args = ap.parse_args()
    total: dict[str, list[int]] = defaultdict(lambda: [0, 0, 0])
    for match in args.matches:
        for why, row in picture(match, args.team, args.near, args.within).items():
            total[why] = [a + b for a, b in zip(total[why], row, strict=True)]
    print(table(total, args.near, args.within))
    return 0


if __name__ == "__main__":
    sys.exit(main())
