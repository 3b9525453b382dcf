"""Who reaches a rolling ball first (ROS-free): the model behind interceptions, passes and shots.

The ball keeps BALL_DECAY of its speed every cycle; a player needs TURN_CYCLES to face it, then
runs up to his top speed a cycle (PLAYER_SPEED unless the WorldState tells his, START_LOSS metres
behind that pace from a standstill at PLAYER_SPEED), and has the ball once within REACH of it (a
goalkeeper catches within CATCH_REACH), plus how far he may be from where he is believed to be
(``Runner.unsure``). Both back-ends follow rcssserver's physics, so one model serves both.
Positions are in the player's own frame, speeds in metres per cycle.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from cf_lang.ontology import FIELD, Player, Velocity, actions

Point = tuple[float, float]

BALL_DECAY = 0.94
BALL_SPEED_MAX = 2.7  # the fastest one kick makes a still ball
PLAYER_SPEED = 1.0  # rcssserver's default type: dash accel 0.6 a cycle, speed decays by 0.4: tops out at 1.0
START_LOSS = 0.7  # metres lost to accelerating: 0.6, 1.44, 2.38, 3.35 after 1, 2, 3, 4 dashes
TURN_CYCLES = 1
REACH = 1.0
CATCH_REACH = 1.5  # rcssserver's catchable area is 1.2 m by 1 m in the catch direction
HORIZON = 40  # cycles looked ahead: a ball still rolling after that is anybody's
CYCLES_PER_SECOND = 10.0


class Runner(NamedTuple):
    """A player as the model sees him: where he is, whether he may catch, how fast he runs (m/cycle)."""

    pos: Point
    goalie: bool = False
    speed: float = PLAYER_SPEED
    unsure: float = 0.0  # m: how far off ``pos`` he may be (believed, not seen): added to his reach


def top_speed(player: Player | None) -> float:
    """A player's top speed in metres per cycle: as the WorldState tells it (m/s), else PLAYER_SPEED.

    Unknown (an opponent on rcssserver, whose type nobody is told) counts as the default type's,
    which is as fast as any type gets within a few per cent: a pass is not judged safe on the
    hope that an opponent is slow.
    """
    if player is None or player.top_speed is None:
        return PLAYER_SPEED
    return player.top_speed / CYCLES_PER_SECOND


def per_cycle(velocity: Velocity | None) -> Point:
    """An ontology velocity (metres per second) in metres per cycle; none is a still ball."""
    if velocity is None:
        return (0.0, 0.0)
    return (velocity.vx / CYCLES_PER_SECOND, velocity.vy / CYCLES_PER_SECOND)


def pass_speed(dist: float) -> float:
    """The speed a pass leaves the foot with to cover ``dist`` metres (as the action kicks it)."""
    return min(BALL_SPEED_MAX, actions.pass_speed(dist, BALL_DECAY))


def ball_path(start: Point, velocity: Point, cycles: int = HORIZON) -> list[Point]:
    """Where the ball is after 1, 2, ... ``cycles`` cycles."""
    out, (x, y), (vx, vy) = [], start, velocity
    for _ in range(cycles):
        x, y = x + vx, y + vy
        vx, vy = vx * BALL_DECAY, vy * BALL_DECAY
        out.append((x, y))
    return out


def kicked_path(start: Point, target: Point, speed: float) -> list[Point]:
    """The path of a ball kicked from ``start`` towards ``target`` at ``speed``."""
    angle = math.atan2(target[1] - start[1], target[0] - start[0])
    return ball_path(start, (speed * math.cos(angle), speed * math.sin(angle)))


def in_field(path: list[Point]) -> list[Point]:
    """``path`` up to where the ball leaves the field (over a touch line or a goal line)."""
    for n, (x, y) in enumerate(path):
        if abs(y) > FIELD.width / 2 or abs(x) > FIELD.length / 2:
            return path[:n]
    return path


def cycles_to_path(
    player: Point, path: list[Point], reach: float = REACH, react: int = TURN_CYCLES, speed: float = PLAYER_SPEED
) -> int | None:
    """The first cycle in which ``player``, setting off after ``react`` cycles and running up to
    ``speed``, can have a ball on ``path``; None: not within the horizon."""
    loss = START_LOSS * speed / PLAYER_SPEED  # a slower type also gets up to pace slower
    for n, (bx, by) in enumerate(path, start=1):
        run = max(0.0, speed * (n - react) - loss)
        if math.hypot(bx - player[0], by - player[1]) - reach <= run:
            return n
    return None


def cycles_to_ball(me: Point, ball: Point, velocity: Point = (0.0, 0.0), speed: float = PLAYER_SPEED) -> int:
    """How soon I, running up to ``speed``, can have the ball, rolling as it does (velocity in metres per cycle)."""
    if math.hypot(me[0] - ball[0], me[1] - ball[1]) <= REACH:
        return 0
    path = ball_path(ball, velocity)
    n = cycles_to_path(me, path, speed=speed)
    if n is not None:
        return n
    stop = path[-1]  # it stops about there
    return HORIZON + int(math.hypot(me[0] - stop[0], me[1] - stop[1]) / speed)


def first_cycles(path: list[Point], players: list[Runner], react: int = TURN_CYCLES) -> int | None:
    """The earliest cycle any of ``players`` has a ball on ``path``, each setting off after ``react`` cycles."""
    best = None
    for pos, goalie, speed, unsure in players:
        n = cycles_to_path(pos, path, (CATCH_REACH if goalie else REACH) + unsure, react, speed)
        if n is not None and (best is None or n < best):
            best = n
    return best
