"""What a player of the embedded simulator remembers between perceptions, as an rcssserver player does (ROS-free).

:func:`perception.observe` tells only what the player sees this cycle. On rcssserver the adapter's
belief (:mod:`rcss.belief`) keeps what it saw: the decision there was told of players out of
sight for up to :data:`PLAYER_MEMORY` cycles and of the ball for up to :data:`BALL_MEMORY`, so the
same decision knew fewer team-mates and opponents on the embedded simulator and passed forward a
third as often (docs/performance.md, session 33). :class:`Memory` keeps the same, with the
belief's rules and figures:

- a player seen with his team and number is known by them; a sighting without (too far to read)
  is a known player of that team believed near enough to it, else it is told this cycle only;
- a known player not seen again runs on as he was seen running (:func:`rcss.belief.run_on`), his
  uncertainty growing each cycle;
- the ball not seen rolls on with its decay, its uncertainty growing; it is forgotten where the
  player should have seen it (well inside his view, or close by), and when the referee moves it
  (a new play mode; at a kick-off it is on the centre spot).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_lang.ontology import (
    AbsolutePositioning,
    Ball,
    Player,
    PlayMode,
    RelativePositioning,
    Team,
    Velocity,
    WorldState,
)
from cf_sim_backend.perception import FEEL_DISTANCE, VIEW_WIDTH
from cf_sim_backend.rcss.belief import (
    BALL_MEMORY,
    BALL_SIGMA_GROWTH,
    MATCH_GATE,
    MATCH_MOST,
    MATCH_RUN,
    PLAYER_MEMORY,
    PLAYER_SIGMA_GROWTH,
    run_on,
    surely_seen,
)
from cf_sim_backend.world import Params, norm_deg

_KICK_OFFS = (PlayMode.KICK_OFF_OUR, PlayMode.KICK_OFF_OPP, PlayMode.BEFORE_KICK_OFF)
_FAR_X, _FAR_Y = 70.0, 50.0  # m: the furthest an AbsolutePositioning may lie


@dataclass
class _Seen:
    player: Player
    x: float
    y: float
    sigma: float
    time: int
    vx: float = 0.0  # m/cycle, after the cycle's decay (as seen)
    vy: float = 0.0


class Memory:
    """One player's memory of the others and the ball, in his own frame."""

    def __init__(self, params: Params | None = None):
        self.decay = (params or Params()).ball_decay
        self.player_decay = (params or Params()).player_decay
        self.players: dict[tuple[Team, int], _Seen] = {}
        self.ball: tuple[float, float, float, float, float, int] | None = None  # x, y, vx, vy (m/cycle), sigma, seen
        self.mode: PlayMode | None = None
        self.time: int | None = None

    def recall(self, state: WorldState) -> WorldState:
        """``state`` (this cycle's perception) with what is remembered of what it does not show."""
        t, me = state.time, state.me.positioning
        if me is None:
            return state
        mode = state.game.play_mode if state.game else None
        if mode != self.mode and self.mode is not None:
            self.ball = (0.0, 0.0, 0.0, 0.0, 0.5, t) if mode in _KICK_OFFS else None  # the referee moved it
        self.mode = mode
        elapsed = 0 if self.time is None else max(0, t - self.time)
        self.time = t
        ball = self._ball(state, elapsed)
        return state.model_copy(update={"ball": ball, "players": self._players(state)})

    # ---- the ball ---------------------------------------------------------

    def _ball(self, state: WorldState, elapsed: int) -> Ball | None:
        t, seen = state.time, state.ball
        if seen is not None and seen.positioning is not None:
            v = seen.velocity or Velocity(vx=0.0, vy=0.0)
            p = seen.positioning
            self.ball = (p.x, p.y, v.vx / 10, v.vy / 10, p.sigma_x or 0.0, t)
            return seen
        if self.ball is None:
            return None
        x, y, vx, vy, sigma, when = self.ball
        for _ in range(elapsed):
            x, y, vx, vy, sigma = x + vx, y + vy, vx * self.decay, vy * self.decay, sigma + BALL_SIGMA_GROWTH
        self.ball = (x, y, vx, vy, sigma, when)
        if t - when > BALL_MEMORY or _should_see(state, x, y) or abs(x) > _FAR_X or abs(y) > _FAR_Y:
            # (Beyond the ontology's positions it has long left the field: the referee has it.)
            self.ball = None
            return None
        return Ball(
            positioning=AbsolutePositioning(x=x, y=y, sigma_x=sigma, sigma_y=sigma),
            relative=_relative(state, x, y, sigma),
            velocity=Velocity(vx=vx * 10, vy=vy * 10),
            age=t - when,
        )

    # ---- the players -------------------------------------------------------

    def _players(self, state: WorldState) -> tuple[Player, ...]:
        t, told, anonymous = state.time, [], []
        fresh: set[tuple[Team, int]] = set()
        for p in state.players:
            pos = p.positioning
            if pos is None:
                continue
            if p.which_team is not None and p.player_number is not None:
                key = (p.which_team, p.player_number)
                self.players[key] = _Seen(p, pos.x, pos.y, pos.sigma_x or 0.0, t, *_per_cycle(p))
                fresh.add(key)
                told.append(p)
            else:
                anonymous.append(p)
        by_distance = sorted(anonymous, key=lambda p: _distance_to_me(state, p.positioning.x, p.positioning.y))
        for p in by_distance:
            key = self._known_near(p, t, fresh)
            if key is None:
                told.append(p)  # for this cycle only
                continue
            old = self.players[key].player
            pos = p.positioning
            named = p.model_copy(
                update={
                    "player_number": key[1],
                    "which_team": key[0],
                    "is_goalie": old.is_goalie,
                    "top_speed": old.top_speed,
                }
            )
            self.players[key] = _Seen(named, pos.x, pos.y, pos.sigma_x or 0.0, t, *_per_cycle(p))
            fresh.add(key)
            told.append(named)
        self.players = {k: s for k, s in self.players.items() if t - s.time <= PLAYER_MEMORY}
        for key, s in self.players.items():
            if key in fresh:
                continue
            sigma = s.sigma + PLAYER_SIGMA_GROWTH * (t - s.time)
            yaw = s.player.positioning.yaw if s.player.positioning else None
            x, y, vx, vy = run_on(s.x, s.y, s.vx, s.vy, t - s.time, self.player_decay)
            told.append(
                s.player.model_copy(
                    update={
                        "positioning": AbsolutePositioning(x=x, y=y, yaw=yaw, sigma_x=sigma, sigma_y=sigma),
                        "relative": _relative(state, x, y, sigma),
                        "velocity": Velocity(vx=vx * 10, vy=vy * 10) if s.player.velocity else None,
                        "age": t - s.time,
                    }
                )
            )
        return tuple(told)

    def _known_near(self, p: Player, t: int, fresh: set[tuple[Team, int]]) -> tuple[Team, int] | None:
        """The known player (not seen this cycle) a sighting without a number most likely is."""
        best, best_d = None, math.inf
        for key, s in self.players.items():
            if key in fresh or (p.which_team is not None and key[0] is not p.which_team):
                continue
            d = math.hypot(s.x - p.positioning.x, s.y - p.positioning.y)
            if d < min(MATCH_MOST, MATCH_GATE + MATCH_RUN * (t - s.time)) and d < best_d:
                best, best_d = key, d
        return best


def _distance_to_me(state: WorldState, x: float, y: float) -> float:
    me = state.me.positioning
    return math.hypot(x - me.x, y - me.y)


def _relative(state: WorldState, x: float, y: float, sigma: float) -> RelativePositioning:
    """Where (x, y) lies from the player: distance, and direction from his body (as observe tells it)."""
    me = state.me.positioning
    direction = math.atan2(y - me.y, x - me.x) - (me.yaw or 0.0)
    direction = math.atan2(math.sin(direction), math.cos(direction))
    return RelativePositioning(
        distance=min(200.0, _distance_to_me(state, x, y)), direction=direction, sigma_distance=sigma
    )


def _should_see(state: WorldState, x: float, y: float) -> bool:
    """Whether this cycle's perception would have shown an object at (x, y) (the belief's rule)."""
    me = state.me.positioning
    head = (me.yaw or 0.0) + (state.me.head_angle or 0.0)
    off = norm_deg(math.degrees(math.atan2(y - me.y, x - me.x) - head))
    return surely_seen(_distance_to_me(state, x, y), off, VIEW_WIDTH / 2, FEEL_DISTANCE)


def _per_cycle(p: Player) -> tuple[float, float]:
    """A sighting's velocity in m/cycle (none told: standing)."""
    return (p.velocity.vx / 10, p.velocity.vy / 10) if p.velocity else (0.0, 0.0)
