"""Body commands and the movement of ball and players, in the style of rcssserver (ROS-free).

One body command per player per cycle (dash, turn, kick, catch, tackle,
move); turn_neck may come with it. The formulas follow rcssserver's:
kick power falls off with the angle and distance to the ball, dash
acceleration is power x dash_power_rate capped at the maximum speed, turning
is damped by speed (moment / (1 + inertia_moment x speed)), velocities decay
every cycle and get a little random noise. The random generator is passed in,
so a seed makes a match repeatable.
"""

from __future__ import annotations

import math
import random

from cf_sim_backend.world import SimPlayer, World, direction_deg, distance, norm_deg

BODY_COMMANDS = ("dash", "turn", "kick", "catch", "tackle", "move")
STOPPED_MODES = ("before_kick_off", "half_time", "time_over")


class CommandError(ValueError):
    """A command the server would reject (wrong form, not allowed now)."""


def _clamp(value: float, low: float, high: float) -> float:
    return max(low, min(high, value))


def _cap(vx: float, vy: float, limit: float) -> tuple[float, float]:
    speed = math.hypot(vx, vy)
    if speed > limit:
        return vx * limit / speed, vy * limit / speed
    return vx, vy


def ball_distance(world: World, p: SimPlayer) -> float:
    return distance(p.x, p.y, world.ball.x, world.ball.y)


def kickable(world: World, p: SimPlayer) -> bool:
    return ball_distance(world, p) <= world.params_of(p).kickable_distance


def dash(world: World, p: SimPlayer, power: float, direction: float = 0.0) -> None:
    prm = world.params_of(p)
    power = _clamp(power, -100.0, 100.0)
    cost = abs(power) * (2.0 if power < 0 else 1.0)
    effort = prm.effort_max if p.stamina >= cost else 0.3  # an exhausted player barely accelerates
    p.stamina = max(0.0, p.stamina - cost)
    direction = _clamp(direction, -180.0, 180.0)
    accel = power * prm.dash_power_rate * effort * prm.dash_rate(direction)
    angle = math.radians(p.body + direction)
    p.vx, p.vy = _cap(p.vx + accel * math.cos(angle), p.vy + accel * math.sin(angle), prm.player_speed_max)


def turn(world: World, p: SimPlayer, moment: float) -> None:
    prm = world.params_of(p)
    moment = _clamp(moment, -prm.max_moment, prm.max_moment)
    speed = math.hypot(p.vx, p.vy)
    p.body = norm_deg(p.body + moment / (1.0 + prm.inertia_moment * speed))


def turn_neck(world: World, p: SimPlayer, angle: float) -> None:
    limit = world.params.max_neck_angle
    p.neck = _clamp(p.neck + angle, -limit, limit)


def kick(world: World, p: SimPlayer, power: float, direction: float, rng: random.Random | None = None) -> bool:
    """Kick the ball if it is kickable; return whether it was touched.

    With ``rng``, the kick gets rcssserver's noise: up to kick_rand x power share x (0.5..1 for the
    ball's place off the body and foot + 0.5..1 for its speed) m/cycle, in any direction.
    """
    prm = world.params_of(p)
    if not kickable(world, p):
        return False
    power = _clamp(power, 0.0, 100.0)
    ball_dir = direction_deg(p.x, p.y, world.ball.x, world.ball.y)
    dir_diff = abs(norm_deg(ball_dir - p.body))
    dist_ball = max(0.0, ball_distance(world, p) - prm.player_size - prm.ball_size)
    rate = prm.kick_power_rate * (1.0 - 0.25 * dir_diff / 180.0 - 0.25 * dist_ball / prm.kickable_margin)
    accel = min(power * rate, prm.ball_accel_max)
    angle = math.radians(p.body + _clamp(direction, -180.0, 180.0))
    b = world.ball
    ax, ay = accel * math.cos(angle), accel * math.sin(angle)
    if rng is not None:
        pos_rate = 0.5 + 0.25 * (dir_diff / 180.0 + dist_ball / prm.kickable_margin)
        speed_rate = 0.5 + 0.5 * math.hypot(b.vx, b.vy) / (prm.ball_speed_max * prm.ball_decay)
        size = rng.uniform(0.0, prm.kick_rand * power / 100.0 * (pos_rate + speed_rate))
        heading = rng.uniform(-math.pi, math.pi)
        ax, ay = _cap(ax + size * math.cos(heading), ay + size * math.sin(heading), prm.ball_accel_max)
    b.vx, b.vy = _cap(b.vx + ax, b.vy + ay, prm.ball_speed_max)
    p.kicks += 1
    return True


def catch(world: World, p: SimPlayer, direction: float) -> bool:
    """A goalkeeper in its own penalty area catches a ball in reach in that direction (bounded to
    max_catch_angle off his body, as rcssserver bounds it: a ball behind him is not caught)."""
    prm = world.params_of(p)
    if not p.goalie or not in_own_penalty_area(world, p):
        return False
    direction = max(-prm.max_catch_angle, min(prm.max_catch_angle, direction))
    if ball_distance(world, p) > prm.catchable_area * prm.catchable_area_l_stretch:
        return False
    ball_dir = direction_deg(p.x, p.y, world.ball.x, world.ball.y)
    if abs(norm_deg(ball_dir - (p.body + direction))) > 45.0:
        return False
    world.ball.vx = world.ball.vy = 0.0
    return True


def tackle_failure(world: World, p: SimPlayer) -> float:
    """The chance a tackle misses the ball where it is now (rcssserver's; 1: out of the tackle area)."""
    prm = world.params
    rel = math.radians(direction_deg(p.x, p.y, world.ball.x, world.ball.y) - p.body)
    d = distance(p.x, p.y, world.ball.x, world.ball.y)
    ahead, aside = d * math.cos(rel), d * math.sin(rel)
    if ahead <= 0.0:
        return 1.0  # behind the body: rcssserver's tackle_back_dist is 0
    chance = (ahead / prm.tackle_dist) ** prm.tackle_exponent + (abs(aside) / prm.tackle_width) ** prm.tackle_exponent
    return min(1.0, chance)


def tackle(world: World, p: SimPlayer, direction: float, rng: random.Random) -> bool:
    """Tackle towards ``direction`` (degrees from the body), as rcssserver 12+ does; return whether it hit.

    It may miss (:func:`tackle_failure`); either way the player can do nothing else for
    ``tackle_cycles``. A hit pushes the ball with up to 100 x kick_power_rate, less the further the
    direction turns from the body and the ball lies off it.
    """
    prm = world.params
    p.frozen = prm.tackle_cycles - 1  # the tackle's own cycle is the first
    if rng.random() < tackle_failure(world, p):
        return False
    angle = norm_deg(_clamp(direction, -180.0, 180.0))
    off = abs(norm_deg(direction_deg(p.x, p.y, world.ball.x, world.ball.y) - p.body))
    power = 100.0 * (1.0 - abs(angle) / 180.0) * prm.kick_power_rate * (1.0 - 0.5 * off / 180.0)
    heading = math.radians(p.body + angle)
    b = world.ball
    b.vx, b.vy = _cap(b.vx + power * math.cos(heading), b.vy + power * math.sin(heading), prm.ball_speed_max)
    p.kicks += 1
    return True


def foul_risk(world: World, tackler: SimPlayer, margin: float = 0.0) -> list[SimPlayer]:
    """The opponents a tackle by ``tackler`` now may foul (rcssserver's Referee::checkFoul, a foul not
    meant): each has the ball in kicking reach and stands between the tackler and the ball (nearer
    than it, ahead within the two bodies' width), facing within 90 degrees of the ball's way from
    the tackler. The referee also asks that he dashed lately, and sees each with
    ``foul_detect_probability``. ``margin`` (m) widens the place he stands in, for a belief's error.
    """
    b = world.ball
    ball_way = math.atan2(b.y - tackler.y, b.x - tackler.x)
    ball_dist = math.hypot(b.x - tackler.x, b.y - tackler.y)
    out = []
    for p in world.players.values():
        if p.side is tackler.side or math.hypot(p.x - b.x, p.y - b.y) > world.params_of(p).kickable_distance:
            continue
        dx, dy = p.x - tackler.x, p.y - tackler.y
        ahead = dx * math.cos(ball_way) + dy * math.sin(ball_way)
        aside = -dx * math.sin(ball_way) + dy * math.cos(ball_way)
        if (
            math.hypot(dx, dy) > ball_dist + margin
            or ahead < -margin
            or abs(aside) > 2 * world.params.player_size + margin
        ):
            continue
        if abs(norm_deg(p.body - math.degrees(ball_way))) > 90.0:
            continue
        out.append(p)
    return out


def in_own_penalty_area(world: World, p: SimPlayer) -> bool:
    prm = world.params
    own_goal_x = -p.side.sign * prm.field_length / 2
    return abs(p.x - own_goal_x) <= prm.penalty_area_length and abs(p.y) <= prm.penalty_area_width / 2


def _advance(obj, rand: float, decay: float, rng: random.Random) -> None:
    """One cycle of motion for the ball or a player: noise on the velocity, move, decay."""
    speed = math.hypot(obj.vx, obj.vy)
    if speed > 0.0:
        noise = rand * speed
        obj.vx += rng.uniform(-noise, noise)
        obj.vy += rng.uniform(-noise, noise)
    obj.x += obj.vx
    obj.y += obj.vy
    obj.vx *= decay
    obj.vy *= decay


def move_objects(world: World, rng: random.Random) -> None:
    """Advance ball and players one cycle: position += velocity, velocity decays, with noise."""
    prm = world.params
    _advance(world.ball, prm.ball_rand, prm.ball_decay, rng)
    for p in world.players.values():
        own = world.params_of(p)
        _advance(p, own.player_rand, own.player_decay, rng)
        p.stamina = min(own.stamina_max, p.stamina + own.stamina_inc_max)
    collide(world)


def collide(world: World) -> None:
    """Players and the ball cannot overlap: push them apart and damp their speed, as rcssserver does."""
    prm = world.params
    players = list(world.players.values())
    limit = 2 * prm.player_size
    for i, a in enumerate(players):
        for b in players[i + 1 :]:
            d = distance(a.x, a.y, b.x, b.y)
            if d < limit:
                if d < 1e-6:
                    dx, dy, d = 1.0, 0.0, 1.0
                else:
                    dx, dy = (b.x - a.x) / d, (b.y - a.y) / d
                push = (limit - d) / 2
                a.x, a.y = a.x - dx * push, a.y - dy * push
                b.x, b.y = b.x + dx * push, b.y + dy * push
                a.vx, a.vy, b.vx, b.vy = -0.1 * a.vx, -0.1 * a.vy, -0.1 * b.vx, -0.1 * b.vy
    ball = world.ball
    limit = prm.player_size + prm.ball_size
    for p in players:
        d = ball_distance(world, p)
        if d < limit:
            if d < 1e-6:
                dx, dy, d = 1.0, 0.0, 1.0
            else:
                dx, dy = (ball.x - p.x) / d, (ball.y - p.y) / d
            ball.x, ball.y = p.x + dx * limit, p.y + dy * limit
            ball.vx, ball.vy = -0.1 * ball.vx, -0.1 * ball.vy
