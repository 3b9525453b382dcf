"""The league-independent team policy: from a perceived WorldState to one action (ROS-free).

Input is only what the Framework Language carries (the player's own
WorldState, in its own frame: x towards the opponents' goal) and what
team-mates said (who goes for the ball). Output is an ontology action for
``(exec Player <method> ...)``. Nothing here knows the back-end.

What it does, in order:
- before a kick-off: take the formation position;
- goalkeeper: catch a ball in reach, clear a kickable ball, close down an
  opponent through on goal, else guard the goal on the line between ball and
  goal centre, further out the further the ball;
- with the ball: shoot when close enough with a free line, else pass to the
  best open team-mate ahead, else carry it at full speed on an open run; else,
  in our half, clear it long towards the wing; in theirs, shoot when within
  LONG_SHOT_RANGE, else dribble into space, else any safe pass, else take it
  on towards the goal;
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

from . import reach
from .roles import Role, home_position, role_of

FIELD_HALF_LENGTH = FIELD.half_length
GOAL = (FIELD_HALF_LENGTH, 0.0)
OWN_GOAL = (-FIELD_HALF_LENGTH, 0.0)
KICKABLE = 1.0
SHOOT_RANGE = 22.0  # at a set piece, shoot from within this distance
SHOT_RANGE = 30.0  # in play, consider shots from within this distance
LONG_SHOT_RANGE = 25.0  # in play, with nothing better, shoot anyway from within this distance
SHOT_SPEED = 2.4  # m/cycle a shot is assumed to leave the foot with
SAFE_MARGIN = 2  # cycles: our receiver must be this much sooner at the ball than any opponent
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
FRESH_AGE = 1  # cycles: a player seen this long ago is where he was seen (rcssserver: a see every 2 cycles)
TAKER_MEMORY = 100  # cycles after which a set piece's taker plays on as usual
NEVER = 10**6  # cycles to the ball of a player who may not touch it
MARK_RADIUS = 15.0  # m from a defender's or midfielder's formation spot: opponents he may mark
MARK_DISTANCE = 1.5  # m goal-side of the marked opponent
TIRED = 0.45  # stamina share
MARK_BALL_X = 15.0  # mark while their ball is short of this x (deeper in their half: keep the shape)
KEEPER_OUT_SHARE = 0.25  # the goalkeeper stands this share of the ball's distance out of his goal,
KEEPER_OUT_MAX = 6.0  # m: at most this far
RUSH_DISTANCE = 14.0  # m from our goal: an opponent with the ball this close is closed down by the keeper
OPEN_NEAR = 5.0  # m: no opponent this close, and
OPEN_AHEAD = 15.0  # m: none this far along the way: a dribble may go at full speed


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


def cycles_to_ball(me: tuple[float, float], ball: tuple[float, float], velocity=None) -> int:
    """Cycles until I can have the ball, rolling as it does (``velocity``: the ontology's, metres per second)."""
    v = (velocity.vx / reach.CYCLES_PER_SECOND, velocity.vy / reach.CYCLES_PER_SECOND) if velocity else (0.0, 0.0)
    return reach.cycles_to_ball(me, ball, v)


def state_eta(state: WorldState) -> int | None:
    """My cycles to the ball in ``state`` (None: I or the ball are not known)."""
    if not (state.ball and state.ball.positioning and state.me and state.me.positioning):
        return None
    return cycles_to_ball(_xy(state.me.positioning), _xy(state.ball.positioning), state.ball.velocity)


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


def set_piece_kick(state: WorldState, me: tuple[float, float]) -> Decision:
    """Our set piece: one touch only, so shoot, pass (backwards if need be), or kick long into their half."""
    ball = _xy(state.ball.positioning) if state.ball and state.ball.positioning else me
    if _dist(ball, GOAL) <= SHOOT_RANGE:
        target, _ = shot_margin(state, ball)  # the corner the keeper is furthest from
        return Decision("shoot", act.Shoot(target=_point(*target), power=100.0), "set piece near goal")
    choice = best_pass(state, ball)
    if choice is not None:
        return _pass(choice, "set piece")
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
        self.spot: tuple[float, float] | None = None  # where the ball lay when the taker chose his kick
        self.mode: PlayMode | None = None  # the set piece he took

    def may_touch(self, state: WorldState) -> bool:
        if self.took_at is None:
            return True
        mode = play_mode(state)
        ball = _xy(state.ball.positioning) if state.ball and state.ball.positioning else None
        if mode is self.mode:
            if ball is None or self.spot is None or _dist(ball, self.spot) < TOUCHED:
                return True  # not kicked yet
            # Kicked, and the mode lags behind (a goal kick stays one until the ball leaves the area).
        elif mode is not PlayMode.PLAY_ON:
            self.took_at = None  # another stoppage: a new set piece
        # Only players seen just now count: a stale sighting of the opponent who stood at the ball
        # when play stopped would release the taker at once (a free kick fault on rcssserver).
        someone_else = ball is not None and any(
            p.positioning is not None
            and (p.age is None or p.age <= FRESH_AGE)
            and _dist(_xy(p.positioning), ball) <= TOUCHED
            for p in state.players
        )
        if someone_else or (self.took_at is not None and state.time - self.took_at > TAKER_MEMORY):
            self.took_at = None
        return self.took_at is None

    def decided(self, state: WorldState, decision: Decision) -> None:
        mode = play_mode(state)
        if mode in OUR_SET_PIECES and decision.method in KICKING:
            self.took_at = state.time
            self.spot = _xy(state.ball.positioning) if state.ball and state.ball.positioning else None
            self.mode = mode


def _sides(state: WorldState) -> tuple[list[tuple[int, tuple[float, float]]], list[tuple[tuple[float, float], bool]]]:
    """Team-mates (number, position) other than me, and opponents (position, goalkeeper)."""
    mates, opponents = [], []
    me = state.me.player_number if state.me else None
    for p in state.players:
        if p.positioning is None:
            continue
        if p.which_team is Team.OUR and p.player_number not in (None, me):
            mates.append((p.player_number, _xy(p.positioning)))
        elif p.which_team is Team.OPP:
            opponents.append((_xy(p.positioning), bool(p.is_goalie)))
    return mates, opponents


def best_shot(state: WorldState, ball: tuple[float, float]) -> tuple[float, float] | None:
    """The point in the goal a shot reaches before any opponent can stop it (the widest margin), if any."""
    if _dist(ball, GOAL) > SHOT_RANGE:
        return None
    target, margin = shot_margin(state, ball)
    return target if margin > 0 else None


def shot_margin(state: WorldState, ball: tuple[float, float]) -> tuple[tuple[float, float], int]:
    """The point in the goal with the widest margin (cycles between the ball crossing the line and
    the first opponent who could stop it; negative: stopped first), and that margin.

    When every line is blocked, the one the goalkeeper reaches last: a blocked shot may still get
    through, and the block is hard to foresee, the keeper's reach less so.
    """
    _, opponents = _sides(state)
    keepers = [o for o in opponents if o[1]]
    best, best_key, best_margin = (FIELD_HALF_LENGTH + 1.0, 0.0), (-1, 0, 0.0), -reach.HORIZON
    half_goal = FIELD.goal_width / 2 - 0.8
    for y in (-half_goal, -half_goal / 2, 0.0, half_goal / 2, half_goal):
        target = (FIELD_HALF_LENGTH + 1.0, y)
        path = reach.kicked_path(ball, target, SHOT_SPEED)
        arrive = next((n for n, (x, _) in enumerate(path, start=1) if x >= FIELD_HALF_LENGTH), None)
        if arrive is None:
            continue
        margin, keeper = (
            reach.HORIZON if stopped is None else stopped - arrive
            for stopped in (reach.first_cycles(path[:arrive], group) for group in (opponents, keepers))
        )
        away = min((_dist(target, pos) for pos, _ in keepers), default=0.0)  # ties: further from him
        key = (max(margin, 0), keeper, away)
        if key > best_key:
            best, best_key, best_margin = target, key, margin
    return best, best_margin


@dataclass(frozen=True)
class PassChoice:
    number: int
    target: tuple[float, float] | None  # None: to the team-mate's feet
    gain: float  # metres up the field from the ball to where it is received


def best_pass(state: WorldState, ball: tuple[float, float], min_gain: float = -1e9) -> PassChoice | None:
    """The best pass a team-mate receives SAFE_MARGIN cycles before any opponent could, gaining ``min_gain``.

    Targets are team-mates' feet and points ahead of them (through balls); the score is how far
    up the field the ball is received, plus a little for time to spare.
    """
    mates, opponents = _sides(state)
    best, best_score = None, -1e9
    for number, here in mates:
        leads = (0.0, 5.0, 10.0) if here[0] > ball[0] - 5.0 else (0.0,)
        for lead in leads:
            target = (min(FIELD_HALF_LENGTH - 3.0, here[0] + lead), here[1])
            d = _dist(ball, target)
            if not 4.0 <= d <= 40.0:
                continue
            path = reach.kicked_path(ball, target, reach.pass_speed(d))
            ours = reach.first_cycles(path, [(pos, False) for n, pos in mates])
            if ours is None:
                continue
            theirs = reach.first_cycles(path, opponents)
            spare = reach.HORIZON if theirs is None else theirs - ours
            if spare < SAFE_MARGIN:
                continue
            received = path[ours - 1]
            if received[0] - ball[0] < min_gain:
                continue
            score = received[0] + 0.5 * min(spare, 6) - 0.3 * abs(received[1]) * (received[0] > 30.0)
            if score > best_score:
                best, best_score = PassChoice(number, target if lead else None, received[0] - ball[0]), score
    return best


def space_ahead(
    state: WorldState,
    me: tuple[float, float],
    towards: tuple[float, float],
    near: float = 2.5,
    ahead: float = 6.0,
    cone: float = 60.0,
) -> bool:
    """No opponent within ``near``, nor within ``ahead`` and ``cone`` degrees of the way towards ``towards``."""
    heading = math.atan2(towards[1] - me[1], towards[0] - me[0])
    for pos, _ in _sides(state)[1]:
        d = _dist(me, pos)
        off = abs(math.remainder(math.atan2(pos[1] - me[1], pos[0] - me[0]) - heading, math.tau))
        if d < near or (d < ahead and off < math.radians(cone)):
            return False
    return True


def dribble_speed(state: WorldState, me: tuple[float, float], towards: tuple[float, float]) -> float:
    """Full speed (the ball pushed further ahead) on an open run; else close control.

    An open run: nobody within OPEN_NEAR, nor within OPEN_AHEAD and 45 degrees of the way. A
    dribbler at close control moves at about two thirds of a runner's pace and is caught from behind.
    """
    if space_ahead(state, me, towards, OPEN_NEAR, OPEN_AHEAD, 45.0):
        return 100.0
    return 70.0


def dribble_room(state: WorldState, me: tuple[float, float]) -> tuple[float, float] | None:
    """A point 10 m away, towards the goal or up to 60 degrees off it, with space on the way (the straightest).

    In our own third only straight ahead: beating a man there risks a goal.
    """
    toward = math.atan2(GOAL[1] - me[1], GOAL[0] - me[0])
    for off in (0.0,) if me[0] < -FIELD_HALF_LENGTH / 3 else (0.0, 30.0, -30.0, 60.0, -60.0):
        heading = toward + math.radians(off if me[1] <= 0 else -off)  # try the middle of the field first
        x = min(FIELD_HALF_LENGTH - 8.0, me[0] + 10.0 * math.cos(heading))
        y = max(-FIELD.width / 2 + 3.0, min(FIELD.width / 2 - 3.0, me[1] + 10.0 * math.sin(heading)))
        if _dist(me, (x, y)) > 4.0 and space_ahead(state, me, (x, y)):
            return (x, y)
    return None


def with_ball(state: WorldState, number: int, me: tuple[float, float]) -> Decision:
    mode = play_mode(state)
    if mode in OUR_SET_PIECES:
        return set_piece_kick(state, me)
    ball = _xy(state.ball.positioning) if state.ball and state.ball.positioning else me
    shot = best_shot(state, ball)
    if shot is not None:
        return Decision("shoot", act.Shoot(target=_point(*shot), power=100.0), "a free shot")
    safe = best_pass(state, ball)
    if safe is not None and safe.gain >= 10.0:
        return _pass(safe, "forward pass")
    space = dribble_room(state, me)
    speed = dribble_speed(state, me, space) if space is not None else 0.0
    if speed >= 100.0:
        return Decision("dribble", act.Dribble(target=_point(*space), speed=speed), "open run: carry it fast")
    if me[0] < 0.0:
        # In our half without a forward pass or an open run: clear it. Against real teams a short
        # pass or a dribble there reached a team-mate about one time in six and left the ball where
        # it was (docs/decision.md): if it is lost, lose it far from our goal.
        aim, _ = best_clearance(state, ball)
        return Decision("pass", act.Pass(target=_point(*aim), power=100.0), "clear the ball")
    if _dist(ball, GOAL) <= LONG_SHOT_RANGE:
        # Near their goal every other way was lost nearly every time: a shot at least may go in.
        target, _ = shot_margin(state, ball)
        return Decision("shoot", act.Shoot(target=_point(*target), power=100.0), "a hopeful shot")
    aim, kept = best_clearance(state, ball)
    if kept:
        # A close-control dribble here kept the ball about one time in ten (docs/decision.md).
        return Decision("pass", act.Pass(target=_point(*aim), power=100.0), "kick it into space for a team-mate")
    if space is not None:
        return Decision("dribble", act.Dribble(target=_point(*space), speed=speed), "space ahead: carry it")
    if safe is not None:
        return _pass(safe, "safe pass")
    goal_ward = _point(min(FIELD_HALF_LENGTH - 8.0, me[0] + 10.0), me[1] * 0.7)
    return Decision("dribble", act.Dribble(target=goal_ward, speed=70.0), "pressed: take it on")


CLEAR_ANGLES = range(-70, 71, 10)  # degrees off straight up the field a clearance may take
CLEAR_AIM = 20.0  # m: the clearance aims at a point this far along its way (inside the field)
CLEAR_SPEED = 2.0  # m/cycle: what a hurried touch of a ball not placed for it gives (not the 2.7 most)


def best_clearance(state: WorldState, ball: tuple[float, float]) -> tuple[tuple[float, float], bool]:
    """Where to aim a ball kicked as hard as possible: of the ways a team-mate reaches first
    (if any, else of all), the one on which the ball is met furthest from our goal; and whether
    a team-mate reaches it first.

    A fixed aim (long to the near wing) went to the forward pressing the kicker about half
    the time against real teams and was lost 10 m from where it was kicked (docs/decision.md).
    A ball that crosses the touch line first is lost where it crosses (their throw-in).
    """
    mates, opponents = _sides(state)
    ours_all = [(pos, False) for _, pos in mates]
    ways = []
    for degrees in CLEAR_ANGLES:
        heading = math.radians(degrees)
        target = (ball[0] + CLEAR_AIM * math.cos(heading), ball[1] + CLEAR_AIM * math.sin(heading))
        path = reach.kicked_path(ball, target, CLEAR_SPEED)
        inside = next((n for n, (_, y) in enumerate(path) if abs(y) > FIELD.width / 2), len(path))
        path = path[: max(1, inside)]
        ours, theirs = reach.first_cycles(path, ours_all), reach.first_cycles(path, opponents)
        kept = ours is not None and (theirs is None or theirs - ours >= SAFE_MARGIN)
        met = path[(ours if kept else theirs or len(path)) - 1]
        ways.append(((kept, met[0], -abs(degrees)), target))
    (kept, _, _), best = max(ways, key=lambda way: way[0])  # the first of equals, as the angles go
    return best, kept


def _pass(choice: PassChoice, why: str) -> Decision:
    if choice.target is None:
        action = act.Pass(to=Player(player_number=choice.number, which_team=Team.OUR))
    else:
        action = act.Pass(target=_point(*choice.target))
    return Decision("pass", action, f"{why} to team-mate {choice.number}")


def goalkeeper(state: WorldState, me: tuple[float, float], ball: tuple[float, float] | None) -> Decision:
    if ball is not None:
        d = _dist(me, ball)
        in_area = (
            ball[0] < -FIELD_HALF_LENGTH + FIELD.penalty_area_length and abs(ball[1]) < FIELD.penalty_area_width / 2
        )
        if d <= KICKABLE:
            aim, _ = best_clearance(state, ball)
            return Decision("pass", act.Pass(target=_point(*aim), power=100.0), "clear the ball")
        if in_area and d <= 1.2:
            direction = math.atan2(ball[1] - me[1], ball[0] - me[0]) - (state.me.positioning.yaw or 0.0)
            direction = math.atan2(math.sin(direction), math.cos(direction))
            return Decision("catch", act.Catch(direction=direction), "ball in reach")
        to_goal = _dist(ball, OWN_GOAL)
        if in_area and d < 8.0:
            return Decision("intercept", act.Intercept(), "ball in the penalty area")
        if in_area and to_goal < RUSH_DISTANCE and opponent_on_ball(state, ball):
            # One on one: from the line he could not cover the goal, so close the shooter down.
            return Decision("intercept", act.Intercept(), "one on one: close the shooter down")
        # Stand on the line from the goal centre to the ball, further out the further the ball:
        # at the line a shot from 10 m passes him out of reach on either side.
        out = max(2.0, min(KEEPER_OUT_MAX, KEEPER_OUT_SHARE * to_goal))
        angle = math.atan2(ball[1] - OWN_GOAL[1], ball[0] - OWN_GOAL[0])
        spot = (OWN_GOAL[0] + out * math.cos(angle), OWN_GOAL[1] + out * math.sin(angle))
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
    my_eta = cycles_to_ball(me_pos, ball, state.ball.velocity)
    if not may_touch:
        my_eta = NEVER  # the ball is someone else's until they have touched it
    contested = opponent_on_ball(state, ball)
    if may_touch and choose_interceptor(number, my_eta, claims):
        if contested:
            return win_the_ball(ball, f"fastest to a contested ball ({my_eta} cycles)")
        return Decision("intercept", act.Intercept(), f"fastest to the ball ({my_eta} cycles)")
    if may_touch and ball[0] < 0.0 and contested and second_fastest(number, my_eta, claims):
        return win_the_ball(ball, f"press the opponent on the ball ({my_eta} cycles)")
    if role in (Role.DEFENDER, Role.MIDFIELDER) and ball[0] < MARK_BALL_X and their_ball(state, ball):
        mark = marking(state, team_size, ball).get(number)
        if mark is not None:
            why = f"{role.value}: mark the opponent at {mark[0]:.0f} {mark[1]:.0f}"
            return _hold(me_pos, goal_side(mark), why, 1.0, tired(state))
    line = offside_line(state, ball)
    x, y = home_position(number, team_size, ball_x=ball[0], ball_y=ball[1], offside_x=line)
    if role is Role.FORWARD and line is not None and not their_ball(state, ball) and ball[0] > -20.0:
        # Our ball: stand on their last line, ready to run onto a ball played behind it.
        return _hold(me_pos, (max(x, line - 1.0), y), "forward: on their last line", tired=tired(state))
    return _hold(me_pos, (x, y), f"{role.value}: hold position", tired=tired(state))


def tired(state: WorldState) -> bool:
    """Below TIRED of its stamina a player walks to its spot: under rcssserver's 30 % it recovers slower for good."""
    return state.me is not None and state.me.stamina is not None and state.me.stamina < TIRED


def their_ball(state: WorldState, ball: tuple[float, float]) -> bool:
    """An opponent is the player nearest the ball (or has it at his feet)."""
    nearest_opp = min(
        (_dist(_xy(p.positioning), ball) for p in state.players if p.which_team is Team.OPP and p.positioning),
        default=None,
    )
    if nearest_opp is None:
        return False
    ours = [_dist(_xy(p.positioning), ball) for p in state.players if p.which_team is Team.OUR and p.positioning]
    if state.me and state.me.positioning:
        ours.append(_dist(_xy(state.me.positioning), ball))
    return nearest_opp < 2.0 or nearest_opp < min(ours, default=1e9)


def marking(state: WorldState, team_size: int, ball: tuple[float, float]) -> dict[int, tuple[float, float]]:
    """Which opponent each defender and midfielder marks (number -> the opponent's position).

    The pairs nearest each other go first (a player's formation spot to an opponent, within
    MARK_RADIUS); the opponent on the ball is left to those who go for it. Every team-mate
    computes the same from what he sees, so nobody needs to be told.
    """
    opponents = [
        _xy(p.positioning)
        for p in state.players
        if p.which_team is Team.OPP and p.positioning and not p.is_goalie and _dist(_xy(p.positioning), ball) > 3.0
    ]
    pairs = []
    for n in range(2, team_size + 1):
        if role_of(n, team_size) not in (Role.DEFENDER, Role.MIDFIELDER):
            continue
        home = home_position(n, team_size, ball_x=ball[0], ball_y=ball[1])
        pairs += [(_dist(home, o), n, i) for i, o in enumerate(opponents) if _dist(home, o) < MARK_RADIUS]
    out, taken = {}, set()
    for _, n, i in sorted(pairs):
        if n not in out and i not in taken:
            out[n] = opponents[i]
            taken.add(i)
    return out


def goal_side(mark: tuple[float, float]) -> tuple[float, float]:
    """Where to stand to mark an opponent: MARK_DISTANCE from him towards our goal."""
    d = _dist(mark, OWN_GOAL) or 1.0
    return (
        mark[0] + (OWN_GOAL[0] - mark[0]) * MARK_DISTANCE / d,
        mark[1] + (OWN_GOAL[1] - mark[1]) * MARK_DISTANCE / d,
    )


def offside_line(state: WorldState, ball: tuple[float, float]) -> float | None:
    """The x beyond which our attackers are offside: the second-last opponent's, or the ball's if further.

    None while fewer than two opponents are known (the line cannot be told).
    """
    xs = sorted((p.positioning.x for p in state.players if p.which_team is Team.OPP and p.positioning), reverse=True)
    if len(xs) < 2:
        return None
    return max(xs[1], ball[0], 0.0)


def _hold(
    me: tuple[float, float], spot: tuple[float, float], why: str, slack: float = 3.0, tired: bool = False
) -> Decision:
    """Go to ``spot`` (fast when far, unless ``tired``), or, within ``slack`` of it, watch the ball."""
    d = _dist(me, spot)
    if d > slack:
        speed = 40.0 if tired else 100.0 if d > 8.0 else 70.0
        return Decision("moveTo", act.MoveTo(target=_point(*spot), speed=speed), why)
    return Decision("turnToObject", act.TurnToObject(obj=_ball_model()), why + ", watch the ball")


def _ball_model():
    from cf_lang.ontology import Ball

    return Ball()
