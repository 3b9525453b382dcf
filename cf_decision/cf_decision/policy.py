"""The league-independent team policy: from a perceived WorldState to one action (ROS-free).

Input is only what the Framework Language carries (the player's own
WorldState, in its own frame: x towards the opponents' goal) and what
team-mates said (who goes for the ball). Output is an ontology action for
``(exec Player <method> ...)``. Nothing here knows the back-end.

What it does, in order:
- before a kick-off: take the kick-off position (the formation, wide forwards
  out wide), and keep it at our kick-off until the ball is played;
- goalkeeper: catch a ball in reach in his area, within 90 degrees of his
  body, unless a team-mate touched it last (a back pass), take the free kick
  that follows as a set piece, else clear a kickable ball, close down an
  opponent through on goal, else guard the goal on the line that halves the
  angle the ball sees it under, further out the further the ball;
- with the ball: shoot when close enough with a free line, else pass to the
  best open team-mate ahead (or play a through ball behind their last line),
  never to one offside, else carry it at full speed on an open run; else,
  in our half, a safe pass losing at most 3 m, received outside our penalty
  area, else clear it long; in theirs, within LONG_SHOT_RANGE drive at goal
  at close control on a way with room (from beyond CLOSE_SHOT), else shoot;
  else a safe pass to a team-mate within that range and
  nearer the goal (a set-up), else a safe pass that loses no ground, else kick it into
  space a team-mate reaches first, else within DRIVE_RANGE drive at goal, else
  dribble into space, else any safe pass, else take it on towards the goal;
- at our set piece the player with the ball first looks for the opponents near
  it he has not seen lately; then he passes (backwards if need be) or
  kicks long, never dribbles, and then leaves the ball to others until
  somebody else has touched it (the rules forbid the taker a second touch);
- the team-mate chosen to go for the ball (fastest to it; ties to the lower
  number) intercepts; a cycle before the ball is in his reach he asks for what
  he does with it (as with the ball at his feet, on the ball as it will be);
  when an opponent has the ball, he goes for it and plays it in one request:
  in our half to a team-mate up the field who gets it safely, else clear; in
  theirs towards the goal; the team-mate a pass was
  announced to (to a point: the first to reach its path) sets off at once to
  where he meets it (once he sees it rolling: on the path it rolls), and waits
  there facing the ball; a midfielder or forward who has just passed in
  their half runs on, onside, for the ball back (support.py); in our half the second
  fastest stands in his way to our goal, facing the ball; any player within
  tackling reach of an opponent's ball goes for it; the others hold their
  formation position, shifted with the ball, facing the ball (the forwards on
  their last line unless the ball is deep in our half); while a team-mate
  has the ball in play, a midfielder or forward stands where a pass reaches him safely,
  within 4 m of that position and as far up as he may (support.py).
"""

from __future__ import annotations

from collections.abc import Sequence

from cf_lang.ontology import PlayMode, WorldState
from cf_lang.ontology import actions as act

from .goalkeeper import goalkeeper
from .reach import top_speed
from .receive import Announced, meeting, rolling
from .roles import Role, back_line, home_position, kick_off_position, role_of
from .situation import (
    FIELD_HALF_LENGTH,
    KICKABLE,
    Decision,
    ball_ahead,
    dist,
    offside_line,
    opponent_on_ball,
    our_ball,
    play_mode,
    point,
    their_ball,
    xy,
)
from .support import go_spot, open_spot
from .with_ball import win_the_ball, with_ball
from .without_ball import (
    MARK_BALL_X,
    NEVER,
    block,
    choose_interceptor,
    cycles_to_ball,
    goal_side,
    hold,
    marking,
    second_fastest,
    tired,
)

TACKLE_REACH = 2.0  # m: rcssserver's tackle_dist, the furthest a tackle reaches ahead of the body
MEET_SLACK = 0.5  # m: how near the point a pass is met at the receiver waits for it
SUPPORT_SLACK = 1.5  # m: how near the open spot a supporting player goes (a lane is narrow)
MEET_GET = 4  # cycles: a pass seen rolling that I meet this soon, or that rolls
GET_NEAR = 2.5  # m: this near me within MEET_GET cycles, is got by the intercept skill
LINE_AHEAD_MAX = 25.0  # m: a forward on their last line stands at most this far beyond the ball
ANTICIPATE = 1  # cycles: the interceptor this near the ball asks for its kick, not for the intercept


def decide(
    state: WorldState,
    number: int,
    team_size: int,
    claims: dict[int, int],
    may_touch: bool = True,
    passes: Sequence[Announced] = (),
    mate_touched: bool = False,
) -> Decision:
    """The action for player ``number`` now. ``claims``: team-mates' announced times to the ball;
    ``passes``: the passes team-mates announced lately.

    ``may_touch`` False: this player took our set piece, or stood offside at a team-mate's touch, and
    nobody else has touched the ball since (the rules forbid him the ball).
    ``mate_touched``: a team-mate touched the ball last (the goalkeeper may not catch it).
    """
    me_pos = xy(state.me.positioning) if state.me else None
    if me_pos is None:
        return Decision("turn", act.Turn(angle=1.0), "lost: look around")
    role = role_of(number, team_size)
    mode = play_mode(state)
    ball = xy(state.ball.positioning) if state.ball and state.ball.positioning else None

    if mode in (PlayMode.BEFORE_KICK_OFF, PlayMode.GOAL_OUR, PlayMode.GOAL_OPP, PlayMode.HALF_TIME):
        return Decision(
            "move", act.Move(target=point(*kick_off_position(number, team_size))), "formation before kick-off"
        )
    if ball is None:
        return Decision("turn", act.Turn(angle=1.0), "look for the ball")
    if mode.value.endswith("_opp") and mode is not PlayMode.PLAY_ON:
        x, y = home_position(number, team_size, ball_x=ball[0])  # their set piece: keep shape
        return hold(me_pos, (x, y), "their set piece: keep shape")
    if role is Role.GOALKEEPER and may_touch:
        return goalkeeper(state, me_pos, ball, mate_touched)
    if dist(me_pos, ball) <= KICKABLE and may_touch:
        return with_ball(state, number, me_pos)
    my_eta = cycles_to_ball(me_pos, ball, state.ball.velocity, top_speed(state.me))
    if not may_touch:
        my_eta = NEVER  # the ball is someone else's until they have touched it
    contested = opponent_on_ball(state, ball)
    if may_touch and choose_interceptor(number, my_eta, claims):
        if contested:
            return win_the_ball(state, ball, f"fastest to a contested ball ({my_eta} cycles)")
        if my_eta <= ANTICIPATE and mode is PlayMode.PLAY_ON:
            # Decide what to do with it now, on the ball as it will be: the kick skills get to the
            # ball themselves, and an intercept followed by the next decision left the player idle
            # at the ball for the cycle that decision took to arrive (docs/performance.md, session 26).
            coming = ball_ahead(state, my_eta)
            choice = with_ball(coming, number, xy(coming.ball.positioning))
            return Decision(choice.method, choice.action, f"{choice.why} (the ball comes: {my_eta} cycles)")
        return Decision("intercept", act.Intercept(), f"fastest to the ball ({my_eta} cycles)")
    meet = meeting(state, number, passes) if may_touch and mode is PlayMode.PLAY_ON else None
    if meet is not None:
        # Set off the moment the pass is asked for, not once the ball is seen rolling: to where it
        # is met, and wait there facing it until it is the nearest's to intercept.
        spot, cycles = meet
        path = rolling(state)
        if path is not None and (cycles <= MEET_GET or any(dist(me_pos, p) <= GET_NEAR for p in path[:MEET_GET])):
            # Seen rolling, and near: the action component meets it on the ball as it rolls now,
            # by a dash sideways where it passes a metre or two off (the reach model here counts
            # a turn first, and sent the receiver to a spot 20 cycles on). A run to a spot let
            # passes roll by 1-2 m from the receiver: 7% of our passes against HELIOS base.
            return Decision("intercept", act.Intercept(), f"meet the pass: get it ({cycles} cycles)")
        return hold(me_pos, spot, f"meet the pass ({cycles} cycles)", MEET_SLACK, hurry=True)
    line = offside_line(state, ball)
    if role in (Role.MIDFIELDER, Role.FORWARD) and mode is PlayMode.PLAY_ON and not their_ball(state, ball):
        go = go_spot(state, number, passes, line)
        if go is not None:
            return hold(me_pos, go, "pass and go: run on for the ball back", MEET_SLACK, hurry=True)
    if mode is PlayMode.KICK_OFF_OUR:
        # The taker may look before he kicks: a wide forward drifting in meanwhile closes the space
        # the kick-off's pass is meant for.
        return hold(me_pos, kick_off_position(number, team_size), "kick-off: keep the kick-off place")
    if may_touch and contested and dist(me_pos, ball) <= TACKLE_REACH:
        # Whoever is this close to an opponent's ball has a tackle: the skill takes it when it is
        # near-sure (else closes in). Markers and holders used to let such balls go by.
        return win_the_ball(state, ball, "an opponent's ball within tackling reach")
    if may_touch and ball[0] < 0.0 and contested and second_fastest(number, my_eta, claims):
        return block(me_pos, ball, f"cover the opponent on the ball ({my_eta} cycles)", tired(state))
    if role in (Role.DEFENDER, Role.MIDFIELDER) and ball[0] < MARK_BALL_X and their_ball(state, ball):
        mark = marking(state, team_size, ball).get(number)
        if mark is not None:
            why = f"{role.value}: mark the opponent at {mark[0]:.0f} {mark[1]:.0f}"
            spot = goal_side(mark)
            if role is Role.DEFENDER:  # not behind our line: a man beyond it is offside
                spot = (max(spot[0], back_line(ball[0])), spot[1])
            return hold(me_pos, spot, why, 1.0, tired(state))
    x, y = home_position(number, team_size, ball_x=ball[0], ball_y=ball[1], offside_x=line)
    why = f"{role.value}: hold position"
    if role is Role.FORWARD and line is not None and ball[0] > -20.0:
        # Stand on their last line, ready to run onto a ball played behind it, whoever has the ball
        # now: sent there only once it was ours, the forwards stood 9 m short of it (session 58).
        x, why = max(x, min(line - 1.0, ball[0] + LINE_AHEAD_MAX)), "forward: on their last line"
    if role in (Role.MIDFIELDER, Role.FORWARD) and mode is PlayMode.PLAY_ON and our_ball(state, ball):
        # (Not at our set piece: the taker's pass model has the receivers standing still, and there
        # they kept 29 of 33 passes against HELIOS base.)
        onside = line - 1.0 if line is not None else FIELD_HALF_LENGTH
        spot = open_spot(state, me_pos, ball, (x, y), onside)
        if spot != (x, y):
            return hold(me_pos, spot, f"{role.value}: open for a pass", SUPPORT_SLACK, tired(state))
    return hold(me_pos, (x, y), why, tired=tired(state))
