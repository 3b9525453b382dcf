"""The referee: kick-off, goals, ball out of play, offside, half and full time (ROS-free).

Play modes use rcssserver's names with the side that has the ball:
before_kick_off, kick_off_l/r, play_on, kick_in_l/r, corner_kick_l/r,
goal_kick_l/r, free_kick_l/r (after offside or a goalkeeper's catch),
indirect_free_kick_l/r (after a back pass the goalkeeper caught), goal_l/r (the
side that scored), half_time, time_over. In a set piece the ball lies still
until the side that has it kicks; opponents are kept 9.15 m away (at an indirect
free kick they may stand on their goal line), and a ball kicked from an indirect
free kick scores only after a second player has touched it.
"""

from __future__ import annotations

import math

from cf_lang.ontology import FIELD
from cf_sim_backend.world import Side, SimPlayer, World, kick_off_position

SET_PIECES = ("kick_off", "kick_in", "corner_kick", "goal_kick", "free_kick", "indirect_free_kick")


def set_mode(world: World, mode: str) -> None:
    if world.mode != mode:
        world.mode = mode
        world.mode_since = world.time


def set_piece_side(world: World) -> Side | None:
    """The side that may play the ball in the current set piece, or None."""
    for piece in SET_PIECES:
        if world.mode.startswith(piece + "_"):
            return Side(world.mode[-1])
    return None


def place_for_kick_off(world: World, side: Side) -> None:
    world.ball.x = world.ball.y = world.ball.vx = world.ball.vy = 0.0
    for p in world.players.values():
        p.x, p.y = kick_off_position(p.side, p.number, taker=p.side is side)
        p.vx = p.vy = 0.0
        p.body = 0.0 if p.side is Side.LEFT else 180.0
        p.neck = 0.0
    world.kick_off_side = side
    world.last_touch = None
    world.indirect, world.indirect_kicker = False, None


def start_set_piece(world: World, piece: str, side: Side, x: float, y: float) -> None:
    b = world.ball
    b.x, b.y, b.vx, b.vy = x, y, 0.0, 0.0
    world.last_touch = None
    world.indirect, world.indirect_kicker = piece == "indirect_free_kick", None
    set_mode(world, f"{piece}_{side.value}")


def out_of_goal_area(world: World, x: float, y: float) -> tuple[float, float]:
    """A free kick's spot: a ball within a goal area is put on its front line (rcssserver's moveOutOfGoalArea)."""
    edge = world.params.field_length / 2 - FIELD.goal_area_length
    if abs(x) > edge and abs(y) <= FIELD.goal_area_width / 2:
        x = math.copysign(edge, x)
    return x, y


def foul_spot(world: World, tackler: SimPlayer) -> tuple[float, float]:
    """Where the free kick for a foul by ``tackler`` is taken (rcssserver's FoulRef::callFoul): where
    he stood, out of either goal area and out of the penalty area he attacks."""
    prm = world.params
    half_length, half_width = prm.field_length / 2, prm.field_width / 2
    x = max(-half_length, min(half_length, tackler.x))
    x, y = out_of_goal_area(world, x, max(-half_width, min(half_width, tackler.y)))
    box_edge = half_length - prm.penalty_area_length
    if x * tackler.side.sign > box_edge and abs(y) <= prm.penalty_area_width / 2:
        x = tackler.side.sign * box_edge
    return x, y


def keep_opponents_away(world: World) -> None:
    side = set_piece_side(world)
    if side is None:
        return
    b = world.ball
    radius = world.params.kick_off_clearance
    goal_line = world.params.field_length / 2
    for p in world.players.values():
        if p.side is side or (world.indirect and abs(p.x) >= goal_line):
            continue  # (at an indirect free kick a defender may stand on his goal line, as in rcssserver)
        dx, dy = p.x - b.x, p.y - b.y
        d = (dx * dx + dy * dy) ** 0.5
        if d < radius:
            if d < 1e-6:
                dx, dy, d = -side.sign, 0.0, 1.0
            p.x, p.y = b.x + dx / d * radius, b.y + dy / d * radius
            if world.indirect and abs(p.x) > goal_line:  # pushed behind it: onto it, on the same ray
                p.x, p.y = math.copysign(goal_line, p.x), b.y + dy / dx * (math.copysign(goal_line, p.x) - b.x)


def offside_players(world: World, kicker_side: Side, kicker_number: int) -> set[int]:
    """Team-mates of the kicker in an offside position at the moment of the kick."""
    sign = kicker_side.sign
    opponents = sorted((p.x * sign for p in world.players.values() if p.side is not kicker_side), reverse=True)
    second_last = opponents[1] if len(opponents) >= 2 else 0.0
    ball_x = world.ball.x * sign
    line = max(second_last, ball_x, 0.0)
    return {
        p.number
        for p in world.players.values()
        if p.side is kicker_side and p.number != kicker_number and p.x * sign > line + 1e-9
    }


SHOT_RANGE = 30.0  # m from the goal line: a kick from further out is not counted as a shot
POST_MARGIN = 1.0  # m outside a post a shot may be aimed and still count (it was meant for the corner)


def is_shot(world: World, side: Side) -> bool:
    """Whether the ball, as ``side`` has just kicked it, is a shot: kicked from within SHOT_RANGE of
    the goal ``side`` attacks, it rolls as far as that goal line and crosses it between the posts
    (or within POST_MARGIN of one).

    Aimed at the goal, not at its centre: a shot into a corner from 20 m is 19 degrees off the
    centre (the embedded demo once showed a goal scored with no shot).
    """
    prm, b = world.params, world.ball
    goal_x = side.sign * prm.field_length / 2
    ahead = (goal_x - b.x) * side.sign  # m to the goal line
    towards = b.vx * side.sign  # m/cycle towards it
    if not 0.0 <= ahead <= SHOT_RANGE or towards <= 0.0:
        return False
    crossing_y = b.y + b.vy * (ahead / towards)
    if abs(crossing_y) > prm.goal_width / 2 + POST_MARGIN:
        return False
    rolls = math.hypot(b.vx, b.vy) / (1.0 - prm.ball_decay)  # how far the ball goes untouched
    return rolls >= math.hypot(ahead, crossing_y - b.y)


def check_ball(world: World) -> str | None:
    """After the ball moved in play_on: goal or out of play. Returns an event, if any."""
    prm = world.params
    b = world.ball
    half_length, half_width = prm.field_length / 2, prm.field_width / 2
    if abs(b.x) > half_length:
        goal_side = Side.RIGHT if b.x > 0 else Side.LEFT  # whose goal line it crossed
        attacker = goal_side.other
        if abs(b.y) < prm.goal_width / 2 and not world.indirect:
            world.score[attacker] += 1
            set_mode(world, f"goal_{attacker.value}")
            b.vx = b.vy = 0.0
            return f"goal {attacker.value}"
        toucher = world.last_touch[0] if world.last_touch else attacker
        if toucher is goal_side:  # the defenders put it out: corner
            y = half_width - 0.5 if b.y > 0 else -(half_width - 0.5)
            start_set_piece(world, "corner_kick", attacker, (half_length - 0.5) * (1 if b.x > 0 else -1), y)
            return f"corner {attacker.value}"
        x = (half_length - 5.5) * (1 if b.x > 0 else -1)
        start_set_piece(world, "goal_kick", goal_side, x, 0.0)
        return f"goal kick {goal_side.value}"
    if abs(b.y) > half_width:
        toucher = world.last_touch[0] if world.last_touch else Side.LEFT
        y = half_width if b.y > 0 else -half_width
        start_set_piece(world, "kick_in", toucher.other, max(-half_length, min(half_length, b.x)), y)
        return f"kick in {toucher.other.value}"
    return None


def advance_clock(world: World) -> str | None:
    """Count the cycle; end halves and the match. Returns an event, if any."""
    prm = world.params
    if world.mode in ("before_kick_off", "half_time", "time_over"):
        return None
    world.time += 1
    if world.time >= prm.half_cycles * world.half:
        if world.half >= prm.halves:
            set_mode(world, "time_over")
            return "time over"
        world.half += 1
        second = world.kick_off_side.other
        place_for_kick_off(world, second)
        set_mode(world, "half_time")
        world.kick_off_side = second
        return "half time"
    return None
