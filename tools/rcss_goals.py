"""Every goal of our matches on rcssserver: who scored, from where, and how the attack came about.

    python tools/rcss_goals.py MATCH_DIR [MATCH_DIR ...] [--team CF]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``). For each goal the game log (``*.rcg``) tells:

- the shot: the scoring side's last kick before the referee's ``goal_l``/``goal_r``, where the
  ball was when it was kicked (the scorers' own frame: x towards the goal they attack) and how far
  that is from the goal's centre; a later touch by the side that conceded (a block, the
  goalkeeper's parry, an own goal) is named;
- the conceding goalkeeper (the player the server flags as one, else number 1): how far he stood
  from his goal's centre when the shot was kicked;
- the move: the scorers' kicks since the other side last kicked the ball (or since the kick-off),
  how many cycles it took, and where it began: at a set piece of theirs (``corner_kick``, ...),
  else where they won the ball, by third of the field seen from the scorers (``own``, ``middle``,
  ``attacking``).

A second table sums the goals for us and against us. This is how docs/performance.md counts
where and how goals are conceded.
"""

from __future__ import annotations

import math
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, match_parser
from rcss_series import GOAL_X, kick_events, third_of

GOALIE = 0x8  # a player's state bit in the game log: he is his team's goalkeeper
THIRDS = ("own", "middle", "attacking")  # seen from the side whose frame x is in
NEAR, BOX = 11.0, 16.5  # m from the goal's centre: about the penalty spot; the penalty area's depth


@dataclass(frozen=True)
class Goal:
    match: str
    time: int
    ours: bool  # scored by us
    scorer: int
    shot: tuple[float, float]  # the ball when the shot was kicked, the scorers' frame
    distance: float  # m from the goal's centre
    touched: str  # "" or who of the conceding side touched the ball after the shot ("keeper 1", "5")
    keeper_off: float | None  # m the conceding goalkeeper stood from his goal's centre (None: not in the log)
    kicks: int  # the scorers' kicks in the move, the shot included
    cycles: int  # from the move's first kick to the goal
    began: str  # a set piece's play mode, or "won in the own/middle/attacking third"


def goals(match: Path, team: str = "CF") -> list[Goal]:
    """The goals of one match, in order."""
    frames, our_side, _ = game(match, team, counters=True)
    events = kick_events(frames)
    out, kick_off, before = [], 0, None
    for i, (_, mode, _, _) in enumerate(frames):
        if mode != before and mode.startswith("kick_off"):
            kick_off = i  # a goal's move never starts before the last kick-off
        if mode != before and mode in ("goal_l", "goal_r"):
            kicks = [e for e in events if kick_off <= e[0] <= i]
            goal = _goal(f"{match.parent.name}/{match.name}", frames, i, kicks, mode[-1], our_side)
            if goal is not None:
                out.append(goal)
        before = mode
    return out


def _goal(name: str, frames: list, at: int, kicks: list, side: str, our_side: str) -> Goal | None:
    """The goal ``side`` scored at frame ``at`` after ``kicks`` (those since the kick-off, in order)."""
    fwd = 1.0 if side == "l" else -1.0
    ours = [k for k in kicks if k[1] == side]
    if not ours:
        return None  # an own goal with no kick of the scorers since the kick-off: nothing to tell
    shot = ours[-1]
    theirs = [k for k in kicks if k[1] != side]
    lost = [k for k in theirs if k[0] < shot[0]]  # the other side's kicks before the shot
    move = [k for k in ours if not lost or k[0] > lost[-1][0]]
    j = max(1, shot[0])
    ball = frames[j - 1][2]  # the frame shows the ball after the kick: it was kicked from here
    defenders = [p for p in frames[j - 1][3] if p[0] != side]
    # The server flags the player who connected as the goalkeeper; Pyrus2D's does not connect as one.
    keeper = next((p for p in defenders if p[6] & GOALIE), next((p for p in defenders if p[1] == 1), None))
    after = [k for k in theirs if k[0] > shot[0]]
    touched = ""
    if after:
        toucher = after[-1][2]
        touched = f"keeper {toucher}" if keeper is not None and keeper[1] == toucher else str(toucher)
    first = max(1, move[0][0])
    start_mode = frames[first - 1][1]
    if start_mode == "play_on":
        began = f"won in the {THIRDS[third_of(fwd * frames[first - 1][2][0])]} third"
    else:
        began = start_mode.removesuffix(f"_{side}")
    return Goal(
        match=name,
        time=frames[at][0],
        ours=side == our_side,
        scorer=shot[2],
        shot=(fwd * ball[0], fwd * ball[1]),
        distance=math.hypot(GOAL_X - fwd * ball[0], ball[1]),
        touched=touched,
        keeper_off=None if keeper is None else math.hypot(fwd * GOAL_X - keeper[2], keeper[3]),
        kicks=len(move),
        cycles=frames[at][0] - frames[first][0] + 1,
        began=began,
    )


def goal_rows(found: list[Goal]) -> str:
    """One row per goal."""
    rows = [
        "| match | time | for | scorer | shot from (x, y) | distance | touched after | keeper off his goal "
        "| kicks in the move | cycles | began |",
        "|---|---:|---|---:|---|---:|---|---:|---:|---:|---|",
    ]
    for g in found:
        keeper = "?" if g.keeper_off is None else f"{g.keeper_off:.1f}"
        rows.append(
            f"| {g.match} | {g.time} | {'us' if g.ours else 'them'} | {g.scorer} | {g.shot[0]:.1f}, {g.shot[1]:.1f} "
            f"| {g.distance:.1f} | {g.touched or '-'} | {keeper} | {g.kicks} | {g.cycles} | {g.began} |"
        )
    return "\n".join(rows)


def summary(found: list[Goal]) -> str:
    """The goals for us and against us: how far out, how the move began, how long it was."""
    rows = [
        f"| goals | n | shot from < {NEAR:.0f} m | {NEAR:.0f}-{BOX} m | > {BOX} m | after a set piece "
        "| won in the attacking third | middle third | own third | kicks in the move (median) | cycles (median) |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for label, ours in (("for us", True), ("against us", False)):
        gs = [g for g in found if g.ours is ours]
        if not gs:
            rows.append(f"| {label} | 0 |" + " |" * 9)
            continue
        near = sum(g.distance < NEAR for g in gs)
        far = sum(g.distance > BOX for g in gs)
        won = [sum(g.began == f"won in the {t} third" for g in gs) for t in reversed(THIRDS)]
        set_piece = len(gs) - sum(won)
        rows.append(
            f"| {label} | {len(gs)} | {near} | {len(gs) - near - far} | {far} | {set_piece} | {won[0]} | {won[1]} "
            f"| {won[2]} | {statistics.median(g.kicks for g in gs):g} | {statistics.median(g.cycles for g in gs):g} |"
        )
    return "\n".join(rows)


def main() -> int:
    args = match_parser(__doc__).parse_args()
    found = [g for match in args.matches for g in goals(match, args.team)]
    print(goal_rows(found))
    print()
    print(summary(found))
    return 0


if __name__ == "__main__":
    sys.exit(main())
