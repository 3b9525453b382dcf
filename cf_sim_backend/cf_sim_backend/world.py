"""The simulated world's state and parameters (ROS-free), in the style of rcssserver.

Units: metres, metres per cycle, degrees for bodies and heads (as rcssserver),
cycles of 100 ms. The frame is absolute: the left team attacks towards +x,
the right team towards -x; origin at the centre spot, y to the left.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from enum import StrEnum

from cf_lang.ontology import FIELD

MAX_DASH_POWER = 100.0  # rcssserver 19's max_dash_power


def top_speed(player_speed_max: float, dash_power_rate: float, player_decay: float, effort_max: float = 1.0) -> float:
    """Metres per cycle that repeated full dashes reach (rcssserver's ``real_speed_max`` of a player type).

    Each dash adds ``MAX_DASH_POWER * dash_power_rate * effort_max``, each cycle keeps ``player_decay``
    of the speed: the speed levels off where the two balance, unless the cap is lower.
    """
    accel = MAX_DASH_POWER * dash_power_rate * effort_max
    return min(player_speed_max, accel / max(1e-6, 1.0 - player_decay))


class Side(StrEnum):
    LEFT = "l"
    RIGHT = "r"

    @property
    def other(self) -> Side:
        return Side.RIGHT if self is Side.LEFT else Side.LEFT

    @property
    def sign(self) -> int:
        """+1 if this side attacks towards +x."""
        return 1 if self is Side.LEFT else -1


@dataclass(frozen=True)
class Params:
    """rcssserver's defaults where it has one."""

    field_length: float = FIELD.length
    field_width: float = FIELD.width
    goal_width: float = FIELD.goal_width
    penalty_area_length: float = FIELD.penalty_area_length
    penalty_area_width: float = FIELD.penalty_area_width
    ball_size: float = 0.085
    ball_decay: float = 0.94
    ball_speed_max: float = 3.0
    ball_accel_max: float = 2.7  # the most one kick adds to the ball's velocity
    ball_rand: float = 0.05
    player_size: float = 0.3
    player_decay: float = 0.4
    player_speed_max: float = 1.05
    player_rand: float = 0.1
    dash_power_rate: float = 0.006
    effort_max: float = 1.0  # the share of a dash's power a rested player gets
    effort_min: float = 0.6  # (a heterogeneous type's, kept for the game log: the embedded stamina model
    extra_stamina: float = 50.0  # has no effort decay and no extra stamina)
    side_dash_rate: float = 0.4  # a dash at 90 degrees off the body accelerates this share (rcssserver 14+)
    back_dash_rate: float = 0.7  # and one straight back this share
    kick_power_rate: float = 0.027
    kick_rand: float = 0.1  # a kick's noise at full power (rcssserver's default player type)
    kickable_margin: float = 0.7
    inertia_moment: float = 5.0
    max_moment: float = 180.0
    max_neck_angle: float = 90.0
    stamina_max: float = 8000.0
    stamina_inc_max: float = 45.0
    catchable_area: float = 1.3
    catchable_area_l_stretch: float = 1.0  # a heterogeneous goalkeeper's longer catch
    max_catch_angle: float = 90.0  # degrees off the body a catch may go (rcssserver bounds it there)
    tackle_dist: float = 2.0
    tackle_width: float = 1.25
    tackle_exponent: float = 6.0
    tackle_cycles: int = 10  # a tackler can do nothing else this long, won or not
    kick_off_clearance: float = FIELD.centre_circle_radius
    half_cycles: int = 3000
    halves: int = 2
    goal_pause_cycles: int = 20
    auto_kick_off_cycles: int = 50
    set_piece_timeout: int = 100
    back_passes: bool = True  # the goalkeeper may not catch a team-mate's kick (rcssserver's back_passes)
    foul_detect_probability: float = 0.5  # the referee sees a tackle through a man this often (rcssserver's)
    say_msg_size: int = 10  # characters a say may carry (rcssserver's say_msg_size)
    audio_cut_dist: float = 50.0  # m: a say is heard this far off at most

    @property
    def dash_accel(self) -> float:
        """Metres per cycle a full dash adds to a rested player's speed (before the speed cap)."""
        return MAX_DASH_POWER * self.dash_power_rate * self.effort_max

    @property
    def top_speed(self) -> float:
        """Metres per cycle that repeated full dashes reach (1.0 for rcssserver's default type)."""
        return top_speed(self.player_speed_max, self.dash_power_rate, self.player_decay, self.effort_max)

    @property
    def kickable_distance(self) -> float:
        return self.player_size + self.ball_size + self.kickable_margin

    def dash_rate(self, direction: float) -> float:
        """The share of a dash's power that acts ``direction`` degrees off the body (rcssserver's rule)."""
        off = abs(direction)
        if off > 90.0:
            return self.back_dash_rate - (self.back_dash_rate - self.side_dash_rate) * (1.0 - (off - 90.0) / 90.0)
        return self.side_dash_rate + (1.0 - self.side_dash_rate) * (1.0 - off / 90.0)


@dataclass
class SimBall:
    x: float = 0.0
    y: float = 0.0
    vx: float = 0.0
    vy: float = 0.0


# rcssserver's command counters, in the order its game log writes them.
COUNTED = (
    "kick",
    "dash",
    "turn",
    "catch",
    "move",
    "turn_neck",
    "change_view",
    "say",
    "tackle",
    "pointto",
    "attentionto",
    "change_focus",
)


@dataclass
class SimPlayer:
    side: Side
    number: int
    x: float = 0.0
    y: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    body: float = 0.0  # degrees, absolute, counter-clockwise from +x
    neck: float = 0.0  # degrees, relative to body
    stamina: float = 8000.0
    goalie: bool = False
    ptype: int = 0  # heterogeneous player type (World.types)
    kicks: int = 0  # kicks that reached the ball
    frozen: int = 0  # cycles left in which a tackle keeps the player from any body command
    # The cycle of his last dash: rcssserver calls a tackle through a man who dashed lately a foul.
    dashed_at: int = -10
    # The commands the simulator carried out, counted as rcssserver counts them (by COUNTED): a kick
    # once it reached the ball, a tackle whether it hit or not.
    counts: list[int] = field(default_factory=lambda: [0] * len(COUNTED))

    @property
    def key(self) -> tuple[Side, int]:
        return (self.side, self.number)

    @property
    def head(self) -> float:
        return norm_deg(self.body + self.neck)


@dataclass
class World:
    params: Params = field(default_factory=Params)
    time: int = 0
    mode: str = "before_kick_off"  # rcssserver play mode names, with _l/_r
    score: dict[Side, int] = field(default_factory=lambda: {Side.LEFT: 0, Side.RIGHT: 0})
    ball: SimBall = field(default_factory=SimBall)
    players: dict[tuple[Side, int], SimPlayer] = field(default_factory=dict)
    team_names: dict[Side, str] = field(default_factory=lambda: {Side.LEFT: "left", Side.RIGHT: "right"})
    half: int = 1
    last_touch: tuple[Side, int] | None = None
    mode_since: int = 0
    kick_off_side: Side = Side.LEFT
    types: tuple[Params, ...] = ()  # the heterogeneous types' parameters by id (none: all of ``params``)
    types_seed: int = 0  # the seed they were drawn with (player_types.hetero_types)
    said: tuple[tuple[Side, int, str], ...] = ()  # the says of the cycle just played: heard in this one
    indirect: bool = False  # an indirect free kick's ball: no goal until a second player has touched it
    indirect_kicker: tuple[Side, int] | None = None  # the first player to touch it since

    def player(self, side: Side, number: int) -> SimPlayer:
        return self.players[(side, number)]

    def params_of(self, p: SimPlayer) -> Params:
        """Player ``p``'s parameters: his type's (an unknown type: the default's)."""
        return self.types[p.ptype] if 0 <= p.ptype < len(self.types) else self.params

    def as_player(self, p: SimPlayer) -> World:
        """This world with ``p``'s parameters as its ``params`` (the same players and ball, not copies):
        what the skills read, as the rcssserver adapter's belief gives them its own player's type."""
        return dataclasses.replace(self, params=self.params_of(p))


SAY_CHARACTERS = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 ().+*/?<>_-")


def say_error(text: str, params: Params) -> str | None:
    """Why rcssserver would not carry ``text`` as a say (too long, a character it refuses), or None."""
    if not 1 <= len(text) <= params.say_msg_size:
        return f"a say carries 1 to {params.say_msg_size} characters, not {len(text)}"
    bad = sorted(set(text) - SAY_CHARACTERS)
    if bad:
        return f"a say carries letters, digits and ' ().+*/?<>_-' only, not {''.join(bad)!r}"
    return None


def norm_deg(angle: float) -> float:
    """An angle in degrees in (-180, 180]."""
    angle = math.fmod(angle, 360.0)
    if angle > 180.0:
        angle -= 360.0
    elif angle <= -180.0:
        angle += 360.0
    return angle


def distance(ax: float, ay: float, bx: float, by: float) -> float:
    return math.hypot(bx - ax, by - ay)


def direction_deg(ax: float, ay: float, bx: float, by: float) -> float:
    return math.degrees(math.atan2(by - ay, bx - ax))


# The positions a side takes before a kick-off (its own half, x as for the left side).
KICK_OFF_FORMATION: dict[int, tuple[float, float]] = {
    1: (-50.0, 0.0),
    2: (-36.0, 15.0),
    3: (-38.0, 5.0),
    4: (-38.0, -5.0),
    5: (-36.0, -15.0),
    6: (-22.0, 18.0),
    7: (-24.0, 0.0),
    8: (-22.0, -18.0),
    9: (-10.0, 12.0),
    10: (-1.0, 0.0),
    11: (-10.0, -12.0),
}


def move_allowed(mode: str) -> bool:
    """Whether a move is allowed in this play mode (rcssserver: before a kick-off and after a goal)."""
    return mode.startswith(("before_kick_off", "goal_", "half_time"))


def kick_off_position(side: Side, number: int, taker: bool) -> tuple[float, float]:
    x, y = KICK_OFF_FORMATION.get(number, (-20.0, 0.0))
    if number == 10 and not taker:
        x = -9.5  # outside the centre circle
    return (x * side.sign, y * side.sign)


def world_from_snapshot(snap: dict, params: Params | None = None) -> World:
    """Rebuild a World from Simulator.snapshot() data (what the state topic carries).

    The types are drawn again from the seed and count the snapshot names (each player's row ends
    with his type's id), so the 18 types' parameters need not travel every cycle.
    """
    from cf_sim_backend.player_types import hetero_types  # (it builds on this module)

    w = World(params=params or Params())
    w.time, w.mode = int(snap["t"]), str(snap["mode"])
    w.score = {Side.LEFT: int(snap["score"][0]), Side.RIGHT: int(snap["score"][1])}
    w.ball = SimBall(*(float(v) for v in snap["ball"]))
    if "types" in snap:
        w.types_seed, count = (int(v) for v in snap["types"])
        w.types = hetero_types(w.types_seed, count, w.params)
    for side, number, x, y, vx, vy, body, neck, stamina, goalie, *ptype in snap["players"]:
        p = SimPlayer(
            side=Side(side),
            number=int(number),
            x=x,
            y=y,
            vx=vx,
            vy=vy,
            body=body,
            neck=neck,
            stamina=float(stamina),
            goalie=bool(goalie),
            ptype=int(ptype[0]) if ptype else 0,
        )
        w.players[p.key] = p
    w.half = int(snap.get("half", 1))
    w.said = tuple((Side(side), int(number), str(text)) for side, number, text in snap.get("said", ()))
    return w
