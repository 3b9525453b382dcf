"""How our goalkeeper stood at the opponents' shots on target: which of them were his to reach.

    python tools/rcss_keeper.py MATCH_DIR [MATCH_DIR ...] [--team CF]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``); only its game log (``*.rcg``) is read. A shot on target is an opponent's kick in play
from within SHOT_RANGE of our goal (the last of his touches in a row) whose ball, rolling on as it
left the foot, would cross our goal line between the posts. For each: could our goalkeeper have
been within his catch (``CATCH_REACH``, 1.2 m) of the ball before it crossed, moved as rcssserver moves a player
(``cf_sim_backend.intercept``: a dash at any angle off the body, or turns then dashes, from his
body and speed in the game log), setting off in the cycle the ball was first seen rolling, or a
cycle later; and from the spot the decision sends him to guard the goal
(``cf_decision.goalkeeper.guard_spot``, for the ball where it was kicked), standing there facing
the ball, setting off at once; and how far he stood from that spot. One row per match: it tells a
late goalkeeper, and one out of position, from shots nobody could stop (docs/performance.md).
"""

from __future__ import annotations

import dataclasses
import math
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, match_parser
from rcss_picture import bodies
from rcss_series import GOAL_X, kick_events

from cf_decision import reach
from cf_decision.goalkeeper import CATCH_REACH, guard_spot, into_our_goal
from cf_sim_backend import intercept
from cf_sim_backend.embedded.rcg import GOALIE  # the game log's player state bit of a goalkeeper
from cf_sim_backend.world import Params

SHOT_RANGE = 30.0  # m from our goal's centre: a kick from further is not counted as a shot
TOUCHES_APART = 2  # cycles: a kicker's touches this close together are one kick (the shot is the last)
SERVER = Params()  # rcssserver's default player type: dash, speed, decay, turn


@dataclass(frozen=True)
class Shot:
    time: int
    goal: bool  # a goal followed before anyone kicked the ball again (within twice its time to the line)
    reached: bool  # the goalkeeper could have had it from where he stood, setting off at once
    late: bool  # ... setting off a cycle later
    from_spot: bool  # ... from his guard spot, at once
    off_spot: float  # m he stood from it


def shots(match: Path, team: str = "CF") -> list[Shot]:
    """The opponents' shots on target at our goal in one match (x in our attack's direction)."""
    frames, side, forward = game(match, team, counters=True)
    events = kick_events(frames)
    body = bodies(match, side)
    out = []
    for k, (i, s, number, _, _) in enumerate(events):
        if s == side or not 1 <= i < len(frames) - 1 or frames[i][1] != "play_on":
            continue
        later = events[k + 1] if k + 1 < len(events) else None
        if later is not None and (later[1], later[2]) == (s, number) and later[0] - i <= TOUCHES_APART:
            continue  # not his last touch
        kicked = _ours(frames[i - 1][2], forward)
        ball, after = _ours(frames[i][2], forward), _ours(frames[i + 1][2], forward)
        if math.dist(kicked, (-GOAL_X, 0.0)) > SHOT_RANGE:
            continue
        path = reach.ball_path(ball, (after[0] - ball[0], after[1] - ball[1]))
        crossing = into_our_goal(path)
        if crossing is None:
            continue
        keeper = next((p[1] for p in frames[i][3] if p[0] == side and p[6] & GOALIE), None)
        him = body.get((frames[i][0], keeper))
        if him is None:
            continue
        at = _ours((him.x, him.y), forward)
        runner = intercept.Runner(*at, *_ours((him.vx, him.vy), forward), him.body + (0.0 if forward > 0 else 180.0))
        spot, before = guard_spot(kicked), path[:crossing]
        facing = math.degrees(math.atan2(kicked[1] - spot[1], kicked[0] - spot[0]))
        # A goal after anyone's next kick is that kick's.
        until = min(later[0] if later is not None else len(frames), i + 2 * crossing + 3)
        goal = any(f[1].startswith("goal_") for f in frames[i:until])
        out.append(
            Shot(
                time=frames[i][0],
                goal=goal,
                reached=catches(runner, before, 0),
                late=catches(runner, before, 1),
                from_spot=catches(intercept.Runner(*spot, 0.0, 0.0, facing), before, 0),
                off_spot=math.dist(at, spot),
            )
        )
    return out


def catches(keeper: intercept.Runner, path: list[tuple[float, float]], late: int) -> bool:
    """Whether ``keeper``, drifting ``late`` cycles before he sets off, can be within CATCH_REACH of a
    point of ``path`` (where the ball is after 1, 2, ... cycles) by the cycle the ball is there."""
    for _ in range(late):
        x, y, decay = keeper.x + keeper.vx, keeper.y + keeper.vy, SERVER.player_decay
        keeper = dataclasses.replace(keeper, x=x, y=y, vx=keeper.vx * decay, vy=keeper.vy * decay)
    return any(
        intercept.cycles_to(SERVER, keeper, x, y, CATCH_REACH, n - late) is not None
        for n, (x, y) in enumerate(path, start=1)
        if n > late
    )


def _ours(point: tuple[float, float], forward: float) -> tuple[float, float]:
    return (forward * point[0], forward * point[1])


def row(name: str, found: list[Shot]) -> str:
    """A table row: shots, goals, reachable as he stood (at once, a cycle late) and from his spot, his
    distance from it."""
    if not found:
        return f"| {name} | 0 | 0 | - | - | - | - |"
    off = sorted(s.off_spot for s in found)
    quartiles = statistics.quantiles(off, n=4, method="inclusive") if len(off) > 1 else [off[0]] * 3
    return (
        f"| {name} | {len(found)} | {sum(s.goal for s in found)} | {sum(s.reached for s in found)} "
        f"| {sum(s.late for s in found)} | {sum(s.from_spot for s in found)} | {quartiles[1]:.1f} ({quartiles[0]:.1f}-{quartiles[2]:.1f}) |"
    )


HEADER = (
    "| match | shots on target | goals | his to reach as he stood, setting off at once | a cycle late "
    "| from his guard spot, at once | m off his spot: median (quartiles) |\n|---|---:|---:|---:|---:|---:|---|"
)


def main() -> int:
    args = match_parser(__doc__).parse_args()
    print(HEADER)
    everything = []
    for match in args.matches:
        found = shots(match, args.team)
        everything += found
        print(row(f"{match.parent.name}/{match.name}", found))
    if len(args.matches) > 1:
        print(row("all", everything))
    return 0


if __name__ == "__main__":
    sys.exit(main())
