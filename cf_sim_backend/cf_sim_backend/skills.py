"""From Framework Language actions to simulator commands, cycle by cycle (ROS-free).

An action component turns each ``(exec Player <method> ...)`` into a
:class:`Skill`. Every cycle the skill looks at the true state of its own body
and the ball (what a robot knows from its own sensors and the perception it
trusts) and gives at most one body command, until it is done or fails.
Targets arrive in the player's own frame and are turned into the absolute one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_lang.ontology import actions as act
from cf_lang.ontology.actions import pass_speed
from cf_sim_backend import intercept, kick_plan
from cf_sim_backend.embedded.physics import foul_risk, in_own_penalty_area, tackle_failure
from cf_sim_backend.perception import to_own_frame
from cf_sim_backend.world import (
    Side,
    SimPlayer,
    World,
    direction_deg,
    distance,
    move_allowed,
    norm_deg,
    say_error,
)

Command = tuple  # ("dash", power, dir) | ("turn", moment) | ("kick", power, dir) | ...
TIMEOUT_CYCLES = 300


class SkillError(ValueError):
    """The action cannot be carried out now (e.g. the ball is not kickable)."""


@dataclass
class Step:
    commands: list[Command]
    status: str = "running"  # running | done | failed
    reason: str = ""


def _turn_moment(world: World, me: SimPlayer, angle: float) -> float:
    """The turn moment that turns the body by ``angle`` degrees at the current speed."""
    speed = math.hypot(me.vx, me.vy)
    return max(-180.0, min(180.0, angle * (1.0 + world.params.inertia_moment * speed)))


def _off_field(world: World, x: float, y: float, edge: float = 0.0) -> bool:
    """(x, y) lies beyond the touch lines or the goal lines, or within ``edge`` m inside them."""
    prm = world.params
    return abs(x) > prm.field_length / 2 - edge or abs(y) > prm.field_width / 2 - edge


def _absolute(side: Side, x: float, y: float) -> tuple[float, float]:
    return to_own_frame(side, x, y)  # turning by 180 degrees is its own inverse


SIDE_STEP = 3.0  # m: a target this close is reached by dashing sideways rather than turning first
AIM_TOLERANCE = 12.0  # degrees: a target this far off the body is run at without turning first


def _go(world: World, me: SimPlayer, x: float, y: float, power: float) -> Command:
    angle = norm_deg(direction_deg(me.x, me.y, x, y) - me.body)
    if abs(angle) <= AIM_TOLERANCE:
        return ("dash", power)
    if distance(me.x, me.y, x, y) <= SIDE_STEP and abs(angle) <= 90.0:
        # Close by (a ball being dribbled, a man to block): a turn every cycle would never get there.
        return ("dash", power, round(angle))
    return ("turn", _turn_moment(world, me, angle))


def kick_rate(world: World, me: SimPlayer) -> float:
    """The ball's acceleration per unit of kick power with the ball where it is now (rcssserver's formula)."""
    return kick_plan.rate_at(world.params, me.body, world.ball.x - me.x, world.ball.y - me.y)


def most_accel(world: World, rate: float) -> float:
    """The most acceleration one kick gives the ball at this kick rate."""
    return kick_plan.most_accel(world.params, rate)


def kick_towards(world: World, me: SimPlayer, x: float, y: float, speed: float | None) -> Command:
    """The kick that sends the ball towards (x, y) at ``speed`` m/cycle (None: as fast as this touch can).

    A kick adds to the ball's velocity, so a rolling ball's motion is taken out: the kick aims the
    sum, not the push. When the ball rolls too fast across the line to be turned onto it, the kick
    stops the ball instead (the next touch can then aim).
    """
    b, rate = world.ball, kick_rate(world, me)
    angle = math.radians(direction_deg(b.x, b.y, x, y))
    ux, uy = math.cos(angle), math.sin(angle)
    reach = kick_reach(world, me, x, y, rate)
    if reach is None:
        ax, ay = -b.vx, -b.vy
    else:
        want = reach if speed is None else max(0.0, min(speed, reach))
        ax, ay = want * ux - b.vx, want * uy - b.vy
    return _kick_for(me, ax, ay, rate)


def _kick_for(me: SimPlayer, ax: float, ay: float, rate: float) -> Command:
    """The kick that gives the ball the acceleration (ax, ay)."""
    direction = norm_deg(math.degrees(math.atan2(ay, ax)) - me.body)
    return ("kick", max(0.0, min(100.0, math.hypot(ax, ay) / rate)), direction)


def _kick_capped(world: World, me: SimPlayer, ax: float, ay: float) -> Command:
    """The kick that gives the ball the acceleration (ax, ay), or as much of it as one touch can."""
    rate = kick_rate(world, me)
    most = most_accel(world, rate)
    if math.hypot(ax, ay) > most:
        ax, ay = _scaled(ax, ay, most)
    return _kick_for(me, ax, ay, rate)


def _scaled(x: float, y: float, length: float) -> tuple[float, float]:
    """(x, y) cut to ``length``."""
    size = math.hypot(x, y)
    return x * length / size, y * length / size


def kick_reach(world: World, me: SimPlayer, x: float, y: float, rate: float | None = None) -> float | None:
    """The fastest the ball can leave towards (x, y) from this touch; None: it rolls too fast across to turn.

    ``rate``: the kick rate if the caller has it already.
    """
    b = world.ball
    most = most_accel(world, kick_rate(world, me) if rate is None else rate)
    angle = math.radians(direction_deg(b.x, b.y, x, y))
    return kick_plan.reach_along(world.params, math.cos(angle), math.sin(angle), b.vx, b.vy, most)


PRESSED = 2.5  # m: an opponent this close to the ball may take it during a first touch
LAY_CLEAR = 3.0  # m from where an opponent will be: a first touch lays the ball no nearer (his dash and tackle)
FIRST_TOUCHES = 2  # touches at most before a pass or shot's kick: each is a cycle the receiver and the opponents move
TOUCH_GAIN = 0.2  # m/cycle: a first touch must make the kick at least this much faster to be worth its cycle


def first_touch(world: World, me: SimPlayer, x: float, y: float, wanted: float, now: float) -> Command | None:
    """The touch after which the next kick sends the ball towards (x, y) fastest (up to ``wanted``),
    laying it no nearer than LAY_CLEAR to where an opponent will be; None if an opponent is within
    PRESSED of the ball or it would not gain TOUCH_GAIN over ``now``, the fastest a kick now gives
    (:mod:`kick_plan`)."""
    if pressed(world, me):
        return None
    b = world.ball
    kicker = kick_plan.Kicker(me.x, me.y, me.vx, me.vy, me.body, b.x, b.y, b.vx, b.vy)
    opponents = [(p.x + p.vx, p.y + p.vy) for p in world.players.values() if p.side is not me.side]
    touch = kick_plan.best_touch(world.params, kicker, (x, y), wanted, opponents, LAY_CLEAR)
    if touch is None or touch.then < min(wanted, now + TOUCH_GAIN):
        return None
    return _kick_for(me, touch.ax, touch.ay, kick_rate(world, me))


def pressed(world: World, me: SimPlayer, within: float = PRESSED) -> bool:
    """An opponent is within ``within`` m of the ball."""
    b = world.ball
    return any(p.side is not me.side and distance(p.x, p.y, b.x, b.y) <= within for p in world.players.values())


class Skill:
    """One action in progress."""

    name = "skill"

    def __init__(self) -> None:
        self.cycles = 0

    def step(self, world: World, me: SimPlayer) -> Step:
        self.cycles += 1
        if self.cycles > TIMEOUT_CYCLES:
            return Step([], "failed", f"{self.name} did not finish in {TIMEOUT_CYCLES} cycles")
        return self._step(world, me)

    def _step(self, world: World, me: SimPlayer) -> Step:
        raise NotImplementedError


class Once(Skill):
    """A single command, done at once."""

    def __init__(self, command: Command, name: str):
        super().__init__()
        self.command, self.name = command, name

    def _step(self, world: World, me: SimPlayer) -> Step:
        return Step([self.command], "done")


class Move(Once):
    """A move: refused once the play mode no longer allows it (the server would ignore it)."""

    def __init__(self, x: float, y: float):
        super().__init__(("move", x, y), "move")  # own-half coordinates as for the left side

    def _step(self, world: World, me: SimPlayer) -> Step:
        if not move_allowed(world.mode):
            return Step([], "failed", "move is allowed only before a kick-off")
        return super()._step(world, me)


class MoveTo(Skill):
    name = "moveTo"

    def __init__(self, x: float, y: float, speed: float, tolerance: float = 0.7):
        super().__init__()
        self.x, self.y, self.speed, self.tolerance = x, y, speed, tolerance

    def _step(self, world: World, me: SimPlayer) -> Step:
        if distance(me.x, me.y, self.x, self.y) <= self.tolerance:
            return Step([], "done")
        return Step([_go(world, me, self.x, self.y, self.speed)])


class TurnTo(Skill):
    name = "turn"

    def __init__(self, target: tuple[float, float] | None = None, heading: float | None = None):
        super().__init__()
        self.target, self.heading = target, heading

    def _step(self, world: World, me: SimPlayer) -> Step:
        heading = self.heading if self.target is None else direction_deg(me.x, me.y, *self.target)
        angle = norm_deg(heading - me.body)
        if abs(angle) <= 5.0:
            return Step([], "done")
        return Step([("turn", _turn_moment(world, me, angle))])


TACKLE_SURE = 0.2  # the most failure chance worth a tackle (it holds the tackler for tackle_cycles)
# m from our goal (and all our penalty area): a foul there is an indirect free kick in our penalty
# area or a free kick within shooting range. Refused in all our half, a tackle through a man cut
# our tackles against HELIOS base from about 19 to 8 a match, where fouls of ours were 1-3 a match
# (session 63).
FOUL_FREE_RANGE = 25.0
# m the foul check widens the man's place by: a foul of ours in our area came with the man 0.06 m
# inside rcssserver's place (session 63); the belief is not that exact at close range.
FOUL_MARGIN = 0.5


def _tackle_for(world: World, me: SimPlayer, x: float, y: float) -> Step | None:
    """A tackle towards (x, y) if an opponent has the ball at his feet and it would very likely hit;
    near our goal, not through a man (:func:`foul_risk`: rcssserver calls it a foul half the time)."""
    b = world.ball
    contested = any(
        p.side is not me.side and distance(p.x, p.y, b.x, b.y) <= world.params.kickable_distance
        for p in world.players.values()
    )
    if not contested or tackle_failure(world, me) > TACKLE_SURE:
        return None
    near_our_goal = distance(me.x, me.y, -me.side.sign * world.params.field_length / 2, 0.0) <= FOUL_FREE_RANGE
    if (near_our_goal or in_own_penalty_area(world, me)) and foul_risk(world, me, FOUL_MARGIN):
        # Against HELIOS base two such fouls in our area in one match were indirect free kicks
        # there, and one was a goal 7 cycles later (session 63).
        return None
    return Step([("tackle", norm_deg(direction_deg(b.x, b.y, x, y) - me.body))])


INTERCEPT_HORIZON = 50  # cycles of the ball's path looked along for a meeting point
INTERCEPT_REACH = 0.8  # share of the kickable distance planned with (noise, and a touch at the edge is weak)


def run_distances(world: World, me: SimPlayer, dashes: int, speed: float | None = None) -> list[float]:
    """How far 0, 1, ... ``dashes`` full dashes carry the player from his present speed, or from
    ``speed`` (rcssserver's dash model)."""
    prm = world.params
    v, covered, out = math.hypot(me.vx, me.vy) if speed is None else speed, 0.0, [0.0]
    for _ in range(dashes):
        v = min(prm.player_speed_max, v + prm.dash_accel)
        covered += v
        out.append(covered)
        v *= prm.player_decay
    return out


def _meeting(world: World, me: SimPlayer) -> intercept.Meeting | None:
    b = world.ball
    runner = intercept.Runner(me.x, me.y, me.vx, me.vy, me.body)
    reach = world.params.kickable_distance
    if me.goalie and in_own_penalty_area(world, me):
        reach = max(reach, world.params.catchable_area)  # he catches it there: the decision asks once in reach
    reach *= INTERCEPT_REACH
    return intercept.meeting(world.params, runner, (b.x, b.y, b.vx, b.vy), reach, INTERCEPT_HORIZON)


def intercept_point(world: World, me: SimPlayer) -> tuple[float, float, int]:
    """Where and in how many cycles the player can first have the ball, rolling as it does
    (:mod:`intercept`: dashing at an angle off the body or after a turn, whichever is sooner).
    A ball he never catches up with is met where it stops."""
    met = _meeting(world, me)
    return (met.x, met.y, met.cycles) if met is not None else (*_rolled_to(world), INTERCEPT_HORIZON)


def _rolled_to(world: World) -> tuple[float, float]:
    """Where the ball is after INTERCEPT_HORIZON cycles of rolling."""
    prm, b = world.params, world.ball
    rolled = (1.0 - prm.ball_decay**INTERCEPT_HORIZON) / (1.0 - prm.ball_decay)
    return b.x + b.vx * rolled, b.y + b.vy * rolled


def _chase_ball(world: World, me: SimPlayer) -> Step:
    """Run to where the ball and the player first meet; there, face the ball and wait for it."""
    b = world.ball
    if distance(me.x, me.y, b.x, b.y) <= world.params.kickable_distance:
        return Step([], "done")
    met = _meeting(world, me)
    if met is None:
        return Step([_go(world, me, *_rolled_to(world), 100.0)])
    if not met.command or distance(me.x, me.y, met.x, met.y) <= 0.5:
        # At the meeting point before the ball: a dash would carry him past it.
        off = norm_deg(direction_deg(me.x, me.y, b.x, b.y) - me.body)
        return Step([("turn", _turn_moment(world, me, off))] if abs(off) > AIM_TOLERANCE else [])
    if met.command[0] == "turn":
        return Step([("turn", _turn_moment(world, me, met.command[1]))])
    return Step([("dash", met.command[1], round(met.command[2], 1))])


class Intercept(Skill):
    """Get to the ball; if an opponent has it at his feet first, tackle it towards (x, y) when near-sure."""

    name = "intercept"

    def __init__(self, x: float, y: float):
        super().__init__()
        self.x, self.y = x, y

    def _step(self, world: World, me: SimPlayer) -> Step:
        if distance(me.x, me.y, world.ball.x, world.ball.y) > world.params.kickable_distance:
            tackle = _tackle_for(world, me, self.x, self.y)
            if tackle is not None:
                return tackle
        return _chase_ball(world, me)


SET_UP_STEPS = 3  # cycles the taker of our set piece may spend facing and nearing the ball before he kicks
SET_UP_FACING = 10.0  # degrees: a ball this far off the body is turned to first
SET_UP_GAP = 0.1  # m between the body's edge and the ball: where a step up aims (a kick loses 4%)


def set_up(world: World, me: SimPlayer) -> Command | None:
    """A turn to face a still ball, or a dash that brings it SET_UP_GAP from the body; None: close enough.

    Where the ball lies relative to the body is what makes a kick strong (:func:`kick_rate`), and
    neither command touches it: the dash stops short of it.
    """
    b, prm = world.ball, world.params
    off = norm_deg(direction_deg(me.x, me.y, b.x, b.y) - me.body)
    if abs(off) > SET_UP_FACING:
        return ("turn", _turn_moment(world, me, off))
    gap = distance(me.x, me.y, b.x, b.y) - prm.player_size - prm.ball_size
    if gap <= 2.0 * SET_UP_GAP:
        return None
    body = math.radians(me.body)
    drift = me.vx * math.cos(body) + me.vy * math.sin(body)  # the player moves on by his velocity anyway
    power = (gap - SET_UP_GAP - drift) / prm.dash_power_rate
    return ("dash", max(0.0, min(100.0, power))) if power > 0.0 else None


class KickTo(Skill):
    """Shoot or pass: go to the ball if needed, then kick it towards a point.

    ``fastest``: at full power, as fast as the ball may go (a shot), not as fast as one kick sends
    a still ball (see :meth:`_full_power`).
    """

    def __init__(
        self, name: str, x: float, y: float, power: float | None, approach: bool = True, fastest: bool = False
    ):
        super().__init__()
        self.name, self.x, self.y, self.power, self.approach = name, x, y, power, approach
        self.fastest = fastest
        self.kicked = False
        self.touches = 0  # first touches made (FIRST_TOUCHES at most): then the kick goes whatever it gives
        self.set_up = 0  # cycles spent stepping up to the ball of our set piece

    def _step(self, world: World, me: SimPlayer) -> Step:
        b = world.ball
        if self.kicked:
            return Step([], "done")
        if distance(me.x, me.y, b.x, b.y) > world.params.kickable_distance:
            if not self.approach:
                return Step([], "failed", "the ball is not kickable")
            return _tackle_for(world, me, self.x, self.y) or _chase_ball(world, me)
        if self.power is None:  # a pass: fast enough to arrive with some pace left
            speed = pass_speed(distance(b.x, b.y, self.x, self.y), world.params.ball_decay)
        else:  # a share of the fastest one kick gives a still ball (100: as fast as this touch can)
            speed = None if self.power >= 100.0 else self.power / 100.0 * world.params.ball_accel_max
        wanted = self._full_power(world) if speed is None else speed
        now = kick_reach(world, me, self.x, self.y) or 0.0
        if now < 0.9 * wanted:
            # This touch would send it off too slowly. At our set piece the ball lies still and a
            # second touch before anyone else's is a free kick fault: step up to it instead (a
            # kick-off taker 1 m from the ball sent his passes off at 2.1 m/cycle, not 2.7, and
            # they were cut out). In play: a first touch lays it where the kick is strong.
            if world.mode != "play_on":
                if self.set_up < SET_UP_STEPS:
                    self.set_up += 1
                    command = set_up(world, me)
                    if command is not None:
                        return Step([command])
            elif self.touches < FIRST_TOUCHES:
                touch = first_touch(world, me, self.x, self.y, wanted, now)
                if touch is not None:
                    self.touches += 1
                    return Step([touch])
        self.kicked = True
        return Step([kick_towards(world, me, self.x, self.y, speed)])

    def _full_power(self, world: World) -> float:
        """The speed a kick at full power wants: a shot as fast as the ball may go (``ball_speed_max``,
        3.0 m/cycle), any other kick as fast as one kick sends a still ball (``ball_accel_max``, 2.7).

        A shot is touched first unless the kick now sends it at 2.7 or more: a ball rolling along the
        shot's way takes the kick's most on top of its own speed. Of our shots on a way between the
        posts from 17 m or further (tools/rcss_shots.py, sessions 52-55, mostly against Pyrus2D), 6 of
        23 that left at 2.7 m/cycle or faster went in, 3 of 28 slower ones; from 20 m a shot at 3.0
        crosses the line in 8 cycles, one at 2.5 in 10.6.
        """
        return world.params.ball_speed_max if self.fastest else world.params.ball_accel_max


class Dribble(Skill):
    """Push the ball a little ahead towards the target, run after it, repeat; with a man near,
    keep it within reach every cycle."""

    name = "dribble"

    def __init__(self, x: float, y: float, speed: float):
        super().__init__()
        self.x, self.y, self.speed = x, y, speed
        self.heading: float | None = None  # degrees: the way the last touch sent the ball
        self.close_way: float | None = None  # degrees: the way the last close touch took

    def _step(self, world: World, me: SimPlayer) -> Step:
        b = world.ball
        if distance(b.x, b.y, self.x, self.y) <= 1.5:
            return Step([], "done")
        if distance(me.x, me.y, b.x, b.y) <= world.params.kickable_distance:
            if pressed(world, me, CLOSE_PRESS):
                return Step([self._close_touch(world, me)])
            push = dribble_push(world, me, self.speed)
            follow = _go(world, me, b.x + b.vx, b.y + b.vy, 100.0)
            if self._pushed(world, me, push):
                # Pushed already: run (or turn) after it. Kicking again cost a cycle, and on
                # rcssserver the ball was 3 m ahead of a dribbler who had touched it twice, then turned.
                # Unless a man would be near it before I have it again.
                margin = _dribble_margin(world, me, (b.vx, b.vy))
                if margin is not None and margin >= CLOSE_MARGIN:
                    return Step([follow])
                return Step([self._close_touch(world, me)])
            self.heading, margin = dribble_way(world, me, self.x, self.y, push, CLOSE_MARGIN)
            if margin is None or margin < CLOSE_MARGIN:
                return Step([self._close_touch(world, me)])
            off = norm_deg(self.heading - me.body)
            if abs(off) > DRIBBLE_FACING and math.hypot(b.vx, b.vy) < STILL and not pressed(world, me):
                # Face the way first: pushed across the body, the ball runs off while he turns.
                return Step([("turn", _turn_moment(world, me, off))])
            way = math.radians(self.heading)
            return Step([kick_towards(world, me, b.x + 10.0 * math.cos(way), b.y + 10.0 * math.sin(way), push)])
        return _tackle_for(world, me, self.x, self.y) or _chase_ball(world, me)

    def _close_touch(self, world: World, me: SimPlayer) -> Command:
        """A man near: the ball is kept within reach every cycle. A dash when it stays in reach after
        it, a turn when the way is more than DRIBBLE_FACING off the body and the ball stays in reach
        meanwhile, else a touch that lays it CLOSE_AHEAD in front of where I will be two cycles on
        (a dash between).

        Pushed 4 m ahead as in open space, the ball was loose for most of the cycles to the next
        touch, and a man pressing had it first: against HELIOS base 4 carries of 38 in their half
        were kept (docs/performance.md, sessions 60-61).
        """
        b, prm = world.ball, world.params
        self.heading = None  # the next open push picks its own way
        way = self.close_way = close_way(world, me, self.x, self.y, self.close_way)
        ux, uy = math.cos(math.radians(way)), math.sin(math.radians(way))
        bx, by = b.x + b.vx, b.y + b.vy  # the ball next cycle, untouched
        facing = abs(norm_deg(way - me.body)) <= DRIBBLE_FACING
        body = math.radians(me.body)
        accel = prm.dash_accel
        dvx, dvy = me.vx + accel * math.cos(body), me.vy + accel * math.sin(body)
        if math.hypot(dvx, dvy) > prm.player_speed_max:
            dvx, dvy = _scaled(dvx, dvy, prm.player_speed_max)
        if facing and _kept(me.x + dvx, me.y + dvy, me.body, bx, by):
            return ("dash", 100.0)
        if not facing and _kept(me.x + me.vx, me.y + me.vy, way, bx, by):
            return ("turn", _turn_moment(world, me, norm_deg(way - me.body)))
        # Where I will be two cycles on: this cycle's drift, then a dash if I face the way (else a turn).
        mx = me.x + me.vx * (1.0 + prm.player_decay) + (accel * math.cos(body) if facing else 0.0)
        my = me.y + me.vy * (1.0 + prm.player_decay) + (accel * math.sin(body) if facing else 0.0)
        tx, ty = mx + CLOSE_AHEAD * ux, my + CLOSE_AHEAD * uy
        rolls = 1.0 + prm.ball_decay
        return _kick_capped(world, me, (tx - b.x) / rolls - b.vx, (ty - b.y) / rolls - b.vy)

    def _pushed(self, world: World, me: SimPlayer, push: float) -> bool:
        """The ball rolls on the way my last touch sent it; or, before my first, on a way a touch of
        this dribble could take, and I have it again before any opponent.

        A new target every cycle or two (the way with the most room changes as men move) started a
        new dribble that touched the rolling ball again, and again.
        """
        b = world.ball
        if self.heading is not None:
            return _rolling_along(b, self.heading, 0.6 * push)
        straight = direction_deg(b.x, b.y, self.x, self.y)
        if not _rolling_along(b, straight, 0.6 * push, max(DODGE_ANGLES)):
            return False
        if math.hypot(b.vx, b.vy) > push + OUTRUN:
            # Faster than a touch of mine sends it: a pass or a clearance coming by. Let run, it ran
            # away from the dribbler who chased it, over the touch line (rcssserver, session 28).
            return False
        margin = _dribble_margin(world, me, (b.vx, b.vy))
        return margin is not None and margin > 0


class HoldBall(Skill):
    """Keep the ball within reach, where it is furthest from the opponents near, without moving on.

    Each cycle one touch lays the ball on a ring HOLD_RADIUS round where I will be, at the point
    furthest from the nearest opponent (where he will be); none when it rolls there by itself.
    It runs until a newer request replaces it (or the skills' timeout), and fails once the ball is
    out of reach. A base team's hold-ball does the same; note that rcssserver's tackle reaches
    2 m ahead of the tackler, so against a man pressing close it buys time, not safety.
    """

    name = "holdBall"

    def _step(self, world: World, me: SimPlayer) -> Step:
        b = world.ball
        if distance(me.x, me.y, b.x, b.y) > world.params.kickable_distance:
            return Step([], "failed", "the ball is out of reach")
        spot = hold_spot(world, me)
        ax, ay = spot[0] - b.x - b.vx, spot[1] - b.y - b.vy
        if math.hypot(ax, ay) <= HOLD_LAID:
            return Step([])
        return Step([_kick_capped(world, me, ax, ay)])  # as near the spot as one touch gets it


HOLD_RADIUS = 0.7  # m from my centre: inside the kickable distance (1.085) with room for the kick's noise
HOLD_LAID = 0.15  # m: a ball rolling this near the spot by itself is not touched
HOLD_NEAR = 5.0  # m: the opponents this close to me are the ones the ball is kept from
HOLD_EDGE = 0.5  # m inside the field: a spot beyond is not used


def hold_spot(world: World, me: SimPlayer) -> tuple[float, float]:
    """Where a hold-ball touch lays the ball: on the ring HOLD_RADIUS round where I will be next cycle,
    every 30 degrees, the point furthest from the nearest opponent within HOLD_NEAR (where he will be);
    with nobody near, in front of my body. Of two as far, the one nearer the front of my body (a
    touch from there is the strongest)."""
    cx, cy = me.x + me.vx, me.y + me.vy
    near = [
        (p.x + p.vx, p.y + p.vy)
        for p in world.players.values()
        if p.side is not me.side and distance(p.x, p.y, me.x, me.y) <= HOLD_NEAR
    ]
    best, best_key = None, None
    for degrees in range(0, 360, 30):
        heading = math.radians(me.body + degrees)
        x, y = cx + HOLD_RADIUS * math.cos(heading), cy + HOLD_RADIUS * math.sin(heading)
        if _off_field(world, x, y, HOLD_EDGE):
            continue
        room = min((distance(x, y, ox, oy) for ox, oy in near), default=0.0)
        key = (round(room, 1), -abs(norm_deg(degrees)))
        if best_key is None or key > best_key:
            best, best_key = (x, y), key
    return best if best is not None else (cx, cy)


OUTRUN = 0.2  # m/cycle: a ball faster than the push by more than this is not let run as the dribble's own
REGAIN = 5  # cycles: a full-speed dribble's touch sends the ball no further than the dribbler then is
DRIBBLE_FACING = 30.0  # degrees: a dribbler whose body is further off the way turns before he pushes,
STILL = 0.4  # m/cycle: if the ball is slower than this (it stays in reach meanwhile)
DODGE_ANGLES = (0.0, 20.0, -20.0, 40.0, -40.0, 60.0, -60.0)  # degrees off the way a dribble's touch may go
DODGE_LOOK = 10  # cycles of the pushed ball's roll looked at
OPPONENT_REACH = 1.2  # m: an opponent has the ball within this (a base team's widest kickable area)
BEHIND = 90.0  # degrees off the body: a dribbler goes after a ball this far round only after a turn


CLOSE_PRESS = 4.0  # m: with an opponent this near the ball, a dribble keeps it within reach every cycle,
CLOSE_MARGIN = 3  # cycles: and when an opponent could have a pushed ball less than this after I have it again
CLOSE_AHEAD = 0.6  # m in front of the dribbler: where a close touch lays the ball
CLOSE_REACH = 0.85  # m: a ball this near him next cycle is still his (kickable 1.085, less the kick's noise)
CLOSE_GAP = 0.5  # m: nearer, he runs into it (player and ball sizes 0.385)
CLOSE_LOOK = 2.0  # m along a close dribble's way: where its room from the opponents is measured
CLOSE_ROOM = 2.0  # m: the room a close dribble's way needs there (a man's tackle reach)


def close_way(world: World, me: SimPlayer, x: float, y: float, last: float | None) -> float:
    """The way of a close dribble: towards (x, y) if it is open, else the last one while it is open
    and within 90 degrees of (x, y), else the nearest open way off it (every 20 degrees, up to 60),
    of none the one with the most room. Open: CLOSE_ROOM from every opponent (where he will be next
    cycle) CLOSE_LOOK along it, and that point in the field.

    Taken on the open push's reckoning (who has the pushed ball first), every slow push was the
    dribbler's first, as he touches it again a cycle later: he walked the ball into a man standing
    in his way. With 3 m of room asked, the dribble got into their third less often against HELIOS
    base. A new way every cycle, each needing a turn, kicked the ball on the spot for ever (session 61).
    """
    straight = direction_deg(me.x, me.y, x, y)
    opponents = [(p.x + p.vx, p.y + p.vy) for p in world.players.values() if p.side is not me.side]

    def room(way: float) -> float:
        px = me.x + CLOSE_LOOK * math.cos(math.radians(way))
        py = me.y + CLOSE_LOOK * math.sin(math.radians(way))
        if _off_field(world, px, py):
            return -1.0
        return min((distance(px, py, ox, oy) for ox, oy in opponents), default=math.inf)

    ways = [straight + off for off in DODGE_ANGLES]
    if last is not None and abs(norm_deg(last - straight)) <= BEHIND:
        ways.insert(1, last)
    return next((way for way in ways if room(way) >= CLOSE_ROOM), max(ways, key=room))


def _kept(x: float, y: float, body: float, bx: float, by: float) -> bool:
    """A ball at (bx, by) is within reach of a player at (x, y) and in front of his body, clear of it."""
    gap = distance(x, y, bx, by)
    in_front = abs(norm_deg(direction_deg(x, y, bx, by) - body)) <= BEHIND
    return CLOSE_GAP <= gap <= CLOSE_REACH and in_front


def dribble_way(
    world: World, me: SimPlayer, x: float, y: float, push: float, need: int = 1
) -> tuple[float, int | None]:
    """The direction (degrees) of a dribble's touch: towards (x, y) or the nearest way off it, up to
    60 degrees, on which I have the ball again ``need`` cycles or more before any opponent can; of
    none, the one I am soonest at relative to them. With its margin (cycles; None: out of the field).

    A dribble is a pass to oneself: pushed straight at a defender, the ball rolled out of the
    dribbler's reach into the defender's, and against real teams that lost nearly every dribble
    (docs/decision.md).
    """
    b = world.ball
    straight = direction_deg(b.x, b.y, x, y)
    best, best_margin = straight, None
    for off in DODGE_ANGLES:
        way = math.radians(straight + off)
        margin = _dribble_margin(world, me, (push * math.cos(way), push * math.sin(way)))
        if margin is not None and margin >= need:
            return straight + off, margin
        if margin is not None and (best_margin is None or margin > best_margin):
            best, best_margin = straight + off, margin
    return best, best_margin


def _dribble_margin(world: World, me: SimPlayer, velocity: tuple[float, float]) -> int | None:
    """How many cycles before any opponent I have the ball again, rolling from where it is at
    ``velocity`` (after this cycle's touch); None: it leaves the field within DODGE_LOOK cycles.
    """
    b, prm = world.ball, world.params
    path, (bx, by), (vx, vy) = [], (b.x, b.y), velocity
    for _ in range(DODGE_LOOK):
        bx, by, vx, vy = bx + vx, by + vy, vx * prm.ball_decay, vy * prm.ball_decay
        path.append((bx, by))
    if any(_off_field(world, px, py) for px, py in path):
        return None
    opponents = [p for p in world.players.values() if p.side is not me.side]
    theirs = min((_their_cycles(o, path) for o in opponents), default=DODGE_LOOK + 2)
    return theirs - _my_cycles(world, me, path)


def _my_cycles(world: World, me: SimPlayer, path: list[tuple[float, float]]) -> int:
    """The first cycle after this touch in which I can have the ball on ``path`` again (DODGE_LOOK + 1: none).

    This cycle goes to the touch; then I run after it, gathering speed as rcssserver's dash does.
    A ball behind me (more than BEHIND degrees off the body) costs a turn first, from a standstill:
    counted as if I could run any way at full pace, a touch back past me looked safe, and against
    HELIOS base 32 of 46 touches more than 100 degrees off straight up the field were lost at once,
    42 of 247 within 45 degrees of it (docs/performance.md, session 49).
    """
    x, y = me.x + me.vx, me.y + me.vy
    runs = run_distances(world, me, DODGE_LOOK, math.hypot(me.vx, me.vy) * world.params.player_decay)
    turned = [0.0, *run_distances(world, me, DODGE_LOOK, 0.0)]  # a cycle to turn, then from a standstill
    for n, (bx, by) in enumerate(path, start=1):
        behind = abs(norm_deg(direction_deg(x, y, bx, by) - me.body)) > BEHIND
        if distance(x, y, bx, by) - world.params.kickable_distance <= (turned if behind else runs)[n - 1]:
            return n
    return DODGE_LOOK + 1


def _their_cycles(p: SimPlayer, path: list[tuple[float, float]]) -> int:
    """The first cycle in which opponent ``p``, running at full pace from now, can have the ball on ``path``."""
    for n, (bx, by) in enumerate(path, start=1):
        if distance(p.x, p.y, bx, by) - OPPONENT_REACH <= n * 1.0:
            return n
    return DODGE_LOOK + 2


def dribble_push(world: World, me: SimPlayer, speed: float) -> float:
    """How fast a dribble's touch sends the ball (m/cycle): speed 70 about 0.9, 100 about 1.3, but
    above 70 never faster than the dribbler reaches it again REGAIN cycles after the touch.

    Up to 70 the ball stays within a step or two (close control); above it the ball runs ahead
    of the dribbler, who reaches it again after a few cycles at full dash (a runner's pace). A
    fixed 1.3 m/cycle rolled 20 m: he needed 13-17 cycles to catch his own ball, and the other
    side had it first more often than not (docs/performance.md, session 34).
    """
    push = _touch_speed(world, speed)
    if speed <= 70.0:
        return push
    prm, b = world.params, world.ball
    ahead = distance(me.x, me.y, b.x, b.y)
    # This cycle goes to the touch (his speed carries him on), then REGAIN - 1 full dashes.
    drift = math.hypot(me.vx, me.vy) * prm.player_decay
    run = drift + run_distances(world, me, REGAIN - 1, drift * prm.player_decay)[-1]
    rolls = (1.0 - prm.ball_decay**REGAIN) / (1.0 - prm.ball_decay)  # metres per m/cycle of push
    return max(_touch_speed(world, 70.0), min(push, (run + prm.kickable_distance - ahead) / rolls))


def _touch_speed(world: World, speed: float) -> float:
    """The ball's speed (m/cycle) a dribble's touch at ``speed`` aims at, before any cap."""
    share = 0.15 + 0.0025 * speed + 0.0025 * max(0.0, speed - 70.0)
    return share * world.params.ball_accel_max


def _rolling_along(ball, heading: float, speed: float, within: float = 20.0) -> bool:
    """The ball rolls at least ``speed`` within ``within`` degrees of ``heading``."""
    if math.hypot(ball.vx, ball.vy) < speed:
        return False
    return abs(norm_deg(math.degrees(math.atan2(ball.vy, ball.vx)) - heading)) <= within


def skill_for(method: str, action, side: Side, world: World, me: SimPlayer) -> Skill:
    """The skill that carries out ``action`` (an ontology model); raises SkillError if it cannot start."""
    prm = world.params
    opp_goal = (side.sign * prm.field_length / 2, 0.0)
    if isinstance(action, (act.Kick, act.HoldBall)) and (
        distance(me.x, me.y, world.ball.x, world.ball.y) > prm.kickable_distance
    ):
        raise SkillError("the ball is not kickable")
    if isinstance(action, act.Kick):
        return Once(("kick", action.power, math.degrees(action.direction)), "kick")
    if isinstance(action, act.Dash):
        return Once(("dash", action.power, math.degrees(action.direction)), "dash")
    if isinstance(action, act.Turn):
        return Once(("turn", _turn_moment(world, me, math.degrees(action.angle))), "turn")
    if isinstance(action, act.TurnHead):
        return Once(("turn_neck", math.degrees(action.angle) - me.neck), "turnHead")
    if isinstance(action, act.Tackle):
        return Once(("tackle", math.degrees(action.direction)), "tackle")
    if isinstance(action, act.Catch):
        if not me.goalie:
            raise SkillError("only the goalkeeper can catch")
        return Once(("catch", math.degrees(action.direction)), "catch")
    if isinstance(action, act.Say):
        error = say_error(action.message, prm)
        if error is not None:
            raise SkillError(error)
        return Once(("say", action.message), "say")
    if isinstance(action, act.Move):
        if not move_allowed(world.mode):
            raise SkillError("move is allowed only before a kick-off")
        return Move(action.target.x, action.target.y)
    if isinstance(action, act.MoveTo):
        return MoveTo(*_absolute(side, action.target.x, action.target.y), action.speed)
    if isinstance(action, act.TurnToDirection):
        heading = math.degrees(action.direction) + (0.0 if side is Side.LEFT else 180.0)
        return TurnTo(heading=norm_deg(heading))
    if isinstance(action, act.TurnToObject):
        return TurnTo(target=_object_position(action.obj, side, world))
    if isinstance(action, act.Intercept):
        return Intercept(*opp_goal)
    if isinstance(action, act.HoldBall):
        return HoldBall()
    if isinstance(action, act.Dribble):
        return Dribble(*_absolute(side, action.target.x, action.target.y), action.speed)
    if isinstance(action, act.Shoot):
        target = _absolute(side, action.target.x, action.target.y) if action.target else opp_goal
        return KickTo("shoot", *target, action.power, fastest=True)
    if isinstance(action, act.Pass):
        if action.to is not None:
            mate = world.players.get((side, action.to.player_number or 0))
            if mate is None:
                raise SkillError(f"no team-mate number {action.to.player_number}")
            target = (mate.x, mate.y)
        else:
            target = _absolute(side, action.target.x, action.target.y)
        return KickTo("pass", *target, action.power)
    raise SkillError(f"{type(action).__name__} is not supported by this back-end")


def _object_position(obj, side: Side, world: World) -> tuple[float, float]:
    from cf_lang.ontology import Ball, Goal, Team
    from cf_lang.ontology import Player as PlayerModel

    if isinstance(obj, Ball):
        return (world.ball.x, world.ball.y)
    if isinstance(obj, PlayerModel):
        whose = side if obj.which_team in (None, Team.OUR) else side.other
        p = world.players.get((whose, obj.player_number or 0))
        if p is None:
            raise SkillError(f"no such player: {obj.which_team} {obj.player_number}")
        return (p.x, p.y)
    if isinstance(obj, Goal):
        sign = side.sign if obj.which_team is Team.OPP else -side.sign
        return (sign * world.params.field_length / 2, 0.0)
    if obj.positioning is not None:  # a flag with a given position
        return _absolute(side, obj.positioning.x, obj.positioning.y)
    raise SkillError("cannot locate that object")
