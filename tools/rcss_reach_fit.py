"""How well the reach model foresees who gets the balls we kick: the kept share by the model's lead.

    python tools/rcss_reach_fit.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--react 1,2,3]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``). Each kick of ours in play that sends the ball off at MIN_SPEED or faster is replayed
with the decision's reach model (``cf_decision.reach``) on the game log's truth: the ball's true
path (its next frame gives the speed), everyone where he stood as it started to roll. The lead is
the first opponent's cycle at the ball minus the first team-mate's (team-mates set off after REACT
cycles, opponents after the model's TURN_CYCLES; none within the model's horizon: a lead of
HORIZON). The outcome is the next kick by anyone but the kicker: a team-mate's keeps the ball.
One row per REACT; a model that foresees well keeps few balls at a lead of 0 or less and nearly
all at 2 or more. This is how docs/performance.md judges the model the passes are chosen with.

A second table says how each lost kick was lost: an opponent kicked the ball in the same cycle
(both at it: the server adds the two kicks), or, by the nearest any team-mate came to the ball
before the opponents' kick, a team-mate had it in reach first, came within NEAR metres, or none did.

A third table says how soon receivers set off, for both teams: for each kick in play (either
side's) the receiver is the kicker's team-mate the model (react 1) puts first on the true path,
if he has SET_OFF_RUN metres or more to run to where it puts him; he sets off in the first cycle
he moves SET_OFF_STEP or more towards that point (never within SET_OFF_WITHIN cycles: "-").
"""

from __future__ import annotations

import itertools
import math
import sys
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, match_parser
from rcss_series import TOUCH_SPEED, kick_events

from cf_decision import reach
from cf_sim_backend.embedded.rcg import GOALIE  # the game log's player state bit of a goalkeeper
from cf_sim_backend.world import Params

MIN_SPEED = TOUCH_SPEED  # m/cycle: slower touches are a dribble's pushes, not kicks to anybody
KICKABLE = Params().kickable_distance  # m: rcssserver's, of the default player type
HORIZON = reach.HORIZON  # a lead is at most this many cycles either way
SET_OFF_RUN = 2.0  # m: a receiver nearer than this to the ball's path need not run
SET_OFF_STEP = 0.4  # m in one cycle towards where he meets the ball: he is on his way
SET_OFF_WITHIN = 8  # cycles after the kick looked at
BANDS = (("<= -3", -HORIZON, -3), ("-2..0", -2, 0), ("1", 1, 1), ("2..3", 2, 3), (">= 4", 4, HORIZON))


@dataclass(frozen=True)
class Kick:
    ball: tuple[float, float]
    velocity: tuple[float, float]
    mates: tuple[tuple[float, float], ...]  # the kicker left out
    opponents: tuple[tuple[tuple[float, float], bool], ...]  # (position, goalkeeper)
    kept: bool
    lost: str = ""  # how a lost kick was lost: one of LOSSES


def launched(frames: list, i: int) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """Where the ball kicked in frame ``i`` was and its first cycle's velocity, if it was kicked in
    play (and stayed in play) at MIN_SPEED or faster; else None."""
    if i + 1 >= len(frames) or frames[i][1] != "play_on" or frames[i + 1][1] != "play_on":
        return None
    ball, after = frames[i][2], frames[i + 1][2]
    velocity = (after[0] - ball[0], after[1] - ball[1])
    return (ball, velocity) if math.hypot(*velocity) >= MIN_SPEED else None


def kicks(match: Path, team: str = "CF") -> list[Kick]:
    """Our kicks in play of one match, each with the truth as it started to roll and its outcome."""
    frames, side, _ = game(match, team, counters=True)
    events = kick_events(frames)
    out = []
    for k, (i, s, number, _, _) in enumerate(events):
        start = launched(frames, i) if s == side else None
        if start is None:
            continue
        later = itertools.islice(events, k + 1, None)
        nxt = next(((i2, s2, n2) for i2, s2, n2, _, _ in later if (s2, n2) != (s, number)), None)
        if nxt is None:
            continue
        ball, velocity = start
        players = frames[i][3]
        mates = tuple((p[2], p[3]) for p in players if p[0] == side and p[1] != number)
        opponents = tuple(((p[2], p[3]), bool(p[6] & GOALIE)) for p in players if p[0] != side)
        kept = nxt[1] == side
        lost = "" if kept else loss(frames, i, nxt[0], side, number)
        out.append(Kick(ball, velocity, mates, opponents, kept, lost))
    return out


LOSSES = (
    "an opponent kicked it in the same cycle",  # both at the ball: the server adds the two kicks
    "a team-mate had it in reach first",
    "a team-mate came within 2 m, not in reach",
    "no team-mate came within 2 m",
)
NEAR = 2.0  # m: a team-mate this near the rolling ball, not in reach, nearly had it


def loss(frames: list, i: int, lost_at: int, side: str, kicker: int) -> str:
    """How the ball kicked in frame ``i`` was lost to the opponents' kick in frame ``lost_at``: the
    nearest any team-mate (the kicker left out) came to it meanwhile."""
    if lost_at <= i:
        return LOSSES[0]
    nearest = min(
        (
            math.dist((p[2], p[3]), frames[j][2][:2])
            for j in range(i + 1, lost_at + 1)
            for p in frames[j][3]
            if p[0] == side and p[1] != kicker
        ),
        default=math.inf,
    )
    return LOSSES[1] if nearest <= KICKABLE else LOSSES[2] if nearest <= NEAR else LOSSES[3]


def loss_table(all_kicks: list[Kick]) -> str:
    lost = Counter(k.lost for k in all_kicks if not k.kept)
    n = sum(lost.values())
    lines = ["| our lost kicks | kicks | share |", "|---|---:|---:|"]
    lines += [f"| {why} | {lost[why]} | {lost[why] / n:.0%} |" for why in LOSSES if n]
    return "\n".join(lines)


def lead(kick: Kick, react: int) -> int:
    """The model's lead of our first team-mate over their first man on the kick's true path."""
    path = reach.ball_path(kick.ball, kick.velocity)
    ours = reach.first_cycles(path, [reach.Runner(pos) for pos in kick.mates], react)
    theirs = reach.first_cycles(path, [reach.Runner(pos, goalie) for pos, goalie in kick.opponents])
    return (HORIZON if theirs is None else theirs) - (HORIZON if ours is None else ours)


def bands(all_kicks: list[Kick], react: int) -> list[tuple[int, int]]:
    """(kept, kicks) in each of BANDS of the lead."""
    out = [[0, 0] for _ in BANDS]
    for kick in all_kicks:
        n = lead(kick, react)
        row = next(j for j, (_, lo, hi) in enumerate(BANDS) if lo <= n <= hi)
        out[row][0] += kick.kept
        out[row][1] += 1
    return [(kept, n) for kept, n in out]


def table(all_kicks: list[Kick], reacts: list[int]) -> str:
    head = "| team-mates set off after | " + " | ".join(f"lead {name}" for name, _, _ in BANDS) + " |"
    lines = [head, "|---|" + "---:|" * len(BANDS)]
    for react in reacts:
        cells = [f"{kept}/{n} ({kept / n:.0%})" if n else "-" for kept, n in bands(all_kicks, react)]
        lines.append(f"| {react} cycle{'s' if react != 1 else ''} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def set_off(match: Path, team: str = "CF") -> dict[str, Counter]:
    """Cycles after each kick in play before its receiver set off, for "us" and "them" (None: not
    within SET_OFF_WITHIN cycles)."""
    frames, side, _ = game(match, team, counters=True)  # as kicks() reads them: one read per match
    out = {"us": Counter(), "them": Counter()}
    for i, s, number, _, _ in kick_events(frames):
        start = launched(frames, i) if i + SET_OFF_WITHIN < len(frames) else None
        if start is None:
            continue
        path = reach.ball_path(*start)
        firsts = [
            (n, p[1], (p[2], p[3]))
            for p in frames[i][3]
            if p[0] == s and p[1] != number and (n := reach.cycles_to_path((p[2], p[3]), path)) is not None
        ]
        if not firsts:
            continue
        n, receiver, start = min(firsts)
        meet = path[n - 1]
        run = math.dist(start, meet)
        if run < SET_OFF_RUN:
            continue
        way = ((meet[0] - start[0]) / run, (meet[1] - start[1]) / run)
        track = []
        for f in frames[i : i + SET_OFF_WITHIN + 1]:
            where = next(((p[2], p[3]) for p in f[3] if p[:2] == (s, receiver)), None)
            if where is None:
                break  # he is missing from the game log from here on (disconnected)
            track.append(where)
        lag = next(
            (
                j
                for j, (a, b) in enumerate(itertools.pairwise(track), start=1)
                if (b[0] - a[0]) * way[0] + (b[1] - a[1]) * way[1] >= SET_OFF_STEP
            ),
            None,
        )
        out["us" if s == side else "them"][lag] += 1
    return out


def set_off_table(lags: dict[str, Counter], team: str) -> str:
    cycles = [*range(1, SET_OFF_WITHIN + 1), None]
    lines = [
        "| receivers of | kicks | " + " | ".join(str(c) if c else "-" for c in cycles) + " |",
        "|---|---:|" + "---:|" * len(cycles),
    ]
    for who, name in (("us", team), ("them", "opponents")):
        n = sum(lags[who].values())
        cells = [f"{lags[who][c] / n:.0%}" if n else "-" for c in cycles]
        lines.append(f"| {name} | {n} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--react", default="1,2,3", help="comma-separated: cycles before a team-mate sets off")
    args = ap.parse_args()
    all_kicks, lags = [], {"us": Counter(), "them": Counter()}
    for match in args.matches:  # match by match: its game log is read once for both tables
        all_kicks += kicks(match, args.team)
        for who, counts in set_off(match, args.team).items():
            lags[who].update(counts)
    print(
        f"{len(all_kicks)} kicks of {args.team} in play at {MIN_SPEED:g} m/cycle or faster, "
        f"{sum(k.kept for k in all_kicks)} kept"
    )
    print(table(all_kicks, [int(v) for v in args.react.split(",")]))
    print("\nhow the lost ones were lost (the nearest a team-mate came to the ball before the opponents' kick)")
    print(loss_table(all_kicks))
    print(f"\ncycles after the kick before the receiver set off ({SET_OFF_STEP:g} m or more towards the ball's path)")
    print(set_off_table(lags, args.team))
    return 0


if __name__ == "__main__":
    sys.exit(main())
