"""The player with the ball (ROS-free): shots, passes, dribbles and clearances, judged with the
reach model (:mod:`reach`) on what the player believes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_lang.ontology import FIELD, Ball, Player, PlayMode, Team, WorldState
from cf_lang.ontology import actions as act

from . import reach
from .set_piece import OUR_SET_PIECES
from .situation import (
    FIELD_HALF_LENGTH,
    GOAL,
    Decision,
    dist,
    guard_spot,
    offside_line,
    offside_mates,
    onside,
    play_mode,
    point,
    sides,
    xy,
)

SHOOT_RANGE = 22.0  # at a set piece, shoot from within this distance
SHOT_RANGE = 30.0  # in play, consider shots from within this distance
LONG_SHOT_RANGE = 25.0  # in play, with nothing better, shoot anyway from within this distance
# Against HELIOS base every shot from 17 m or further that reached the goal line was caught or went
# wide, and one from 15.8 m went in (docs/performance.md, session 62): from further out, with room,
# the ball is carried nearer first.
CLOSE_SHOT = 16.0  # m: a hopeful shot from further than this waits for a drive at goal with room
DRIVE_GAIN = 4.0  # m: a drive at goal ends at least this much nearer the goal
DRIVE_RANGE = 35.0  # m: a carry this near the goal takes a way towards it, if one has room
SET_UP_GAIN = 3.0  # m: a pass that sets up a shot is received at least this much nearer the goal
SHOT_SPEED = 2.4  # m/cycle a shot is assumed to leave the foot with
WIN_PASS_GAIN = 5.0  # m: a ball won in our half is passed on only this far up the field or further
KEEP_GAIN = -3.0  # m: in our half a safe pass that loses no more ground than this keeps the ball
OUR_BOX_X = -36.0  # m: ... when it is received outside our penalty area
# On the game logs' truth, passes the model gave a team-mate by one cycle were kept 80% of the time
# against HELIOS base, by 2-3 cycles 68% (docs/performance.md, sessions 37-38): a second cycle bought nothing.
SAFE_MARGIN = 1  # cycles: our receiver must be this much sooner at the ball than any opponent
OPEN_NEAR = 5.0  # m: no opponent this close, and
OPEN_AHEAD = 15.0  # m: none this far along the way: a dribble may go at full speed
CLEAR_ANGLES = range(-70, 71, 10)  # degrees off straight up the field a clearance may take
CLEAR_AIM = 20.0  # m: the clearance aims at a point this far along its way (inside the field)
CLEAR_SPEED = 2.0  # m/cycle: what a hurried touch of a ball not placed for it gives (not the 2.7 most)
LANE_LENGTH = 15.0  # m: a dribble's lane: the opponents this close and
LANE_ANGLE = 30.0  # degrees: this far off its way are the ones it runs into
# On the wing 60 degrees off the way to goal is sideways or back: such a carry went back into the
# men in the middle, and 32 of 46 touches more than 100 degrees off straight up were lost at once
# (HELIOS base, docs/performance.md, session 49).
WAY_OFF_UP_FIELD = 75.0  # degrees: a dribble's way goes at most this far off straight up the field
LOOK_AGE = 2  # cycles: at our set piece, an opponent seen longer ago than this is looked for first,
LOOK_RADIUS = 30.0  # m: if he was this close to the ball and
LOOK_BEHIND = 5.0  # m: at most this much nearer our goal than the ball
# HELIOS base holds its last line about 7 m beyond our ball in the middle third, 35 m short of its
# goal line: balls into that space are through balls (docs/performance.md, session 58).
THROUGH_DEPTHS = (6.0, 12.0, 18.0)  # m behind their last line a through ball is aimed
THROUGH_LANES = (-24.0, -16.0, -8.0, 0.0, 8.0, 16.0, 24.0)  # y of the lanes it is aimed along
THROUGH_MARGIN = 3  # cycles: a through ball runs past their men into their space: a wider margin than SAFE_MARGIN


def win_the_ball(state: WorldState, ball: tuple[float, float], why: str) -> Decision:
    """Go for a ball an opponent has and play it the moment it is in reach, in one request.

    Intercepting first and deciding then would give the opponent the cycles our decision and
    action need to see the ball at our feet: the action's kick skills approach the ball
    themselves. In our half: pass it to a team-mate who gets it safely (to where he stands when
    the request arrives), else clear it long towards the wing; in theirs: take it towards the goal.
    """
    if ball[0] < 0.0:
        choice = best_pass(state, ball, WIN_PASS_GAIN)
        if choice is not None:
            to = Player(player_number=choice.number, which_team=Team.OUR)
            return Decision("pass", act.Pass(to=to), f"{why}: win it and pass it to team-mate {choice.number}")
        x = min(30.0, round((ball[0] + 35.0) / 10.0) * 10.0)  # on a 10 m grid: one request, not one a cycle
        target = point(x, 25.0 if ball[1] >= 0 else -25.0)
        return Decision("pass", act.Pass(target=target, power=100.0), why + ": win it and clear it")
    target = point(FIELD_HALF_LENGTH - 8.0, 0.0)
    return Decision("dribble", act.Dribble(target=target, speed=70.0), why + ": win it and go")


def set_piece_kick(state: WorldState, me: tuple[float, float]) -> Decision:
    """Our set piece: one touch only, so shoot (not at an indirect free kick), pass (backwards if need
    be), or kick long into their half."""
    ball = xy(state.ball.positioning) if state.ball and state.ball.positioning else me
    if unseen_near(state, ball):
        # A set piece leaves time to look: against a real team most of the men near the ball were
        # not believed within 3 m of where they stood when the taker chose, and every pass that
        # went to an opponent went to one of those (docs/performance.md, session 17).
        return Decision("turnToObject", act.TurnToObject(obj=Ball()), "set piece: look first")
    indirect = play_mode(state) is PlayMode.INDIRECT_FREE_KICK_OUR
    if dist(ball, GOAL) <= SHOOT_RANGE and not indirect:
        target, _ = shot_margin(state, ball)  # the corner the keeper is furthest from
        return Decision("shoot", act.Shoot(target=point(*target), power=100.0), "set piece near goal")
    choice = best_pass(state, ball)
    if choice is not None:
        return pass_to(choice, "set piece")
    mates = sides(state)[0]
    if indirect and mates:
        # A shot from an indirect free kick cannot score: against HELIOS base one from 10.8 m, the
        # defenders on their goal line, went wide for their goal kick. A team-mate's touch first.
        number, runner = min(mates, key=lambda mate: dist(mate[1].pos, ball))
        return pass_to(PassChoice(number, None, runner.pos[0] - ball[0], runner.pos), "indirect free kick")
    target = point(min(FIELD_HALF_LENGTH - 10.0, me[0] + 35.0), me[1] * 0.5)
    return Decision("pass", act.Pass(target=target, power=100.0), "set piece: kick long")


def unseen_near(state: WorldState, ball: tuple[float, float]) -> bool:
    """An opponent near the ball, not behind it, was seen more than LOOK_AGE cycles ago; or, at our
    kick-off, one is believed more than LOOK_BEHIND behind the ball, however lately seen.

    At a kick-off every opponent stands in his own half, so a man believed in ours is where he was
    before the goal (the goal stops the clock, so he looks fresh), and the men in front of the
    taker are unknown: after a goal the taker had seen none of them, did not look, and passed into
    the middle. The wait ends: the head sweeps while the body faces the ball and sees them again,
    or the belief's memory (30 cycles, and the clock runs at a kick-off) lets a man go.
    """
    kick_off = play_mode(state) is PlayMode.KICK_OFF_OUR
    for p in state.players:
        if p.which_team is not Team.OPP or p.positioning is None:
            continue
        behind = p.positioning.x < ball[0] - LOOK_BEHIND
        if kick_off and behind:
            return True
        if (p.age or 0) > LOOK_AGE and dist(xy(p.positioning), ball) <= LOOK_RADIUS and not behind:
            return True
    return False


def best_shot(state: WorldState, ball: tuple[float, float]) -> tuple[float, float] | None:
    """The point in the goal a shot reaches before any opponent can stop it (the widest margin), if any."""
    if dist(ball, GOAL) > SHOT_RANGE:
        return None
    target, margin = shot_margin(state, ball)
    return target if margin > 0 else None


def shot_margin(state: WorldState, ball: tuple[float, float]) -> tuple[tuple[float, float], int]:
    """The point in the goal with the widest margin (cycles between the ball crossing the line and
    the first opponent who could stop it; negative: stopped first), and that margin.

    When every line is blocked, the one the goalkeeper reaches last: a blocked shot may still get
    through, and the block is hard to foresee, the keeper's reach less so.
    """
    _, opponents = sides(state)
    keepers = [o for o in opponents if o.goalie]
    if not keepers:
        # Their goalkeeper is out of sight more often than not (behind the head's sweep): a shot
        # judged free of him went straight into his hands from 30 m against HELIOS base. Unseen, he
        # is where a goalkeeper guards his goal.
        keepers = [reach.Runner(their_guard_spot(ball), True)]
        opponents = [*opponents, *keepers]
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
        away = min((dist(target, k.pos) for k in keepers), default=0.0)  # ties: further from him
        key = (max(margin, 0), keeper, away)
        if key > best_key:
            best, best_key, best_margin = target, key, margin
    return best, best_margin


def their_guard_spot(ball: tuple[float, float]) -> tuple[float, float]:
    """Where their goalkeeper guards against a ball at ``ball``: as ours does (:func:`guard_spot`), mirrored."""
    x, y = guard_spot((-ball[0], ball[1]))
    return -x, y


@dataclass(frozen=True)
class PassChoice:
    number: int
    target: tuple[float, float] | None  # None: to the team-mate's feet
    gain: float  # metres up the field from the ball to where it is received
    at: tuple[float, float]  # where it is received


def best_pass(
    state: WorldState, ball: tuple[float, float], min_gain: float = -1e9, to_shoot: bool = False
) -> PassChoice | None:
    """The best pass a team-mate receives SAFE_MARGIN cycles before any opponent could, gaining ``min_gain``.

    Targets are team-mates' feet, points ahead of them, and through balls: points behind their
    last line, got THROUGH_MARGIN cycles first. No team-mate beyond that line is a receiver (he
    would be offside). The score is how far up the field the ball is received, plus a little for
    time to spare. ``to_shoot``: only balls
    received within LONG_SHOT_RANGE of the goal count, the nearest the goal best (a set-up).
    """
    mates, opponents = sides(state)
    line = offside_line(state, ball)
    mates = [(n, r) for n, r in mates if onside(r.pos[0], line)]  # (as offside_mates: the others may not play it)
    targets = []
    for number, runner in mates:
        here = runner.pos
        leads = (0.0, 5.0, 10.0) if here[0] > ball[0] - 5.0 else (0.0,)
        targets += [
            ((min(FIELD_HALF_LENGTH - 3.0, here[0] + lead), here[1]), number, lead > 0.0, SAFE_MARGIN) for lead in leads
        ]
    if line is not None and line > ball[0]:
        targets += [
            ((min(FIELD_HALF_LENGTH - 3.0, line + depth), y), None, True, THROUGH_MARGIN)
            for depth in THROUGH_DEPTHS
            for y in THROUGH_LANES
        ]
    best, best_score = None, -1e9
    for target, meant, to_point, margin in targets:
        d = dist(ball, target)
        if not 4.0 <= d <= 40.0:
            continue
        # A pass to a point keeps rolling past it: received beyond a line, it is theirs.
        path = reach.in_field(reach.kicked_path(ball, target, reach.pass_speed(d)))
        reached = [(c, n) for n, r in mates if (c := reach.cycles_to_path(r.pos, path, speed=r.speed)) is not None]
        if not reached:
            continue
        ours, first = min(reached)  # (ties to the lower number, as receivers tell who meets a pass)
        number = meant or first  # a through ball is the first team-mate's
        theirs = reach.first_cycles(path, opponents)
        spare = reach.HORIZON if theirs is None else theirs - ours
        if spare < margin:
            continue
        received = path[ours - 1]
        if received[0] - ball[0] < min_gain or in_our_box(received):
            continue  # (in our area the keeper would take it: a back pass he may not catch)
        if to_shoot:
            to_goal = dist(received, GOAL)
            if to_goal > LONG_SHOT_RANGE:
                continue
            score = -to_goal + 0.5 * min(spare, 6)
        else:
            score = received[0] + 0.5 * min(spare, 6) - 0.3 * abs(received[1]) * (received[0] > 30.0)
        if score > best_score:
            best, best_score = PassChoice(number, target if to_point else None, received[0] - ball[0], received), score
    return best


def in_our_box(at: tuple[float, float]) -> bool:
    """In our penalty area."""
    return at[0] < -FIELD_HALF_LENGTH + FIELD.penalty_area_length and abs(at[1]) < FIELD.penalty_area_width / 2


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
    for pos, *_ in sides(state)[1]:
        d = dist(me, pos)
        off = abs(math.remainder(math.atan2(pos[1] - me[1], pos[0] - me[0]) - heading, math.tau))
        if d < near or (d < ahead and off < math.radians(cone)):
            return False
    return True


def open_run(state: WorldState, me: tuple[float, float], towards: tuple[float, float]) -> bool:
    """Nobody within OPEN_NEAR, nor within OPEN_AHEAD and 45 degrees of the way: dribble at full speed
    (the ball pushed further ahead), not at close control.

    A dribbler at close control moves at about two thirds of a runner's pace and is caught from behind.
    """
    return space_ahead(state, me, towards, OPEN_NEAR, OPEN_AHEAD, 45.0)


Way = tuple[tuple[float, float], tuple[int, float]]  # a dribble's target, and its room


def free_ways(state: WorldState, me: tuple[float, float]) -> list[Way]:
    """The points 10 m away, towards the goal or up to 60 degrees off it (but at most WAY_OFF_UP_FIELD off
    straight up the field), with space on the way: the
    straightest first (of two as straight, the one towards the middle of the field), each with its room.

    Space: nobody within 2.5 m, nor within 6 m and 60 degrees of the way (:func:`space_ahead`).
    Room: (minus the opponents in the lane, the nearest of them): the lane is within LANE_LENGTH and
    LANE_ANGLE degrees of the way. In our own third only straight ahead: beating a man there risks
    a goal.
    """
    opponents = [o.pos for o in sides(state)[1]]
    toward = math.atan2(GOAL[1] - me[1], GOAL[0] - me[0])
    ways = []
    for off in (0.0,) if me[0] < -FIELD_HALF_LENGTH / 3 else (0.0, 30.0, -30.0, 60.0, -60.0):
        heading = toward + math.radians(off if me[1] <= 0 else -off)
        if abs(heading) > math.radians(WAY_OFF_UP_FIELD):
            continue
        x = min(FIELD_HALF_LENGTH - 8.0, me[0] + 10.0 * math.cos(heading))
        y = max(-FIELD.width / 2 + 3.0, min(FIELD.width / 2 - 3.0, me[1] + 10.0 * math.sin(heading)))
        if dist(me, (x, y)) <= 4.0 or not space_ahead(state, me, (x, y)):
            continue
        lane = [
            d
            for d, bearing in ((dist(me, pos), math.atan2(pos[1] - me[1], pos[0] - me[0])) for pos in opponents)
            if d < LANE_LENGTH and abs(math.remainder(bearing - heading, math.tau)) < math.radians(LANE_ANGLE)
        ]
        ways.append(((x, y), (-len(lane), min(lane, default=LANE_LENGTH))))
    return ways


def roomiest(ways: list[Way]) -> tuple[float, float] | None:
    """The way with the most room: the fewest opponents in its lane, then the nearest of them furthest
    away; of equals the straightest.

    Taking the straightest free way led a wide forward into a block of men 10 m on rather than up
    the empty wing.
    """
    return max(ways, key=lambda way: way[1])[0] if ways else None  # max keeps the first of equals


def goal_drive(
    ways: list[Way], ball: tuple[float, float], within: float = LONG_SHOT_RANGE
) -> tuple[float, float] | None:
    """From further than CLOSE_SHOT, the free way with the most room of those that end DRIVE_GAIN
    nearer the goal (a close-control dribble into shooting range), if any."""
    to_goal = dist(ball, GOAL)
    if not CLOSE_SHOT < to_goal <= within:
        return None
    return roomiest([way for way in ways if dist(way[0], GOAL) <= to_goal - DRIVE_GAIN])


def with_ball(state: WorldState, number: int, me: tuple[float, float]) -> Decision:
    """What the player with the ball at his feet does with it (the order is in policy.py's docstring)."""
    mode = play_mode(state)
    if mode in OUR_SET_PIECES:
        return set_piece_kick(state, me)
    ball = xy(state.ball.positioning) if state.ball and state.ball.positioning else me
    shot = best_shot(state, ball)
    if shot is not None:
        return Decision("shoot", act.Shoot(target=point(*shot), power=100.0), "a free shot")
    safe = best_pass(state, ball)
    if safe is not None and safe.gain >= 10.0:
        return pass_to(safe, "forward pass")
    ways = free_ways(state, me)
    straight = ways[0][0] if ways else None
    if straight is not None and open_run(state, me, straight):
        return Decision("dribble", act.Dribble(target=point(*straight), speed=100.0), "open run: carry it fast")
    if me[0] < 0.0 and safe is not None and safe.gain >= KEEP_GAIN and ball[0] + safe.gain > OUR_BOX_X:
        # Now that receivers set off when the pass is asked for, such a pass was kept 45% of the
        # time against Pyrus2D, the clearance it comes before 21% (docs/performance.md, session 24).
        return pass_to(safe, "keep it: safe pass")
    if me[0] < 0.0:
        # In our half without a forward pass or an open run: clear it. Against real teams a short
        # pass or a dribble there reached a team-mate about one time in six and left the ball where
        # it was (docs/decision.md): if it is lost, lose it far from our goal.
        aim, _ = best_clearance(state, ball)
        return Decision("pass", act.Pass(target=point(*aim), power=100.0), "clear the ball")
    if dist(ball, GOAL) <= LONG_SHOT_RANGE:
        drive = goal_drive(ways, ball)
        if drive is not None:
            return Decision("dribble", act.Dribble(target=point(*drive), speed=70.0), "drive at goal")
        # Near their goal every other way was lost nearly every time: a shot at least may go in.
        target, _ = shot_margin(state, ball)
        return Decision("shoot", act.Shoot(target=point(*target), power=100.0), "a hopeful shot")
    set_up = best_pass(state, ball, to_shoot=True)
    if set_up is not None and dist(set_up.at, GOAL) < dist(ball, GOAL) - SET_UP_GAIN:
        # Out of shooting range (wide, or by the goal line), a team-mate in range gets it safely:
        # against HELIOS base the wide forward carried the ball to their goal line and passed it
        # back out of range (docs/performance.md, session 36).
        return pass_to(set_up, "set up a shot")
    if safe is not None and safe.gain >= 0.0:
        # Keep the ball in their half: a close-control dribble there was lost 33 times in 34
        # against HELIOS base, while a ball the reach model gives a team-mate by 2 cycles on the
        # game log's truth was kept 46-69% of the time (docs/performance.md, session 23).
        return pass_to(safe, "safe pass on")
    aim, kept = best_clearance(state, ball)
    if kept:
        # A close-control dribble here kept the ball about one time in ten (docs/decision.md).
        return Decision("pass", act.Pass(target=point(*aim), power=100.0), "kick it into space for a team-mate")
    drive = goal_drive(ways, ball, DRIVE_RANGE)
    if drive is not None:
        # The roomiest way from the wing runs along the touch line to their corner flag, 33 m from
        # goal, where HELIOS base took the ball back (kick-off drills, docs/performance.md, session 64).
        return Decision("dribble", act.Dribble(target=point(*drive), speed=70.0), "drive at goal from further out")
    space = roomiest(ways)
    if space is not None:
        # At close control the way is chosen for room: the straightest, into a block of men 10 m
        # on, was lost within a few cycles against HELIOS base (docs/decision.md).
        return Decision("dribble", act.Dribble(target=point(*space), speed=70.0), "space ahead: carry it")
    if safe is not None:
        return pass_to(safe, "safe pass")
    goal_ward = point(min(FIELD_HALF_LENGTH - 8.0, me[0] + 10.0), me[1] * 0.7)
    return Decision("dribble", act.Dribble(target=goal_ward, speed=70.0), "pressed: take it on")


def best_clearance(state: WorldState, ball: tuple[float, float]) -> tuple[tuple[float, float], bool]:
    """Where to aim a ball kicked as hard as possible: of the ways an onside team-mate reaches first
    (if any, else of all), the one on which the ball is met furthest from our goal; and whether
    a team-mate reaches it first.

    A fixed aim (long to the near wing) went to the forward pressing the kicker about half
    the time against real teams and was lost 10 m from where it was kicked (docs/decision.md).
    A ball that crosses the touch line first is lost where it crosses (their throw-in).
    """
    mates, opponents = sides(state)
    offside = offside_mates(state, ball)  # (one of them who went for it would be called offside)
    ours_all = [runner for n, runner in mates if n not in offside]
    ways = []
    for degrees in CLEAR_ANGLES:
        heading = math.radians(degrees)
        target = (ball[0] + CLEAR_AIM * math.cos(heading), ball[1] + CLEAR_AIM * math.sin(heading))
        path = reach.in_field(reach.kicked_path(ball, target, CLEAR_SPEED))
        if not path:  # over the line at once: lost where it lies
            ways.append(((False, ball[0], -abs(degrees)), target))
            continue
        ours, theirs = reach.first_cycles(path, ours_all), reach.first_cycles(path, opponents)
        kept = ours is not None and (theirs is None or theirs - ours >= SAFE_MARGIN)
        met = path[(ours if kept else theirs or len(path)) - 1]
        ways.append(((kept, met[0], -abs(degrees)), target))
    (kept, _, _), best = max(ways, key=lambda way: way[0])  # the first of equals, as the angles go
    return best, kept


def pass_to(choice: PassChoice, why: str) -> Decision:
    """The pass request for ``choice``: to the team-mate's feet, or to a point ahead of him."""
    if choice.target is None:
        action = act.Pass(to=Player(player_number=choice.number, which_team=Team.OUR))
    else:
        action = act.Pass(target=point(*choice.target))
    return Decision("pass", action, f"{why} to team-mate {choice.number}")
