"""The league-independent team policy: from a perceived WorldState to one action (ROS-free).

Input is only what the Framework Language carries (the player's own
WorldState, in its own frame: x towards the opponents' goal) and what
team-mates said (who goes for the ball). Output is an ontology action for
``(exec Player <method> ...)``. Nothing here knows the back-end.

What it does, in order:
- before a kick-off: take the formation position;
- goalkeeper: catch a ball in reach, clear a kickable ball, else guard the goal
  on the line between ball and goal centre;
- with the ball: shoot when close enough with a free line, else pass to the
  best open team-mate ahead, else (pressed in our own third) clear it long
  towards the wing, else dribble towards the goal;
- at our set piece the player with the ball passes (backwards if need be) or
  kicks long, never dribbles, and then leaves the ball to others until
  somebody else has touched it (the rules forbid the taker a second touch);
- the team-mate chosen to go for the ball (fastest to it; ties to the lower
  number) intercepts; in our half, when an opponent has the ball, the second
  fastest presses too; the others hold their formation position, shifted
  with the ball, facing the ball.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_lang.ontology import FIELD, AbsolutePositioning, Player, PlayMode, Team, WorldState
from cf_lang.ontology import actions as act

from .roles import Role, home_position, role_of

FIELD_HALF_LENGTH = FIELD.half_length
GOAL = (FIELD_HALF_LENGTH, 0.0)
OWN_GOAL = (-FIELD_HALF_LENGTH, 0.0)
KICKABLE = 1.0
SHOOT_RANGE = 22.0
PLAYER_SPEED = 0.8  # m per cycle, for time-to-ball estimates
CLAIM_MARGIN = 2  # cycles: someone must be this much faster to take the ball from the current claimer
OUR_SET_PIECES = frozenset(
    {
        PlayMode.KICK_OFF_OUR,
        PlayMode.KICK_IN_OUR,
        PlayMode.CORNER_KICK_OUR,
        PlayMode.GOAL_KICK_OUR,
        PlayMode.FREE_KICK_OUR,
    }
)
KICKING = frozenset({"shoot", "pass", "dribble", "kick"})
TOUCHED = 1.5  # m: another player this close to the ball has (or may have) touched it
TAKER_MEMORY = 100  # cycles after which a set piece's taker plays on as usual
NEVER = 10**6  # cycles to the ball of a player who may not touch it
CLEAR_LINE = -FIELD_HALF_LENGTH / 3  # behind it, a pressed player clears the ball instead of dribbling


@dataclass(frozen=True)
class Decision:
    method: str
    action: object  # an ontology action model
    why: str


def _xy(pos: AbsolutePositioning | None) -> tuple[float, float] | None:
    return (pos.x, pos.y) if pos is not None else None


def play_mode(state: WorldState) -> PlayMode:
    return state.game.play_mode if state.game else PlayMode.PLAY_ON


def _dist(a: tuple[float, float], b: tuple[float, float]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def _point(x: float, y: float) -> AbsolutePositioning:
    return AbsolutePositioning(x=max(-60.0, min(60.0, x)), y=max(-40.0, min(40.0, y)))


def cycles_to_ball(me: tuple[float, float], ball: tuple[float, float]) -> int:
    return int(max(0.0, _dist(me, ball) - KICKABLE) / PLAYER_SPEED)


def choose_interceptor(my_number: int, my_eta: int, claims: dict[int, int]) -> bool:
    """Whether I go for the ball, given team-mates' times to the ball (number -> cycles)."""
    best = min([(eta, n) for n, eta in claims.items() if n != my_number], default=None)
    if best is None:
        return True
    eta, number = best
    return my_eta + (0 if my_eta < eta else CLAIM_MARGIN) < eta or (my_eta == eta and my_number < number)


def win_the_ball(ball: tuple[float, float], why: str) -> Decision:
    """Go for a ball an opponent has and play it the moment it is in reach, in one request.

    Intercepting first and deciding then would give the opponent the cycles our decision and
    action need to see the ball at our feet: the action's kick skills approach the ball
    themselves. In our half: clear it long towards the wing; in theirs: take it towards the goal.
    """
    if ball[0] < 0.0:
        x = min(30.0, round((ball[0] + 35.0) / 10.0) * 10.0)  # on a 10 m grid: one request, not one a cycle
        target = _point(x, 25.0 if ball[1] >= 0 else -25.0)
        return Decision("pass", act.Pass(target=target, power=100.0), why + ": win it and clear it")
    target = _point(FIELD_HALF_LENGTH - 8.0, 0.0)
    return Decision("dribble", act.Dribble(target=target, speed=70.0), why + ": win it and go")


def second_fastest(my_number: int, my_eta: int, claims: dict[int, int]) -> bool:
    """Whether exactly one team-mate is faster to the ball than I am (ties to the lower number)."""
    ahead = sum(1 for n, eta in claims.items() if n != my_number and (eta, n) < (my_eta, my_number))
    return ahead == 1


def opponent_on_ball(state: WorldState, ball: tuple[float, float]) -> bool:
    """An opponent has the ball at his feet (within 2 m)."""
    return any(
        p.which_team is Team.OPP and p.positioning is not None and _dist(_xy(p.positioning), ball) < 2.0
        for p in state.players
    )


def open_mates(state: WorldState) -> list[tuple[Player, float]]:
    """Team-mates with their openness (distance to the nearest opponent), best first."""
    opponents = [_xy(p.positioning) for p in state.players if p.which_team is Team.OPP and p.positioning]
    out = []
    for p in state.players:
        if p.which_team is not Team.OUR or p.player_number is None or p.positioning is None:
            continue
        here = _xy(p.positioning)
        openness = min((_dist(here, o) for o in opponents), default=30.0)
        out.append((p, openness))
    return sorted(out, key=lambda item: -item[1])


def line_is_free(state: WorldState, start: tuple[float, float], end: tuple[float, float], width: float = 2.0) -> bool:
    """No opponent within ``width`` of the segment start-end."""
    sx, sy = start
    ex, ey = end
    length = math.hypot(ex - sx, ey - sy) or 1e-9
    for p in state.players:
        if p.which_team is not Team.OPP or p.positioning is None:
            continue
        px, py = p.positioning.x, p.positioning.y
        t = max(0.0, min(1.0, ((px - sx) * (ex - sx) + (py - sy) * (ey - sy)) / length**2))
        if math.hypot(sx + t * (ex - sx) - px, sy + t * (ey - sy) - py) < width:
            return False
    return True


def choose_pass(state: WorldState, me: tuple[float, float]) -> Player | None:
    """The best open team-mate clearly ahead of me with a free passing line."""
    best, best_score = None, -1e9
    for mate, openness in open_mates(state):
        here = _xy(mate.positioning)
        d = _dist(me, here)
        if here[0] < me[0] + 2.0 or not 5.0 <= d <= 35.0 or openness < 3.0:
            continue
        if not line_is_free(state, me, here):
            continue
        score = here[0] * 0.5 + openness - 0.2 * d
        if score > best_score:
            best, best_score = mate, score
    return best


def choose_safe_pass(state: WorldState, me: tuple[float, float]) -> Player | None:
    """The most open team-mate 5-30 m away with a free passing line, ahead or not."""
    for mate, openness in open_mates(state):
        here = _xy(mate.positioning)
        if 5.0 <= _dist(me, here) <= 30.0 and openness >= 2.0 and line_is_free(state, me, here):
            return mate
    return None


def set_piece_kick(state: WorldState, me: tuple[float, float]) -> Decision:
    """Our set piece: one touch only, so pass, or kick long into the opponents' half."""
    if _dist(me, GOAL) <= SHOOT_RANGE:
        return Decision("shoot", act.Shoot(target=_point(FIELD_HALF_LENGTH, 0.0), power=100.0), "set piece near goal")
    mate = choose_pass(state, me) or choose_safe_pass(state, me)
    if mate is not None:
        to = Player(player_number=mate.player_number, which_team=Team.OUR)
        return Decision("pass", act.Pass(to=to), f"set piece to team-mate {mate.player_number}")
    target = _point(min(FIELD_HALF_LENGTH - 10.0, me[0] + 35.0), me[1] * 0.5)
    return Decision("pass", act.Pass(target=target, power=100.0), "set piece: kick long")


class SetPieceTaker:
    """Remembers that this player took our set piece, until somebody else has touched the ball.

    The rules (rcssserver's free_kick_fault, and the embedded simulator's) forbid the taker a
    second touch before another player's; the decision asks :meth:`may_touch` before it decides
    and tells :meth:`decided` what it chose.
    """

    def __init__(self) -> None:
        self.took_at: int | None = None

    def may_touch(self, state: WorldState) -> bool:
        if self.took_at is None:
            return True
        mode = play_mode(state)
        if mode in OUR_SET_PIECES:
            return True  # not kicked yet (the ball is still in place)
        ball = _xy(state.ball.positioning) if state.ball and state.ball.positioning else None
        someone_else = ball is not None and any(
            p.positioning is not None and _dist(_xy(p.positioning), ball) <= TOUCHED for p in state.players
        )
        if mode is not PlayMode.PLAY_ON or someone_else or state.time - self.took_at > TAKER_MEMORY:
            self.took_at = None
        return self.took_at is None

    def decided(self, state: WorldState, decision: Decision) -> None:
        mode = play_mode(state)
        if mode in OUR_SET_PIECES and decision.method in KICKING:
            self.took_at = state.time


def with_ball(state: WorldState, number: int, me: tuple[float, float]) -> Decision:
    mode = play_mode(state)
    if mode in OUR_SET_PIECES:
        return set_piece_kick(state, me)
    goal_dist = _dist(me, GOAL)
    if goal_dist <= SHOOT_RANGE:
        # Aim at the post side the goalkeeper covers least.
        keeper = next((p for p in state.players if p.which_team is Team.OPP and p.is_goalie and p.positioning), None)
        aim_y = -5.0 if keeper is not None and keeper.positioning.y > 0 else 5.0
        return Decision("shoot", act.Shoot(target=_point(FIELD_HALF_LENGTH, aim_y), power=100.0), "close to goal")
    mate = choose_pass(state, me)
    if mate is not None and (me[0] < 25.0 or not line_is_free(state, me, GOAL, 3.0)):
        to = Player(player_number=mate.player_number, which_team=Team.OUR)
        return Decision("pass", act.Pass(to=to), f"open team-mate {mate.player_number}")
    if me[0] < CLEAR_LINE and not line_is_free(state, me, (me[0] + 10.0, me[1] * 0.7), 4.0):
        # Pressed in our own third: no dribbling there; clear the ball long towards the wing.
        wing = 25.0 if me[1] >= 0 else -25.0
        return Decision("pass", act.Pass(target=_point(me[0] + 40.0, wing), power=100.0), "clear the ball")
    target = _point(min(FIELD_HALF_LENGTH - 8.0, me[0] + 10.0), me[1] * 0.7)
    return Decision("dribble", act.Dribble(target=target, speed=70.0), "towards goal")


def goalkeeper(state: WorldState, me: tuple[float, float], ball: tuple[float, float] | None) -> Decision:
    if ball is not None:
        d = _dist(me, ball)
        in_area = (
            ball[0] < -FIELD_HALF_LENGTH + FIELD.penalty_area_length and abs(ball[1]) < FIELD.penalty_area_width / 2
        )
        if d <= KICKABLE:
            return Decision(
                "pass", act.Pass(target=_point(0.0, 25.0 if me[1] >= 0 else -25.0), power=100.0), "clear the ball"
            )
        if in_area and d <= 1.2:
            direction = math.atan2(ball[1] - me[1], ball[0] - me[0]) - (state.me.positioning.yaw or 0.0)
            direction = math.atan2(math.sin(direction), math.cos(direction))
            return Decision("catch", act.Catch(direction=direction), "ball in reach")
        if in_area and d < 8.0:
            return Decision("intercept", act.Intercept(), "ball in the penalty area")
        # Stand on the line from the goal centre to the ball, 2 m out.
        angle = math.atan2(ball[1] - OWN_GOAL[1], ball[0] - OWN_GOAL[0])
        spot = (OWN_GOAL[0] + 2.0 * math.cos(angle), OWN_GOAL[1] + 2.0 * math.sin(angle) * 1.5)
    else:
        spot = (OWN_GOAL[0] + 2.0, 0.0)
    if _dist(me, spot) > 1.0:
        return Decision("moveTo", act.MoveTo(target=_point(*spot), speed=80.0), "guard the goal")
    return Decision("turnToDirection", act.TurnToDirection(direction=0.0), "face the field")


def decide(state: WorldState, number: int, team_size: int, claims: dict[int, int], may_touch: bool = True) -> Decision:
    """The action for player ``number`` now. ``claims``: team-mates' announced times to the ball.

    ``may_touch`` False: this player took our set piece and nobody else has touched the ball yet.
    """
    me_pos = _xy(state.me.positioning) if state.me else None
    if me_pos is None:
        return Decision("turn", act.Turn(angle=1.0), "lost: look around")
    role = role_of(number, team_size)
    mode = play_mode(state)
    ball = _xy(state.ball.positioning) if state.ball and state.ball.positioning else None

    if mode in (PlayMode.BEFORE_KICK_OFF, PlayMode.GOAL_OUR, PlayMode.GOAL_OPP, PlayMode.HALF_TIME):
        x, y = home_position(number, team_size, ball_x=0.0)
        return Decision("move", act.Move(target=_point(min(x, -1.0), y)), "formation before kick-off")
    if ball is None:
        return Decision("turn", act.Turn(angle=1.0), "look for the ball")
    if mode.value.endswith("_opp") and mode is not PlayMode.PLAY_ON:
        x, y = home_position(number, team_size, ball_x=ball[0])  # their set piece: keep shape
        return _hold(me_pos, (x, y), "their set piece: keep shape")
    if role is Role.GOALKEEPER and may_touch:
        return goalkeeper(state, me_pos, ball)
    if _dist(me_pos, ball) <= KICKABLE and may_touch:
        return with_ball(state, number, me_pos)
    my_eta = cycles_to_ball(me_pos, ball)
    if not may_touch:
        my_eta = NEVER  # the ball is someone else's until they have touched it
    contested = opponent_on_ball(state, ball)
    if may_touch and choose_interceptor(number, my_eta, claims):
        if contested:
            return win_the_ball(ball, f"fastest to a contested ball ({my_eta} cycles)")
        return Decision("intercept", act.Intercept(), f"fastest to the ball ({my_eta} cycles)")
    if may_touch and ball[0] < 0.0 and contested and second_fastest(number, my_eta, claims):
        return win_the_ball(ball, f"press the opponent on the ball ({my_eta} cycles)")
    x, y = home_position(number, team_size, ball_x=ball[0], ball_y=ball[1])
    return _hold(me_pos, (x, y), f"{role.value}: hold position")


def _hold(me: tuple[float, float], spot: tuple[float, float], why: str) -> Decision:
    if _dist(me, spot) > 3.0:
        return Decision("moveTo", act.MoveTo(target=_point(*spot), speed=70.0), why)
    return Decision("turnToObject", act.TurnToObject(obj=_ball_model()), why + ", watch the ball")


def _ball_model():
    from cf_lang.ontology import Ball

    return Ball()
