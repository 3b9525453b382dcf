"""Our shots, one by one: where each was aimed, how fast and how true the ball left the foot, where
it would cross their goal line, and what came of it.

    python tools/rcss_shots.py MATCH_DIR [MATCH_DIR ...] [--team CF]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``). A shot is a decision's ``shoot`` choice (the line ``t=T shoot: why @ target X Y ...``
every decision logs for a new way of playing the ball) and the kicks its player made from then on
(within WINDOW cycles, until anybody else kicked): the first touches, then the shot itself, the
last of them. From the game log (each side's frame is its own: x towards the other's goal): the
ball's speed as it left the foot, how far its way was off the aim, how wide the goal looked from
where it was kicked (the angle between the posts), where on their goal line that way would cross it
(the posts are at +-7.01 m), and what came next: a goal, their goalkeeper's
catch or kick ("keeper"), another of theirs ("blocked"), over their goal line ("wide", or
"corner" off one of theirs), ours again, or nothing within FOLLOW cycles. A choice that never
became a kick is counted apart (the ball was taken or went first). The totals split the shots by
distance (BANDS): against HELIOS base one shot from 20-25 m went in of forty-three, two from within
16 m of eight (docs/performance.md, session 67).
"""

from __future__ import annotations

import itertools
import math
import re
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, game_log, logged, match_parser
from rcss_belief_error import truth
from rcss_series import GOAL_X, kick_events

from cf_sim_backend.embedded.rcg import GOALIE  # the game log's player state bit of a goalkeeper
from cf_sim_backend.world import Params

WINDOW = 10  # cycles after the choice within which its kicks are looked for
FOLLOW = 60  # cycles after the shot within which what came of it is looked for
KEEPER_HOLDS = 2.0  # m: at a free kick for them, their goalkeeper this near the ball had caught it
POST_Y = Params().goal_width / 2  # m from the middle of the goal to a post
DECAY = Params().ball_decay  # the game log's ball velocity has decayed once since the kick
BANDS = (16.0, 20.0, 25.0)  # m from the goal's middle: the totals' distance bands
_CHOICE = re.compile(r"\[(\w+?)_(\d+)_decision\]: t=(\d+) shoot: (.*?) @ target (\S+) (\S+) ")


@dataclass(frozen=True)
class Shot:
    match: str
    time: int  # the cycle of the shot's kick
    number: int
    why: str  # the choice's reason, without "(the ball comes: N cycles)"
    touches: int  # kicks before the shot itself
    distance: float  # m from the middle of their goal, where the ball was kicked
    seen: float  # degrees between the posts, seen from there
    speed: float  # m/cycle as it left the foot
    off: float  # degrees its way was off the aim (+: to the left of it)
    cross: float | None  # m from the middle where its way crosses their goal line (None: it goes back)
    outcome: str


def choices(match: Path, team: str) -> list[tuple[int, int, str, float, float]]:
    """(cycle, shirt number, reason, aim x, aim y) of every shoot choice our decisions logged."""
    out = []
    for m in logged(match, team, _CHOICE):
        why = re.sub(r" \(the ball comes: \d+ cycles\)", "", m.group(4))
        out.append((int(m.group(3)), int(m.group(2)), why, float(m.group(5)), float(m.group(6))))
    return sorted(out)


def shots(match: Path, team: str = "CF") -> tuple[list[Shot], int]:
    """One match's shots, and how many shoot choices never became a kick."""
    frames, side, _ = game(match, team, counters=True)
    ball_now = truth(game_log(match), side)
    kicks = kick_events(frames)
    taken, shots_found, missed = set(), [], 0
    for t, number, why, aim_x, aim_y in choices(match, team):
        after = [k for k in kicks if t <= frames[k[0]][0] <= t + WINDOW]
        mine = []
        for k in after:  # his kicks until anybody else's
            if (k[1], k[2]) != (side, number):
                break
            mine.append(k)
        if not mine:
            missed += 1
            continue
        if mine[0][0] in taken:  # the same kicks, chosen again
            continue
        taken.update(k[0] for k in mine)
        i = mine[-1][0]
        x, y, *_ = ball_now[frames[i - 1][0]]  # where the ball was kicked
        _, _, vx, vy = ball_now[frames[i][0]]
        aim = math.atan2(aim_y - y, aim_x - x)
        off = math.degrees(math.remainder(math.atan2(vy, vx) - aim, math.tau))
        cross = y + vy / vx * (GOAL_X - x) if vx > 0.0 else None
        shots_found.append(
            Shot(
                f"{match.parent.name}/{match.name}",
                frames[i][0],
                number,
                why,
                len(mine) - 1,
                math.hypot(GOAL_X - x, y),
                goal_seen(x, y),
                math.hypot(vx, vy) / DECAY,
                off,
                cross,
                outcome(frames, i, side),
            )
        )
    return shots_found, missed


def goal_seen(x: float, y: float) -> float:
    """Degrees between their posts seen from (x, y) (their goal line at GOAL_X)."""
    left, right = (math.atan2(post - y, GOAL_X - x) for post in (POST_Y, -POST_Y))
    return math.degrees(abs(math.remainder(left - right, math.tau)))


def outcome(frames: list, i: int, side: str) -> str:
    """What came of the ball kicked in frame ``i`` (``read_rcg`` frames with counters)."""
    other = "r" if side == "l" else "l"
    last = {(p[0], p[1]): p[4] for p in frames[i][3]}
    for _, mode, ball, players in frames[i + 1 : i + 1 + FOLLOW]:
        if mode == f"goal_{side}":
            return "goal"
        if mode == f"goal_kick_{other}":
            return "wide"
        if mode == f"free_kick_{other}" and any(
            p[0] == other and keeper(p) and math.dist((p[2], p[3]), ball) <= KEEPER_HOLDS for p in players
        ):
            return "keeper"  # (rcssserver gives the side whose goalkeeper caught the ball a free kick)
        if mode == f"corner_kick_{side}":
            return "corner"
        if mode != "play_on":
            return mode
        for p in players:
            if p[4] > last.get((p[0], p[1]), p[4]):
                if p[0] == side:
                    return "ours again"
                return "keeper" if keeper(p) else "blocked"
    return "-"


def keeper(player: tuple) -> bool:
    """A goalkeeper (the game log's state bit), or shirt number 1: a team may play its goalkeeper
    without telling the server (Pyrus2D's had no goalkeeper's bit)."""
    return bool(player[6] & GOALIE) or player[1] == 1


def table(found: list[Shot], missed: int) -> list[str]:
    """The markdown rows: one per shot, then the totals."""
    rows = [
        "| match | cycle | player | why | touches first | from (m) | goal seen (deg) | speed (m/cycle) "
        "| off aim (deg) | crosses at (m) | came of it |",
        "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for s in found:
        cross = "-" if s.cross is None else f"{s.cross:+.1f}"
        rows.append(
            f"| {s.match} | {s.time} | {s.number} | {s.why} | {s.touches} | {s.distance:.1f} | {s.seen:.0f} "
            f"| {s.speed:.2f} "
            f"| {s.off:+.1f} | {cross} | {s.outcome} |"
        )
    if found:
        on = sum(s.cross is not None and abs(s.cross) < POST_Y for s in found)
        goals = sum(s.outcome == "goal" for s in found)
        speeds = statistics.median(s.speed for s in found)
        off = statistics.median(abs(s.off) for s in found)
        rows.append(
            f"\n{len(found)} shots ({missed} choices never kicked): {goals} goals, {on} on a way between the "
            f"posts; speed median {speeds:.2f} m/cycle, off aim median {off:.1f} degrees"
        )
        rows.append(by_distance(found))
    return rows


def by_distance(found: list[Shot]) -> str:
    """Shots and goals in each distance band, with the median angle the goal was seen under."""
    edges = (0.0, *BANDS, math.inf)
    parts = []
    for near, far in itertools.pairwise(edges):
        band = [s for s in found if near <= s.distance < far]
        if not band:
            continue
        seen = statistics.median(s.seen for s in band)
        goals = sum(s.outcome == "goal" for s in band)
        parts.append(f"{band_name(near, far)}: {len(band)} shots, {goals} goals (goal seen {seen:.0f} degrees, median)")
    return "by distance: " + "; ".join(parts)


def band_name(near: float, far: float) -> str:
    """A distance band's name in the totals: "within 16 m", "16-20 m", "beyond 25 m"."""
    if near == 0.0:
        return f"within {far:.0f} m"
    if far == math.inf:
        return f"beyond {near:.0f} m"
    return f"{near:.0f}-{far:.0f} m"


def main() -> int:
    args = match_parser(__doc__).parse_args()
    found, missed = [], 0
    for match in args.matches:
        here, not_kicked = shots(match, args.team)
        found.extend(here)
        missed += not_kicked
    if not found and not missed:
        print("no shoot choices in these matches' decision logs")
        return 1
    print("\n".join(table(found, missed)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
