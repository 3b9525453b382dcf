"""What a decision reads from a WorldState (ROS-free): positions, the play mode, who is where,
whose ball it is; and the Decision it makes. Positions are in the player's own frame (x towards
the opponents' goal), in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_lang.ontology import FIELD, AbsolutePositioning, Player, PlayMode, Team, WorldState

from . import reach
from .reach import Runner, top_speed

FIELD_HALF_LENGTH = FIELD.half_length
GOAL = (FIELD_HALF_LENGTH, 0.0)
OWN_GOAL = (-FIELD_HALF_LENGTH, 0.0)
KICKABLE = 1.005  # m: a ball rcssserver's see shows at 1.0 m is surely kickable (the back-ends' skills kick it)
KEEPER_OUT_SHARE = 0.25  # a goalkeeper stands this share of the ball's distance out of his goal,
KEEPER_OUT_MAX = 6.0  # m: at most this far
# m a cycle: an opponent not seen may have moved this far from where he was (the rcss belief's doubt
# growth for unseen men); a position a team-mate told grows as unsure (shared.py)
UNSEEN_DRIFT = 0.4
UNSURE_MAX = 3.0  # m: ... up to this: the reach the reach model adds for it
ONSIDE_SLACK = 0.5  # m: a team-mate this little beyond their line at the kick counts as onside (belief noise)


@dataclass(frozen=True)
class Decision:
    """What the player does now: the ``(exec Player <method> ...)`` method, its action, and why (logged)."""

    method: str
    action: object  # an ontology action model
    why: str


def xy(pos: AbsolutePositioning | None) -> tuple[float, float] | None:
    """A positioning as an (x, y) pair."""
    return (pos.x, pos.y) if pos is not None else None


def play_mode(state: WorldState) -> PlayMode:
    """The play mode in ``state`` (play on if it says none)."""
    return state.game.play_mode if state.game else PlayMode.PLAY_ON


def dist(a: tuple[float, float], b: tuple[float, float]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def point(x: float, y: float) -> AbsolutePositioning:
    """An action's target, kept within a few metres of the field."""
    return AbsolutePositioning(x=max(-60.0, min(60.0, x)), y=max(-40.0, min(40.0, y)))


def ball_ahead(state: WorldState, cycles: int) -> WorldState:
    """``state`` with the ball where it will be after ``cycles`` cycles, rolling on as it will then."""
    ball = state.ball
    if cycles <= 0 or ball.velocity is None:
        return state
    x, y = reach.ball_path(xy(ball.positioning), reach.per_cycle(ball.velocity), cycles)[-1]
    slow = reach.BALL_DECAY**cycles
    velocity = ball.velocity.model_copy(update={"vx": ball.velocity.vx * slow, "vy": ball.velocity.vy * slow})
    moved = ball.model_copy(
        update={"positioning": ball.positioning.model_copy(update={"x": x, "y": y}), "velocity": velocity}
    )
    return state.model_copy(update={"ball": moved})


def sides(state: WorldState) -> tuple[list[tuple[int, Runner]], list[Runner]]:
    """Team-mates (number, as a runner) other than me, and opponents (as runners)."""
    mates, opponents = [], []
    me = state.me.player_number if state.me else None
    for p in state.players:
        if p.positioning is None:
            continue
        if p.which_team is Team.OUR and p.player_number not in (None, me):
            mates.append((p.player_number, Runner(xy(p.positioning), False, top_speed(p))))
        elif p.which_team is Team.OPP:
            opponents.append(Runner(xy(p.positioning), bool(p.is_goalie), top_speed(p), unsure(p)))
    return mates, opponents


def unsure(player: Player) -> float:
    """How far from where he was last seen an opponent may be by now: UNSEEN_DRIFT a cycle since,
    up to UNSURE_MAX.

    A pass is judged on the opponents as believed; against HELIOS base about a third of those near
    the ball were not believed within 3 m of where they stood when our player passed in our half
    (tools/rcss_picture.py, session 62).
    """
    return min(UNSURE_MAX, UNSEEN_DRIFT * (player.age or 0))


def nearest_of_each_side(state: WorldState, at: tuple[float, float], fresh: int | None = None) -> dict[Team, float]:
    """How far each side's nearest player is from ``at`` (only those seen within ``fresh`` cycles, if given)."""
    nearest: dict[Team, float] = {}
    for p in state.players:
        if p.positioning is None or p.which_team is None or (fresh is not None and (p.age or 0) > fresh):
            continue
        d = dist(xy(p.positioning), at)
        nearest[p.which_team] = min(d, nearest.get(p.which_team, d))
    return nearest


def opponent_on_ball(state: WorldState, ball: tuple[float, float]) -> bool:
    """An opponent has the ball at his feet (within 2 m)."""
    return any(
        p.which_team is Team.OPP and p.positioning is not None and dist(xy(p.positioning), ball) < 2.0
        for p in state.players
    )


def their_ball(state: WorldState, ball: tuple[float, float]) -> bool:
    """The ball is the opponents': one has it at his feet (within 2 m, nearer than any of us), or
    one gets to it, rolling as it does, sooner than any of us (reach model; ties are ours).

    Who stood nearest the ball changed two or three times along an opponent's pass (the passer,
    whoever it rolled by, the receiver), and each change switched the defenders between marking
    and holding, each switch a turn (docs/performance.md, session 29).
    """
    mates, opponents = sides(state)
    if not opponents:
        return False
    ours = [runner for _, runner in mates]
    if state.me and state.me.positioning:
        ours.append(Runner(xy(state.me.positioning), False, top_speed(state.me)))
    nearest_opp = min(dist(o.pos, ball) for o in opponents)
    if nearest_opp < 2.0 and nearest_opp <= min((dist(r.pos, ball) for r in ours), default=1e9):
        return True
    velocity = reach.per_cycle(state.ball.velocity if state.ball else None)
    path = [ball, *reach.ball_path(ball, velocity)]
    theirs, mine = reach.first_cycles(path, opponents, react=0), reach.first_cycles(path, ours, react=0)
    return theirs is not None and (mine is None or theirs < mine)


def our_ball(state: WorldState, ball: tuple[float, float]) -> bool:
    """A team-mate other than me has the ball at his feet (within 2 m), nearer it than any opponent."""
    ours = min((dist(xy(p.positioning), ball) for p in _others(state, Team.OUR)), default=1e9)
    theirs = min((dist(xy(p.positioning), ball) for p in _others(state, Team.OPP)), default=1e9)
    return ours < 2.0 and ours < theirs


def _others(state: WorldState, team: Team):
    me = state.me.player_number if state.me else None
    return (
        p
        for p in state.players
        if p.which_team is team and p.positioning and not (team is Team.OUR and p.player_number == me)
    )


def offside_line(state: WorldState, ball: tuple[float, float]) -> float | None:
    """The x beyond which our attackers are offside: the second-last opponent's, or the ball's if further.

    None while fewer than two opponents are known (the line cannot be told).
    """
    xs = sorted((p.positioning.x for p in state.players if p.which_team is Team.OPP and p.positioning), reverse=True)
    if len(xs) < 2:
        return None
    return max(xs[1], ball[0], 0.0)


def onside(x: float, line: float | None) -> bool:
    """Whether one of us at ``x`` may play a ball a team-mate kicks now, their offside line at
    ``line`` (:func:`offside_line`; None: unknown, so onside): not beyond it by more than ONSIDE_SLACK."""
    return line is None or x <= line + ONSIDE_SLACK


def offside_mates(state: WorldState, ball: tuple[float, float]) -> frozenset[int]:
    """The shirt numbers of us (me too) not :func:`onside`: none of them may play a ball a
    team-mate kicks now. The passer's choice of receiver and the receivers' choice of who meets a
    pass both leave them out, so the two agree."""
    line = offside_line(state, ball)
    ours = [p for p in (state.me, *state.players) if p is not None and p.which_team is Team.OUR]
    return frozenset(
        p.player_number
        for p in ours
        if p.player_number is not None and p.positioning and not onside(p.positioning.x, line)
    )


def guard_spot(ball: tuple[float, float]) -> tuple[float, float]:
    """Where the goalkeeper guards the goal: on the line that halves the angle the ball sees the
    goal mouth under, further out the further the ball (at the line a shot from 10 m passes him out
    of reach on either side).

    On the line to the goal's centre, with the ball by the goal line 16 m out he stood 1.2 m off a
    shot at the near post and 0.5 m off one at the far post: from that spot 27 of 86 of HELIOS
    base's goals were his to reach, from this one 50 (tools/rcss_keeper.py, session 53).
    """
    post, other = (OWN_GOAL[0], FIELD.goal_width / 2), (OWN_GOAL[0], -FIELD.goal_width / 2)
    # The halving line meets the goal line where it splits the mouth as the ball's distances to the posts.
    share = dist(ball, post) / (dist(ball, post) + dist(ball, other))
    aim = (OWN_GOAL[0], post[1] + (other[1] - post[1]) * share)
    out = max(2.0, min(KEEPER_OUT_MAX, KEEPER_OUT_SHARE * dist(ball, aim)))
    angle = math.atan2(ball[1] - aim[1], ball[0] - aim[0])
    return (aim[0] + out * math.cos(angle), aim[1] + out * math.sin(angle))
