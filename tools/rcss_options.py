"""What the game log's truth offered our player on the ball: the furthest up a kicked ball reaches a team-mate first.

    python tools/rcss_options.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--speed 2.7] [--margin 2]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``); only its game log (``*.rcg``) is read. For each kick of ours in play, the decision's
reach model (``cf_decision.reach``) is run on the truth of that cycle: a ball kicked at ``--speed``
(m/cycle) every 5 degrees all round, stopped where it leaves the field, and everyone where he stood,
at the default type's top speed. The kick's option is the furthest up the field such a ball is
received by a team-mate ``--margin`` cycles or more before any opponent could have it; its gain is
that point's x minus the ball's. One row per third of the field the kick was made in: how many
kicks had no such ball at all, and how many had one gaining less than 0, 0-10, 10-20 and 20 m or
more. It tells whether the team lacked options or chose badly among them (docs/performance.md).
"""

from __future__ import annotations

import math
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, match_parser
from rcss_series import kick_events, third_of

from cf_decision import reach
from cf_sim_backend.embedded.rcg import GOALIE  # the game log's player state bit of a goalkeeper

THIRDS = ("our third", "middle third", "their third")
GAINS = ("none", "< 0 m", "0-10 m", "10-20 m", "20 m or more")


def best_gain(
    ball: tuple[float, float],
    mates: list[tuple[float, float]],
    opponents: list[reach.Runner],
    speed: float,
    margin: int,
) -> float | None:
    """The most metres up the field a ball kicked from ``ball`` at ``speed`` gains to a team-mate
    ``margin`` cycles before any opponent (None: no such ball)."""
    ours, best = [reach.Runner(p) for p in mates], None
    for degrees in range(-180, 180, 5):
        heading = math.radians(degrees)
        path = reach.in_field(
            reach.kicked_path(ball, (ball[0] + math.cos(heading), ball[1] + math.sin(heading)), speed)
        )
        mine, theirs = reach.first_cycles(path, ours), reach.first_cycles(path, opponents)
        if mine is None or (theirs is not None and theirs - mine < margin):
            continue
        gain = path[mine - 1][0] - ball[0]
        best = gain if best is None else max(best, gain)
    return best


def bin_of(gain: float | None) -> str:
    if gain is None:
        return GAINS[0]
    return GAINS[1] if gain < 0 else GAINS[2] if gain < 10 else GAINS[3] if gain < 20 else GAINS[4]


def options(match: Path, team: str = "CF", speed: float = 2.7, margin: int = 2) -> Counter:
    """(third, gain bin) -> kicks of ours in play, in one match (x in our attack's direction)."""
    frames, side, forward = game(match, team, counters=True)  # the state bits tell the goalkeeper
    out: Counter = Counter()
    for i, s, number, _, _ in kick_events(frames):
        _, mode, (bx, by), players = frames[i]
        if s != side or mode != "play_on":
            continue
        ball = (forward * bx, forward * by)
        mates = [(forward * p[2], forward * p[3]) for p in players if p[0] == side and p[1] != number]
        opponents = [
            reach.Runner((forward * p[2], forward * p[3]), bool(p[6] & GOALIE)) for p in players if p[0] != side
        ]
        third = THIRDS[third_of(ball[0])]
        out[(third, bin_of(best_gain(ball, mates, opponents, speed, margin)))] += 1
    return out


def table(counts: Counter) -> str:
    rows = ["| where the ball was | kicks | " + " | ".join(GAINS) + " |", "|---|---:|" + "---:|" * len(GAINS)]
    for third in THIRDS:
        n = sum(counts[(third, g)] for g in GAINS)
        if n:
            rows.append(f"| {third} | {n} | " + " | ".join(str(counts[(third, g)]) for g in GAINS) + " |")
    return "\n".join(rows)


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--speed", type=float, default=2.7, help="m/cycle the ball leaves the foot with")
    ap.add_argument("--margin", type=int, default=2, help="cycles a team-mate must be first by")
    args = ap.parse_args()
    total: Counter = Counter()
    for match in args.matches:
        total += options(match, args.team, args.speed, args.margin)
    print(table(total))
    return 0


if __name__ == "__main__":
    sys.exit(main())
