"""What came of our set pieces on rcssserver: how hard the taker kicked, and how long and how far we kept it.

    python tools/rcss_set_pieces.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--window 150]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``); only its game log (``*.rcg``) is read. For each of our set pieces (kick-off, kick-in,
free kick, corner, goal kick, ...) that ended in a kick: the ball's speed in the cycle after the
kick (a still ball, so what the kick gave it; 2.7 m/cycle is the most), the taker's distance from
the ball then, the cycles until an opponent first kicked it (at most ``--window``), the furthest
point up the field the ball reached while we had it, whether that was in their third, and how
many players of each side stood within ``NEAR`` of the ball when an opponent first touched it (was
our man on the ball alone?). One row per kind of set piece, medians over the kicks. This is how
docs/performance.md counts the kick-offs.
"""

from __future__ import annotations

import math
import statistics
import sys
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game_log, match_parser
from rcss_series import THIRD, read_rcg, side_of

NEAR = 10.0  # m from the ball: the players counted round it when they first touched it
KINDS = ("kick_off", "kick_in", "corner_kick", "goal_kick", "free_kick", "indirect_free_kick")


@dataclass(frozen=True)
class SetPiece:
    kind: str
    time: int
    speed: float  # m/cycle the ball left with
    taker_gap: float  # m from the taker to the ball as he kicked
    theirs_after: int | None  # cycles until an opponent kicked it; None: not within the window
    furthest: float  # m up the field (our frame) the ball reached while ours
    near_at_loss: tuple[int, int] | None  # ours, theirs within NEAR of the ball at their first touch; None: no touch


def kind_of(mode: str, side: str) -> str | None:
    """The kind of our set piece a play mode is (``kick_in_l`` for the left team: ``kick_in``), else None."""
    if not mode.endswith("_" + side):
        return None
    kind = mode[: -len(side) - 1]
    return kind if kind in KINDS else None


def set_pieces(rcg: Path, team: str = "CF", window: int = 150) -> list[SetPiece]:
    """Our set pieces in one game log that ended in a kick of ours."""
    frames, side = read_rcg(rcg), side_of(rcg, team)
    forward = 1.0 if side == "l" else -1.0
    out = []
    for i in range(1, len(frames)):
        (_, mode, ball, players), (t, now, after, moved) = frames[i - 1], frames[i]
        kind = kind_of(mode, side)
        if kind is None or now != "play_on":
            continue
        kicks = {(p[0], p[1]): p[4] for p in players}
        kicker = [p for p in moved if p[0] == side and p[4] > kicks.get((p[0], p[1]), p[4])]
        if not kicker:
            continue  # the mode ended some other way (a drop ball, the goalkeeper's move)
        taker = next(p for p in players if (p[0], p[1]) == (kicker[0][0], kicker[0][1]))  # where he kicked from
        theirs, furthest, last, near = None, forward * ball[0], kicks, None
        for t2, mode2, ball2, players2 in frames[i : i + window]:
            if mode2 != "play_on" and t2 > t:
                break
            if any(p[0] != side and p[4] > last.get((p[0], p[1]), p[4]) for p in players2):
                theirs = t2 - t
                close = [p[0] == side for p in players2 if math.dist((p[2], p[3]), ball2) <= NEAR]
                near = (sum(close), len(close) - sum(close))
                break
            furthest = max(furthest, forward * ball2[0])
            last = {(p[0], p[1]): p[4] for p in players2}
        gap = math.dist((taker[2], taker[3]), ball)
        out.append(SetPiece(kind, t, math.dist(ball, after), gap, theirs, furthest, near))
    return out


def table(pieces: list[SetPiece], window: int) -> str:
    rows = [
        "| our set piece | kicks | ball speed off the kick (m/cycle, median) | taker's distance (m, median) "
        f"| cycles until their first touch (median; {window}: none) | furthest up the field while ours (m, median) "
        f"| reached their third | ours : theirs within {NEAR:g} m at their first touch (median) |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    by_kind: dict[str, list[SetPiece]] = defaultdict(list)
    for p in pieces:
        by_kind[p.kind].append(p)
    for kind, ps in sorted(by_kind.items(), key=lambda kv: -len(kv[1])):
        lost = [p.near_at_loss for p in ps if p.near_at_loss is not None]
        near = f"{statistics.median(n[0] for n in lost):g} : {statistics.median(n[1] for n in lost):g}" if lost else "-"
        rows.append(
            f"| {kind} | {len(ps)} | {statistics.median(p.speed for p in ps):.2f} "
            f"| {statistics.median(p.taker_gap for p in ps):.2f} "
            f"| {statistics.median(window if p.theirs_after is None else p.theirs_after for p in ps):g} "
            f"| {statistics.median(p.furthest for p in ps):.1f} | {sum(p.furthest > THIRD for p in ps)} | {near} |"
        )
    return "\n".join(rows)


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--window", type=int, default=150, help="cycles after the kick that are followed")
    args = ap.parse_args()
    pieces = []
    for match in args.matches:
        try:
            rcg = game_log(match)
        except FileNotFoundError as exc:
            print(exc, file=sys.stderr)
            return 2
        pieces += set_pieces(rcg, args.team, args.window)
    print(table(pieces, args.window) if pieces else "no set piece of ours ended in a kick")
    return 0


if __name__ == "__main__":
    sys.exit(main())
