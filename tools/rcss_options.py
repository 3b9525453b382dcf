"""What the game log's truth offered our player on the ball: the furthest up a kicked ball reaches a team-mate first.

    python tools/rcss_options.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--speed 2.7] [--margin 2]
    python tools/rcss_options.py MATCH_DIR [MATCH_DIR ...] --map "middle third" [--margin 1]
    python tools/rcss_options.py MATCH_DIR [MATCH_DIR ...] --line "middle third" [--margin 1]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``); only its game log (``*.rcg``) is read. For each kick of ours in play, the decision's
reach model (``cf_decision.reach``) is run on the truth of that cycle: a ball kicked at ``--speed``
(m/cycle) every 5 degrees all round, stopped where it leaves the field, and everyone where he stood,
at the default type's top speed. The kick's option is the furthest up the field such a ball is
received by a team-mate ``--margin`` cycles or more before any opponent could have it; its gain is
that point's x minus the ball's. One row per third of the field the kick was made in: how many
kicks had no such ball at all, and how many had one gaining less than 0, 0-10, 10-20 and 20 m or
more. It tells whether the team lacked options or chose badly among them (docs/performance.md).

``--map THIRD`` asks instead where a team-mate would have been found: for our kicks in play from
that third, on a 5 m grid of the field, each point's share of the kicks it was in range of (at
least 5 m up from the ball, 4-40 m from it; "-": never) at which a pass to a team-mate standing
still on it (kicked as the decision kicks a pass) reaches him ``--margin`` cycles or more before
any opponent could have it. Offside is not judged: a point beyond their second-last man is
open only to a runner who set off from onside. A map of low shares says no place to stand would
have helped much: the opponents covered the space.

``--line THIRD`` asks where along their last line a team-mate would have been found with a ball in
behind it: for our kicks in play from that third, in lanes 5 m apart across the field, a team-mate
standing LINE_SHORT onside of their offside line (their second-last man, or the ball if further up)
and a pass aimed LINE_LEADS ahead of him and LINE_SIDES to his side; the lane is open when such a
ball is first within his reach beyond the line, ``--margin`` cycles or more before any opponent
could have it. Beside it: how often one of ours stood on the line in that lane (within ON_LINE
onside of it and of the lane), and at how many kicks such a ball was there for him, from where he
stood. Open lanes where ours seldom stood say where a forward should wait; the last column says how
often a ball in behind was really on for the man who waited there.
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
from cf_lang.ontology import FIELD
from cf_sim_backend.embedded.rcg import GOALIE  # the game log's player state bit of a goalkeeper

THIRDS = ("our third", "middle third", "their third")
GRID_X = tuple(range(-50, 51, 5))  # the map's points (m, our attack's direction)
GRID_Y = tuple(range(-30, 31, 5))
GAINS = ("none", "< 0 m", "0-10 m", "10-20 m", "20 m or more")
LINE_SHORT = 0.5  # m onside of their line: where the team-mate of --line stands
LINE_LEADS = (5.0, 10.0, 15.0, 20.0)  # m ahead of him: where a ball in behind is aimed,
LINE_SIDES = (-6.0, -3.0, 0.0, 3.0, 6.0)  # m to his side: and this far across
ON_LINE = 2.5  # m: one of ours this near the lane and onside of their line by no more than this stood on it


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
    out: Counter = Counter()
    for third, ball, mates, opponents in our_kicks(match, team):
        out[(third, bin_of(best_gain(ball, mates, opponents, speed, margin)))] += 1
    return out


def our_kicks(match: Path, team: str = "CF"):
    """Each kick of ours in play in one match: its third, the ball, the kicker's team-mates and the
    opponents (as runners), all where they stood, x in our attack's direction."""
    frames, side, forward = game(match, team, counters=True)  # the state bits tell the goalkeeper
    for i, s, number, _, _ in kick_events(frames):
        _, mode, (bx, by), players = frames[i]
        if s != side or mode != "play_on":
            continue
        ball = (forward * bx, forward * by)
        mates = [(forward * p[2], forward * p[3]) for p in players if p[0] == side and p[1] != number]
        opponents = [
            reach.Runner((forward * p[2], forward * p[3]), bool(p[6] & GOALIE)) for p in players if p[0] != side
        ]
        yield THIRDS[third_of(ball[0])], ball, mates, opponents


def open_points(
    ball: tuple[float, float], opponents: list[reach.Runner], margin: int
) -> tuple[set[tuple[int, int]], set[tuple[int, int]]]:
    """The grid points in range of a pass from ``ball`` (at least 5 m up, 4-40 m away), and of them
    those where a team-mate standing still gets it (kicked as the decision kicks a pass)
    ``margin`` cycles before any opponent."""
    in_range, out = set(), set()
    for x in GRID_X:
        for y in GRID_Y:
            d = math.dist(ball, (x, y))
            if x < ball[0] + 5.0 or not 4.0 <= d <= 40.0:
                continue
            in_range.add((x, y))
            if received(ball, (x, y), (x, y), opponents, margin) is not None:
                out.add((x, y))
    return in_range, out


def received(
    ball: tuple[float, float],
    target: tuple[float, float],
    at: tuple[float, float],
    opponents: list[reach.Runner],
    margin: int,
) -> tuple[float, float] | None:
    """Where a team-mate standing at ``at`` first has a pass from ``ball`` aimed at ``target`` (kicked as
    the decision kicks a pass), if he has it ``margin`` cycles or more before any opponent could."""
    path = reach.in_field(reach.kicked_path(ball, target, reach.pass_speed(math.dist(ball, target))))
    mine = reach.first_cycles(path, [reach.Runner(at)])
    if mine is None:
        return None
    theirs = reach.first_cycles(path, opponents)
    return path[mine - 1] if theirs is None or theirs - mine >= margin else None


def open_map(match: Path, third: str, team: str = "CF", margin: int = 1) -> tuple[Counter, Counter]:
    """For our kicks in play from ``third`` in one match: at how many each grid point was in range,
    and at how many open."""
    in_range, seen = Counter(), Counter()
    for where, ball, _, opponents in our_kicks(match, team):
        if where != third:
            continue
        reachable, open_ = open_points(ball, opponents, margin)
        in_range.update(reachable)
        seen.update(open_)
    return in_range, seen


def offside_x(ball: tuple[float, float], opponents: list[reach.Runner]) -> float | None:
    """Their offside line: their second-last man's x, or the ball's (or the halfway line) if further up."""
    xs = sorted((o.pos[0] for o in opponents), reverse=True)
    return max(xs[1], ball[0], 0.0) if len(xs) >= 2 else None


def in_behind(
    ball: tuple[float, float], opponents: list[reach.Runner], line: float, me: tuple[float, float], margin: int
) -> bool:
    """Whether a team-mate standing at ``me`` (onside of ``line``) gets a ball in behind it: aimed
    LINE_LEADS ahead of him and LINE_SIDES across (kicked as the decision kicks a pass), first within
    his reach beyond the line, ``margin`` cycles or more before any opponent."""
    half_width = FIELD.width / 2 - 2.0
    for lead in LINE_LEADS:
        for side in LINE_SIDES:
            target = (min(FIELD.length / 2 - 3.0, me[0] + lead), max(-half_width, min(half_width, me[1] + side)))
            if not 4.0 <= math.dist(ball, target) <= 40.0:
                continue
            at = received(ball, target, me, opponents, margin)
            if at is not None and at[0] > line:
                return True
    return False


def line_lanes(match: Path, third: str, team: str = "CF", margin: int = 1) -> Counter:
    """For our kicks in play from ``third`` in one match, per lane y: ("kicks", y) how many had their line
    within 40 m of the lane's spot, ("open", y) at how many a ball in behind was there, ("ours", y) at
    how many one of ours stood on the line there, ("his", y) at how many a ball in behind was there for
    one of those who stood there, from where he stood (he is seldom LINE_SHORT onside)."""
    out: Counter = Counter()
    for where, ball, mates, opponents in our_kicks(match, team):
        line = offside_x(ball, opponents) if where == third else None
        if line is None:
            continue
        for y in GRID_Y:
            if math.dist(ball, (line, y)) > 40.0:
                continue
            out[("kicks", y)] += 1
            out[("open", y)] += in_behind(ball, opponents, line, (line - LINE_SHORT, y), margin)
            there = [(x, my) for x, my in mates if line - ON_LINE <= x <= line and abs(my - y) <= ON_LINE]
            out[("ours", y)] += bool(there)
            out[("his", y)] += any(in_behind(ball, opponents, line, me, margin) for me in there)
    return out


def line_table(lanes: Counter) -> str:
    """One row per lane, from y = +30 down: kicks, open share (%), ours-on-the-line share (%), and how
    many kicks had a ball in behind there for the one of ours who stood there."""
    rows = [
        "| lane y (m) | kicks | a ball in behind their line was there (%) | one of ours stood on the line there (%) "
        "| a ball in behind for him, from where he stood (kicks) |",
        "|---:|---:|---:|---:|---:|",
    ]
    for y in reversed(GRID_Y):
        n = lanes[("kicks", y)]
        if n:
            open_, ours = 100 * lanes[("open", y)] // n, 100 * lanes[("ours", y)] // n
            rows.append(f"| {y} | {n} | {open_} | {ours} | {lanes[('his', y)]} |")
    return "\n".join(rows)


def map_table(in_range: Counter, seen: Counter) -> str:
    """Each grid point's open share (%) of the kicks it was in range of, rows from y = +30 down."""
    rows = ["| y \\ x | " + " | ".join(str(x) for x in GRID_X) + " |", "|---:|" + "---:|" * len(GRID_X)]
    for y in reversed(GRID_Y):
        cells = (str(100 * seen[(x, y)] // in_range[(x, y)]) if in_range[(x, y)] else "-" for x in GRID_X)
        rows.append(f"| {y} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def table(counts: Counter) -> str:
    rows = ["| where the ball was | kicks | " + " | ".join(GAINS) + " |", "|---|---:|" + "---:|" * len(GAINS)]
    for third in THIRDS:
        n = sum(counts[(third, g)] for g in GAINS)
        if n:
            rows.append(f"| {third} | {n} | " + " | ".join(str(counts[(third, g)]) for g in GAINS) + " |")
    return "\n".join(rows)


def the(third: str) -> str:
    """ "our third", "the middle third", "their third"."""
    return third if third != "middle third" else "the middle third"


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--speed", type=float, default=2.7, help="m/cycle the ball leaves the foot with")
    ap.add_argument("--margin", type=int, default=2, help="cycles a team-mate must be first by")
    ap.add_argument("--map", choices=THIRDS, help="instead: where a team-mate standing would have been found")
    ap.add_argument("--line", choices=THIRDS, help="instead: where along their last line a ball in behind was there")
    args = ap.parse_args()
    if args.line:
        lanes: Counter = Counter()
        for match in args.matches:
            lanes += line_lanes(match, args.line, args.team, args.margin)
        print(f"Our kicks from {the(args.line)}: a team-mate on their last line, lane by lane")
        print(line_table(lanes))
        return 0
    if args.map:
        in_range, seen = Counter(), Counter()
        for match in args.matches:
            reachable, open_ = open_map(match, args.map, args.team, args.margin)
            in_range, seen = in_range + reachable, seen + open_
        print(
            f"Our kicks from {the(args.map)}: the share (%) of those in range at which a team-mate on the point was open"
        )
        print(map_table(in_range, seen))
        return 0
    total: Counter = Counter()
    for match in args.matches:
        total += options(match, args.team, args.speed, args.margin)
    print(table(total))
    return 0


if __name__ == "__main__":
    sys.exit(main())
