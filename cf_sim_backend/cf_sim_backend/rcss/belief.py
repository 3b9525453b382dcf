"""What one rcssserver player knows (ROS-free): itself, the ball, the others and the game, with uncertainty and ages.

A :class:`Belief` reads every server message (init, params, sense_body, see, hear) and keeps:

- its own pose, localised from the flags of each ``see`` and carried between sees by the sensed speed
  and the turns it commanded (the uncertainty grows while it is not seen);
- the ball, placed from the latest sighting (velocity from the server's distance/direction change when
  it gives one), rolled on with the ball's decay while not seen; its age counts cycles since seen;
- the other players by team and number, kept with growing uncertainty until :data:`PLAYER_MEMORY`
  cycles old; a sighting without a number updates the known player nearest it, if one is near
  enough, else it lives for one see;
- the play mode (referee) and the score.

It speaks two frames. The server's: y towards the bottom side line, angles positive clockwise. The
embedded simulator's absolute frame (:mod:`world`), which the shared skills use: x as the server's, y
and angles mirrored. :meth:`Belief.world` gives a :class:`World` for the skills;
:func:`world_state` gives what the perception service tells, in the player's own frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from cf_lang.ontology import (
    FIELD,
    AbsolutePositioning,
    Ball,
    Game,
    Heard,
    Player,
    RelativePositioning,
    Team,
    Velocity,
    WorldState,
)
from cf_sim_backend.perception import relative_mode, to_own_frame, yaw_in_own_frame
from cf_sim_backend.rcss.localise import localise
from cf_sim_backend.rcss.protocol import param_pairs, read_see
from cf_sim_backend.world import Params, Side, SimBall, SimPlayer, World, norm_deg, top_speed

PLAYER_MEMORY = 30  # cycles a player not seen again is still reported
BALL_MEMORY = 100  # cycles the ball's estimate is still reported
SELF_SIGMA_GROWTH = 0.1  # m per cycle without a see
BALL_SIGMA_GROWTH = 0.2
PLAYER_SIGMA_GROWTH = 0.4
# An unseen player runs on as last seen: the see shows his velocity after the cycle's decay
# (player_decay, 0.4 for most types), so his step was that over the decay; he is taken to keep
# making it, RUN_ON of it less each cycle (the figure fitted to HELIOS base's men on game logs).
RUN_ON = 0.9
RUN_MOST = 1.2  # m a cycle: no type runs faster (a noisy sighting's velocity over the decay may say so)
MATCH_GATE = 1.5  # m: a sighting without a number is a known player believed this close to it, plus
MATCH_RUN = 1.2  # m per cycle since he was last seen (a player's top speed, with noise), up to
MATCH_MOST = 6.0  # m
HEARD_KEPT = 4  # team-mates' says kept: (time heard, number, text)
UNSURE = 50.0  # m: the sigma of a pose we know nothing about
HALF_VIEW = {"narrow": 30.0, "normal": 60.0, "wide": 90.0}  # degrees each side of the head (synch see, v18+)
QUANT = 0.05  # relative distance error of moving objects (the server rounds log(distance) to 0.1)

# rcssserver play modes the embedded simulator's names do not have, as the nearest of those.
_FOUL = (
    "free_kick_fault",
    "back_pass",
    "catch_fault",
    "foul_charge",
    "foul_push",
    "foul_multiple_attack",
    "foul_multiple_attacker",
    "foul_ballout",
    "illegal_defense",
    "foul",
)
_INDIRECT_AFTER = ("back_pass",)  # fouls whose free kick is always an indirect one (rcssserver's CatchRef)
_FOR_SIDE = ("goalie_catch_ball", "penalty_setup", "penalty_ready", "penalty_taken")
_SIDED = ("kick_off", "kick_in", "corner_kick", "goal_kick", "free_kick", "indirect_free_kick", "offside", "goal")
# The embedded simulator's play modes (absolute): what the rest of the adapter understands.
SIM_MODES = frozenset(
    ["before_kick_off", "play_on", "drop_ball", "half_time", "time_over"]
    + [f"{base}_{side}" for base in _SIDED for side in ("l", "r")]
)
# Referee messages that are no play mode: the game goes on as it was.
_NOT_A_MODE = ("yellow_card_", "red_card_", "pause", "human_judge", "time_extended")


def sim_mode(mode: str) -> str | None:
    """An rcssserver play mode as the embedded simulator names it (absolute _l/_r kept); None if unknown."""
    if mode.startswith("goal_l_") or mode.startswith("goal_r_"):
        return mode[:6]
    base, _, who = mode.rpartition("_")
    if who in ("l", "r"):
        if base in _FOUL:
            kind = "indirect_free_kick" if base in _INDIRECT_AFTER else "free_kick"
            return f"{kind}_{'r' if who == 'l' else 'l'}"
        if base in _FOR_SIDE:
            return f"free_kick_{who}"
        if base.startswith("penalty"):
            return "play_on"
    if mode in ("time_up", "time_up_without_a_team"):
        return "time_over"
    if mode == "first_half_over":
        return "half_time"
    return mode if mode in SIM_MODES else None


@dataclass
class Track:
    """An object's estimate in the server's frame: position, velocity (m/cycle), sigma (m), last cycle seen."""

    x: float
    y: float
    vx: float = 0.0
    vy: float = 0.0
    sigma: float = 0.1
    seen: int = 0
    body: float | None = None  # degrees, server frame
    goalie: bool = False


@dataclass
class OwnPlayer:
    """The player's own state, server frame."""

    x: float = 0.0
    y: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    body: float = 0.0
    neck: float = 0.0  # relative to the body, server frame
    stamina: float = 8000.0
    sigma: float = UNSURE  # nothing known before the first see
    sigma_head: float = 180.0
    localised: int = -1  # cycle of the last see that placed us
    view_width: str = "normal"

    @property
    def head(self) -> float:
        return norm_deg(self.body + self.neck)


@dataclass
class Belief:
    """The player's belief, updated by :meth:`update` with every parsed server message."""

    team: str
    goalie: bool = False
    side: Side | None = None
    number: int = 0
    time: int = 0
    mode: str = "before_kick_off"  # the embedded simulator's names (see sim_mode)
    server_mode: str = "before_kick_off"
    score: dict[Side, int] = field(default_factory=lambda: {Side.LEFT: 0, Side.RIGHT: 0})
    half: int = 1
    server: dict[str, float | str] = field(default_factory=dict)
    player_types: dict[int, dict[str, float | str]] = field(default_factory=dict)
    mate_types: dict[int, int] = field(default_factory=dict)  # shirt number -> type, as told (mine too)
    me: OwnPlayer = field(default_factory=OwnPlayer)
    ball: Track | None = None
    players: dict[tuple[str, int], Track] = field(default_factory=dict)  # (team name, number)
    anonymous: list[tuple[str | None, Track]] = field(default_factory=list)
    opponent: str | None = None
    counters: dict[str, int] = field(default_factory=dict)
    tackle_expires: int = 0  # cycles our last tackle still holds us (sense_body)
    see_time: int = -1
    sense_time: int = -1
    # Server steps (one sense_body each): the clock stands still in some play modes (before a
    # kick-off, after a goal, at an offside or a foul), while the server goes on stepping and
    # executes one body command of each player a step.
    steps: int = 0
    sees: int = 0  # sees read (in a pause they come with the same time, as the sense_bodies do)
    errors: list[str] = field(default_factory=list)
    referee_notes: list[str] = field(default_factory=list)  # the latest cards and pauses
    heard: list[tuple[int, int, str]] = field(default_factory=list)  # team-mates' says: (time, number, text)
    # Turns, moves and kicks we sent, by command: (the server's counter of it when sent, the server
    # step then, its effect). Applied once a sense_body's counter shows the server executed it.
    pending: dict[str, tuple[int | None, int, tuple[float, ...]]] = field(default_factory=dict)

    # ---- reading the server ---------------------------------------------------

    def update(self, msg: list) -> str:
        """Take one parsed server message into account; returns its kind (e.g. "see", "think")."""
        kind = str(msg[0]) if msg else ""
        handler = getattr(self, f"_on_{kind}", None)
        if handler is not None:
            handler(msg)
        return kind

    def _on_init(self, msg: list) -> None:  # (init l 1 before_kick_off)
        if len(msg) >= 4:
            self.side, self.number = Side(str(msg[1])), int(msg[2])
            self._set_mode(str(msg[3]))

    def _on_reconnect(self, msg: list) -> None:  # (reconnect l play_mode)
        if len(msg) >= 3:
            self.side = Side(str(msg[1]))
            self._set_mode(str(msg[2]))

    def _on_server_param(self, msg: list) -> None:
        self.server.update(param_pairs(msg))

    def _on_player_type(self, msg: list) -> None:
        values = param_pairs(msg)
        if "id" in values:
            self.player_types[int(values["id"])] = values

    def _on_change_player_type(self, msg: list) -> None:  # (change_player_type UNUM [TYPE])
        # The server tells a team-mate's new type, an opponent's only that it changed; at the
        # (re)connection it tells every type other than the default again.
        if len(msg) >= 3:
            self.mate_types[int(msg[1])] = int(msg[2])

    def note_error(self, text: str) -> None:
        """Keep the latest 20 errors (the server's, or messages that did not parse)."""
        self.errors = [*self.errors[-19:], text]

    def _on_error(self, msg: list) -> None:
        self.note_error(" ".join(str(x) for x in msg[1:]))

    _on_warning = _on_error

    def _on_hear(self, msg: list) -> None:  # (hear T referee MODE) | (hear T self "..") | (hear T dir our 3 "..")
        if len(msg) >= 4 and str(msg[2]) == "referee":
            self._set_mode(str(msg[3]))
        elif len(msg) >= 6 and str(msg[3]) == "our":
            # A team-mate's say (protocol 8+); "(hear T our 3)" without the message: over the capacity.
            try:
                number, text = int(msg[4]), str(msg[5])
            except (TypeError, ValueError):
                return
            if 1 <= number <= 11 and 1 <= len(text) <= 64:
                self.heard = [*self.heard[-(HEARD_KEPT - 1) :], (int(msg[1]), number, text)]

    def _set_mode(self, mode: str) -> None:
        if mode.startswith(_NOT_A_MODE):  # a card, a pause: noted, the play mode stays
            self.referee_notes = [*self.referee_notes[-19:], mode]
            return
        ours = sim_mode(mode)
        if ours is None:  # a message of a newer server: never fatal
            self.note_error(f"unknown referee message {mode!r}: the play mode stays {self.mode}")
            return
        self.server_mode = mode
        self._place_ball(mode)
        if mode.startswith(("goal_l_", "goal_r_")) and mode[7:].isdigit():
            self.score[Side(mode[5])] = int(mode[7:])
        if mode == "half_time":
            self.half += 1
        near_ball = self.ball is not None and math.hypot(self.ball.x - self.me.x, self.ball.y - self.me.y) < 10.0
        if mode.startswith(("goal_", "half_time", "kick_off_")) or (mode != "play_on" and near_ball):
            # The server may put us elsewhere (own half before a kick-off; 9.15 m from the ball at a set
            # piece): we know nothing until the next see.
            self.me.sigma = max(self.me.sigma, UNSURE)
        self.mode = ours

    def _place_ball(self, mode: str) -> None:
        """Where the server puts the ball for a kick-off, kick-in, goal kick or corner (rcssserver's referee)."""
        b = self.ball
        if mode.startswith("kick_off_"):
            # On the centre spot, wherever it was believed: a ball believed in the goal it went into
            # stayed there for 50 cycles of play for a midfielder who never faced the real one.
            self.ball = Track(0.0, 0.0, 0.0, 0.0, 1.0 if b is None else max(b.sigma, 1.0), self.time)
            return
        if b is None or not mode.startswith(("kick_in_", "goal_kick_", "corner_kick_")):
            return
        half_length, half_width = FIELD.length / 2, FIELD.width / 2
        left = mode.endswith("_l")
        if mode.startswith("kick_in_"):
            x, y = max(-half_length, min(half_length, b.x)), max(-half_width, min(half_width, b.y))
        elif mode.startswith("goal_kick_"):
            x = (-half_length + FIELD.goal_area_length) if left else (half_length - FIELD.goal_area_length)
            y = math.copysign(FIELD.goal_area_width / 2, b.y)
        else:
            x = (half_length - 1.0) if left else (-half_length + 1.0)
            y = math.copysign(half_width - 1.0, b.y)
        self.ball = Track(x, y, 0.0, 0.0, max(b.sigma, 1.0), b.seen)

    def _on_sense_body(self, msg: list) -> None:
        self.time = self.sense_time = int(msg[1])
        self.steps += 1
        parts = {str(item[0]): item[1:] for item in msg[2:] if isinstance(item, list) and item}
        me = self.me
        if "view_mode" in parts and len(parts["view_mode"]) == 2:
            me.view_width = str(parts["view_mode"][1])
        if "stamina" in parts:
            me.stamina = float(parts["stamina"][0])
        if "head_angle" in parts:
            me.neck = float(parts["head_angle"][0])
        for name in ("kick", "dash", "turn", "turn_neck", "catch", "move", "change_view", "say"):
            if name in parts and isinstance(parts[name][0], (int, float)):
                self.counters[name] = int(parts[name][0])
        if "tackle" in parts:  # (tackle (expires N) (count N)): N cycles left in which a tackle holds us
            fields = {str(f[0]): f[1] for f in parts["tackle"] if isinstance(f, list) and len(f) == 2}
            if isinstance(fields.get("count"), (int, float)):
                self.counters["tackle"] = int(fields["count"])
            expires = fields.get("expires", 0)
            self.tackle_expires = int(expires) if isinstance(expires, (int, float)) else 0
        # Dead reckoning: the body turned as commanded, if the server executed the turn (a command
        # that came late, on a loaded machine, runs a cycle later or never, and a replay runs none);
        # it moved by this cycle's speed before its decay.
        self._apply_executed()
        if "speed" in parts and len(parts["speed"]) == 2:
            amount, direction = (float(v) for v in parts["speed"])
            angle = math.radians(me.head + direction)
            me.vx, me.vy = amount * math.cos(angle), amount * math.sin(angle)
        decay = float(self.param("player_decay", 0.4)) or 0.4
        # (collision ...) since protocol 13: what we ran into this cycle. The server then turned
        # our speed round (times -0.1) after it moved us: the step we made was the other way.
        collided = None
        if "collision" in parts:
            collided = {str(c[0]) for c in parts["collision"] if isinstance(c, list) and c}
        step = decay if not collided else -0.1 * decay
        me.x += me.vx / step
        me.y += me.vy / step
        me.sigma += SELF_SIGMA_GROWTH
        me.sigma_head += 1.0
        self._roll_on(collided)

    def _apply_executed(self) -> None:
        me = self.me
        for kind, (count, sent_at, effect) in list(self.pending.items()):
            now = self.counters.get(kind)
            if count is None or now is None or now > count:  # executed (or no counter to tell)
                del self.pending[kind]
                if kind == "turn":
                    me.body = norm_deg(me.body + effect[0])
                elif kind == "kick":
                    self._kicked(*effect)
                else:  # move
                    me.x, me.y, me.vx, me.vy = effect[0], effect[1], 0.0, 0.0
            elif self.steps > sent_at + 1:  # two sense_bodies without it: the server dropped it
                del self.pending[kind]

    def _roll_on(self, collided: set[str] | None = None) -> None:
        """Carry the ball one cycle on (it decays, and bounces off our body) and grow every estimate's uncertainty.

        ``collided``: what the sense_body says we ran into (None: it does not say, older protocols).
        """
        if self.ball is not None:
            decay = float(self.server.get("ball_decay", 0.94))
            self.ball.x += self.ball.vx
            self.ball.y += self.ball.vy
            self.ball.vx *= decay
            self.ball.vy *= decay
            self.ball.sigma += BALL_SIGMA_GROWTH
            if "ball" in (collided or ()) or (collided is None and self._touching()):
                self._bounce()
        decay = float(self.server.get("player_decay", 0.4)) or 0.4  # the default type's: theirs are not told
        for track in self.players.values():
            track.x, track.y, track.vx, track.vy = run_on(track.x, track.y, track.vx, track.vy, 1, decay)
            track.sigma += PLAYER_SIGMA_GROWTH
        self.players = {k: t for k, t in self.players.items() if self.time - t.seen <= PLAYER_MEMORY}

    def _contact(self) -> float:
        """The distance at which the ball touches our body."""
        return float(self.param("player_size", 0.3)) + float(self.server.get("ball_size", 0.085))

    def _touching(self) -> bool:
        """The believed ball overlaps our body."""
        return math.hypot(self.ball.x - self.me.x, self.ball.y - self.me.y) < self._contact()

    def _bounce(self) -> None:
        """The ball bounced off our body, as the server has it: put against the body, its velocity
        times -0.1. A kick that took out the old velocity went astray (passes off by up to 130 degrees)."""
        ball, me, contact = self.ball, self.me, self._contact()
        d = math.hypot(ball.x - me.x, ball.y - me.y)
        if d > 1e-6:
            ball.x, ball.y = me.x + (ball.x - me.x) * contact / d, me.y + (ball.y - me.y) * contact / d
        ball.vx, ball.vy = -0.1 * ball.vx, -0.1 * ball.vy

    def _on_see(self, msg: list) -> None:
        see = read_see(msg)
        self.time = self.see_time = see.time
        self.sees += 1
        me = self.me
        pose = localise(see.flags())
        if pose is not None:
            me.x, me.y = pose.x, pose.y
            me.body = norm_deg(pose.head - me.neck)
            me.sigma, me.sigma_head, me.localised = pose.sigma_xy, max(pose.sigma_head, 0.5), see.time
        head = math.radians(me.head)
        self.anonymous = []
        for obj in see.objects:
            name = obj.name.split(" ")
            if name[0] not in ("b", "B", "p", "P") or obj.distance is None:
                continue
            d, a = obj.distance, math.radians(obj.direction)
            x, y = me.x + d * math.cos(head + a), me.y + d * math.sin(head + a)
            sigma = me.sigma + QUANT * d
            if name[0] in ("b", "B"):
                vx, vy = self.ball.vx if self.ball else 0.0, self.ball.vy if self.ball else 0.0
                if len(obj.extra) >= 2 and isinstance(obj.extra[0], float):
                    vx, vy = _velocity(d, a, obj.extra[0], obj.extra[1], head, me)
                self.ball = Track(x, y, vx, vy, sigma, see.time)
                continue
            track = Track(x, y, sigma=sigma, seen=see.time, goalie="goalie" in name)
            numbers = [v for v in obj.extra if isinstance(v, float)]
            if len(numbers) >= 4:  # dist change, dir change, body and head directions (relative to our head)
                track.vx, track.vy = _velocity(d, a, numbers[0], numbers[1], head, me)
                track.body = norm_deg(me.head + numbers[2])
            team = name[1].strip('"') if len(name) >= 2 else None
            if team is not None and team != self.team:
                self.opponent = team
            if len(name) >= 3 and name[2].isdigit():
                self.players[(team, int(name[2]))] = track
            else:
                self.anonymous.append((team, track))
        self._identify(see.time)
        if self.ball is not None and self.ball.seen != see.time and self._should_see(self.ball):
            # The server shows the ball wherever it is in the view cone, and within visible_distance
            # all around: not seen there, it is not where we believed (taken, kicked, placed).
            self.ball = None

    def _identify(self, now: int) -> None:
        """Give sightings without a number to the known players they most likely are, nearest first.

        The server names a player only in the view cone and not too far: one close by outside the
        cone is just ``(P)``, no team. Left anonymous, an opponent who came round our back to 1 m
        stayed believed where we last saw him, and the player on the ball ran into him.
        """
        me, left = self.me, []
        for team, track in sorted(self.anonymous, key=lambda a: math.hypot(a[1].x - me.x, a[1].y - me.y)):
            best, best_d = None, math.inf
            for key, known in self.players.items():
                if known.seen == now or (team is not None and key[0] != team):
                    continue
                d = math.hypot(known.x - track.x, known.y - track.y)
                if d < min(MATCH_MOST, MATCH_GATE + MATCH_RUN * (now - known.seen)) and d < best_d:
                    best, best_d = known, d
            if best is None:
                left.append((team, track))
                continue
            best.x, best.y, best.vx, best.vy = track.x, track.y, track.vx, track.vy
            best.sigma, best.seen = track.sigma, now
        self.anonymous = left

    def _should_see(self, track: Track) -> bool:
        """Whether a see would show an object at ``track`` (well inside the cone, or close all around)."""
        me = self.me
        d = math.hypot(track.x - me.x, track.y - me.y)
        off = norm_deg(math.degrees(math.atan2(track.y - me.y, track.x - me.x)) - me.head)
        visible = float(self.server.get("visible_distance", 3.0))
        return me.sigma < 5.0 and surely_seen(d, off, HALF_VIEW.get(me.view_width, 60.0), visible)

    def sent(self, msg: list) -> None:
        """Take a command we sent (parsed) into account: what a turn or a move will do to our pose, a kick to the ball.

        It takes effect at the sense_body whose counter shows that the server executed it.
        """
        kind = str(msg[0]) if msg else ""
        me = self.me
        if kind == "turn" and len(msg) >= 2:
            inertia = float(self.param("inertia_moment", 5.0))
            effect: tuple[float, ...] = (float(msg[1]) / (1.0 + inertia * math.hypot(me.vx, me.vy)),)
        elif kind == "move" and len(msg) >= 3:
            sign = -1 if self.side is Side.RIGHT else 1  # the server mirrors a right player's move
            effect = (float(msg[1]) * sign, float(msg[2]) * sign)
        elif kind == "kick" and len(msg) >= 3 and self.ball is not None:
            effect = self._kick_accel(float(msg[1]), float(msg[2]))
        else:
            return
        self.pending[kind] = (self.counters.get(kind), self.steps, effect)

    def _kick_accel(self, power: float, direction: float) -> tuple[float, float]:
        """The ball's acceleration (server frame) a kick gives, as rcssserver computes it without noise."""
        me, ball = self.me, self.ball
        size = self._contact()
        margin = float(self.param("kickable_margin", 0.7)) or 0.7
        to_ball = math.degrees(math.atan2(ball.y - me.y, ball.x - me.x))
        dir_diff = abs(norm_deg(to_ball - me.body))
        gap = max(0.0, math.hypot(ball.x - me.x, ball.y - me.y) - size)
        power = max(-100.0, min(100.0, power))
        eff = (
            power * float(self.param("kick_power_rate", 0.027)) * (1.0 - 0.25 * dir_diff / 180.0 - 0.25 * gap / margin)
        )
        eff = min(max(eff, 0.0), float(self.server.get("ball_accel_max", 2.7)))
        angle = math.radians(me.body + direction)
        return eff * math.cos(angle), eff * math.sin(angle)

    def _kicked(self, ax: float, ay: float) -> None:
        """Our kick ran: the ball leaves with the kick's acceleration added (the next see corrects it)."""
        ball = self.ball
        if ball is None:
            return
        ball.vx, ball.vy = ball.vx + ax, ball.vy + ay
        speed, top = math.hypot(ball.vx, ball.vy), float(self.server.get("ball_speed_max", 3.0))
        if speed > top:
            ball.vx, ball.vy = ball.vx * top / speed, ball.vy * top / speed
        ball.sigma += 0.5  # the kick's noise

    # ---- what others read -----------------------------------------------------

    @property
    def type_id(self) -> int:
        """My player type: the one the server last told for my number, else the default (0)."""
        return self.mate_types.get(self.number, 0)

    def param(self, name: str, default: float, type_id: int | None = None) -> float | str:
        """A parameter of player type ``type_id`` (default: mine), else of the server."""
        type_id = self.type_id if type_id is None else type_id
        return self.player_types.get(type_id, {}).get(name, self.server.get(name, default))

    def told_top_speed(self, number: int) -> float:
        """Metres per second that full dashes of team-mate ``number``'s type reach (mine for my
        number), as the WorldState tells it."""
        type_id = self.mate_types.get(number, 0)
        names = ("player_speed_max", "dash_power_rate", "player_decay", "effort_max")
        return round(top_speed(*(float(self.param(n, getattr(Params, n), type_id)) for n in names)) * 10, 3)

    def params(self) -> Params:
        """The server's and this player type's parameters, as the shared skills read them."""
        names = [f for f in Params.__dataclass_fields__ if f not in ("half_cycles", "halves")]
        values = {n: float(self.param(n, getattr(Params, n))) for n in names}
        for n in ("goal_pause_cycles", "auto_kick_off_cycles", "set_piece_timeout", "say_msg_size"):
            values[n] = int(values[n])
        values["field_length"], values["field_width"] = FIELD.length, FIELD.width  # fixed in rcssserver
        values["goal_width"] = float(self.server.get("goal_width", FIELD.goal_width))
        values["catchable_area"] = float(self.server.get("catchable_area_l", 1.2))
        values["half_cycles"] = int(float(self.server.get("half_time", 300)) * 10)
        # The reach the skills kick within: the server's, less what the see's rounding of the ball's
        # distance may hide (a kick at a ball just out of reach is refused and the cycle is lost).
        reach = values["player_size"] + values["ball_size"] + values["kickable_margin"]
        values["kickable_margin"] -= reach - sure_reach(reach)
        return Params(**values)

    def expects_see(self) -> bool:
        """Whether a see of the current cycle is still to come (rcssserver 19: every 2 cycles at normal width)."""
        every = {"narrow": 1, "normal": 2, "wide": 3}.get(self.me.view_width, 2)
        return self.see_time < self.time and (self.see_time < 0 or self.time - self.see_time >= every)

    def world(self) -> World:
        """The belief as the embedded simulator's absolute frame (y and angles mirrored), for the skills."""
        side = self.side or Side.LEFT
        w = World(params=self.params(), time=self.time, mode=self.mode, score=dict(self.score), half=self.half)
        me = self.me
        w.players[(side, self.number)] = SimPlayer(
            side,
            self.number,
            me.x,
            -me.y,
            me.vx,
            -me.vy,
            -me.body,
            -me.neck,
            me.stamina,
            self.goalie,
            frozen=self.tackle_expires,
        )
        if self.ball is not None:
            w.ball = SimBall(self.ball.x, -self.ball.y, self.ball.vx, -self.ball.vy)
        for (team, number), t in self.players.items():
            whose = side if team == self.team else side.other
            if (whose, number) not in w.players:
                # Unseen, a man faces the way he runs (the skills' foul check reads it).
                body = -t.body if t.body is not None else math.degrees(math.atan2(-t.vy, t.vx))
                w.players[(whose, number)] = SimPlayer(
                    whose, number, t.x, -t.y, t.vx, -t.vy, body, 0.0, 8000.0, t.goalie
                )
        w.team_names = {side: self.team, side.other: self.opponent or "opponent"}
        return w


def run_on(
    x: float, y: float, vx: float, vy: float, cycles: int, decay: float = 0.4
) -> tuple[float, float, float, float]:
    """A player out of sight ``cycles`` cycles on: position and (seen, after-decay) velocity, as RUN_ON has it."""
    for _ in range(cycles):
        step = math.hypot(vx, vy) / decay
        if step <= 0.0:
            break
        scale = min(1.0, RUN_MOST / step) / decay
        x, y, vx, vy = x + vx * scale, y + vy * scale, vx * RUN_ON, vy * RUN_ON
    return x, y, vx, vy


def surely_seen(distance: float, off_head: float, half_view: float, visible_distance: float) -> bool:
    """Whether an object ``distance`` m away, ``off_head`` degrees off the head, is surely shown: well
    inside the view cone (10 degrees in from its edge, 2-50 m away) or well within the distance at
    which everything around is felt. Not shown there, it is not where it was believed."""
    inside = abs(off_head) < half_view - 10.0 and 2.0 < distance < 50.0
    return distance < visible_distance - 0.5 or inside


def sure_reach(reach: float, step: float = 2 * QUANT) -> float:
    """The furthest a see may show the ball when it is surely within ``reach``.

    rcssserver shows a distance d as exp(log d rounded to ``step``) rounded to 0.1: each value it
    shows stands for a band of true distances. The answer is the largest value whose whole band
    lies within reach (for the 1.085 m kickable distance: a ball shown at 1.0 is 0.95-1.05 m off,
    so within reach; one shown at 1.1 is 1.05-1.16 m off, so maybe not), plus a little for the
    floating point. Dead-reckoned distances between sees are held to the same mark.
    """
    k = math.floor(math.log(reach) / step)
    while k > -60:
        shown = round(math.exp(step * k), 1)
        # (near the player two bands may show as one value: then the outer one must be within too)
        if math.exp(step * (k + 0.5)) <= reach and round(math.exp(step * (k + 1)), 1) != shown:
            return shown + 0.005
        k -= 1
    return 0.0


def _velocity(d: float, a: float, dchg: float, dirchg: float, head: float, me: OwnPlayer) -> tuple[float, float]:
    """An object's absolute velocity (server frame, m/cycle) from the see's distance and direction changes."""
    rx, ry = math.cos(a), math.sin(a)
    w = math.radians(dirchg) * d
    vx, vy = dchg * rx - w * ry, dchg * ry + w * rx
    c, s = math.cos(head), math.sin(head)
    return (c * vx - s * vy + me.vx, s * vx + c * vy + me.vy)


def _clip(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))


def world_state(belief: Belief) -> WorldState:
    """What the perception service tells: the belief in the player's own frame, with sigmas and ages."""
    side, t = belief.side or Side.LEFT, belief.time
    me = belief.me

    def place(x: float, y: float, sigma: float, body: float | None = None) -> AbsolutePositioning:
        ox, oy = to_own_frame(side, x, -y)
        return AbsolutePositioning(
            x=_clip(ox, 70.0),
            y=_clip(oy, 50.0),
            yaw=None if body is None else yaw_in_own_frame(side, -body),
            sigma_x=round(sigma, 3),
            sigma_y=round(sigma, 3),
        )

    def relative(x: float, y: float, sigma: float) -> RelativePositioning:
        d = math.hypot(x - me.x, y - me.y)
        direction = -norm_deg(math.degrees(math.atan2(y - me.y, x - me.x)) - me.body)
        return RelativePositioning(distance=min(200.0, d), direction=math.radians(direction), sigma_distance=sigma)

    def velocity(vx: float, vy: float) -> Velocity:
        ovx, ovy = to_own_frame(side, vx * 10, -vy * 10)  # m/cycle -> m/s
        return Velocity(vx=_clip(ovx, 50.0), vy=_clip(ovy, 50.0))

    mine = place(me.x, me.y, me.sigma, me.body)
    myself = Player(
        player_number=belief.number or None,
        which_team=Team.OUR,
        is_goalie=belief.goalie,
        positioning=mine.model_copy(update={"sigma_yaw": math.radians(min(me.sigma_head, 180.0))}),
        velocity=velocity(me.vx, me.vy),
        head_angle=math.radians(-me.neck),
        stamina=round(min(1.0, me.stamina / float(belief.server.get("stamina_max", 8000.0))), 3),
        top_speed=belief.told_top_speed(belief.number),
        age=max(0, t - me.localised) if me.localised >= 0 else None,
    )
    ball = None
    if belief.ball is not None and t - belief.ball.seen <= BALL_MEMORY:
        b = belief.ball
        ball = Ball(
            positioning=place(b.x, b.y, b.sigma),
            relative=relative(b.x, b.y, b.sigma),
            velocity=velocity(b.vx, b.vy),
            age=max(0, t - b.seen),
        )
    others = []
    tracks = [(team, number, tr) for (team, number), tr in belief.players.items()]
    tracks += [(team, None, tr) for team, tr in belief.anonymous]
    for team, number, tr in tracks:
        which = None if team is None else (Team.OUR if team == belief.team else Team.OPP)
        speed = None  # (an opponent's type is not told)
        if which is Team.OUR and number is not None:
            speed = belief.told_top_speed(number)
        others.append(
            Player(
                player_number=number,
                which_team=which,
                is_goalie=tr.goalie if number is not None else None,
                positioning=place(tr.x, tr.y, tr.sigma, tr.body),
                relative=relative(tr.x, tr.y, tr.sigma),
                velocity=velocity(tr.vx, tr.vy) if number is not None else None,
                top_speed=speed,
                age=max(0, t - tr.seen),
            )
        )
    game = Game(
        time=t,
        play_mode=relative_mode(belief.mode, side),
        score_our=belief.score[side],
        score_opp=belief.score[side.other],
        half=min(belief.half, 4),
    )
    # What team-mates said, heard this cycle or the last (the hear may come after the cycle's see).
    heard = tuple(Heard(player_number=n, message=text, time=when) for when, n, text in belief.heard if when >= t - 1)
    return WorldState(time=t, me=myself, ball=ball, players=tuple(others), game=game, heard=heard)
