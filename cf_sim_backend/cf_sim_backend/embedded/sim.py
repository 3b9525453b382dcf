"""The embedded 2D soccer simulator: commands in, one cycle at a time, deterministic for a seed (ROS-free)."""

from __future__ import annotations

import random

from cf_sim_backend.embedded import physics, referee
from cf_sim_backend.embedded.physics import CommandError
from cf_sim_backend.player_types import PlayerType, choose_types, hetero_types
from cf_sim_backend.world import COUNTED, Params, Side, SimBall, SimPlayer, World, say_error

_KICK, _DASH, _TURN, _CATCH, _MOVE, _TURN_NECK, _TACKLE = (
    COUNTED.index(n) for n in ("kick", "dash", "turn", "catch", "move", "turn_neck", "tackle")
)
_ARITY = {
    "dash": (1, 2),
    "turn": (1, 1),
    "kick": (2, 2),
    "catch": (1, 1),
    "tackle": (1, 1),  # the direction, degrees from the body (rcssserver 12+)
    "move": (2, 2),
    "turn_neck": (1, 1),
}


class Simulator:
    """A match: 1..11 players a side, rcssserver-like physics and referee.

    ``command(side, number, name, *args)`` queues a command for the coming
    cycle (one body command per player per cycle, plus ``turn_neck``);
    ``step()`` plays the cycle and returns what the referee saw. ``player_types`` above 1: that many
    of rcssserver's heterogeneous types, drawn from ``seed`` (player_types.py).
    """

    def __init__(
        self,
        params: Params | None = None,
        *,
        team_sizes: tuple[int, int] = (11, 11),
        team_names: tuple[str, str] = ("left", "right"),
        seed: int = 0,
        player_types: int = 1,
    ):
        self.world = World(params=params or Params())
        self.world.team_names = {Side.LEFT: team_names[0], Side.RIGHT: team_names[1]}
        for side, size in zip((Side.LEFT, Side.RIGHT), team_sizes, strict=True):
            if not 0 <= size <= 11:
                raise ValueError("team sizes must be 0..11")
            for n in range(1, size + 1):
                self.world.players[(side, n)] = SimPlayer(
                    side=side, number=n, goalie=(n == 1), stamina=self.world.params.stamina_max
                )
        if player_types > 1:
            self._hand_out_types(seed, player_types)
        referee.place_for_kick_off(self.world, Side.LEFT)
        self.rng = random.Random(seed)
        self._body: dict[tuple[Side, int], tuple[str, tuple[float, ...]]] = {}
        self._neck: dict[tuple[Side, int], float] = {}
        self._said: dict[tuple[Side, int], str] = {}
        self._offside: dict[Side, set[int]] = {Side.LEFT: set(), Side.RIGHT: set()}
        self._stopped = 0
        # Who took the set piece that began this spell of play_on (and when it began), until another touch.
        self._taker: tuple[tuple[Side, int], int] | None = None
        self.stats = {
            "kicks": {Side.LEFT: 0, Side.RIGHT: 0},
            "possession": {Side.LEFT: 0, Side.RIGHT: 0},
            "shots": {Side.LEFT: 0, Side.RIGHT: 0},
        }

    def _hand_out_types(self, seed: int, count: int) -> None:
        """rcssserver's heterogeneous types for ``seed``, given to each side by our coach's rule."""
        w = self.world
        w.types, w.types_seed = hetero_types(seed, count, w.params), seed
        offer = [PlayerType.of(type_id, params) for type_id, params in enumerate(w.types)]
        for side in Side:
            numbers = [p.number for p in w.players.values() if p.side is side]
            for number, type_id in choose_types(offer, numbers).items():
                w.players[(side, number)].ptype = type_id

    @property
    def finished(self) -> bool:
        return self.world.mode == "time_over"

    def command(self, side: Side, number: int, name: str, *args: float) -> None:
        """Queue a command for the next cycle; raise CommandError if the server would refuse it."""
        key = (Side(side), int(number))
        if key not in self.world.players:
            raise CommandError(f"no player {key[0].value} {key[1]}")
        if name == "say":
            # Not a body command: heard next cycle by the players within audio_cut_dist (observe).
            error = say_error(str(args[0]), self.world.params) if len(args) == 1 else "say takes 1 argument"
            if error is not None:
                raise CommandError(error)
            self._said[key] = str(args[0])
            return
        if name not in _ARITY:
            raise CommandError(f"unknown command {name!r}")
        low, high = _ARITY[name]
        if not low <= len(args) <= high:
            raise CommandError(f"{name} takes {low}..{high} arguments")
        try:
            values = tuple(float(a) for a in args)
        except (TypeError, ValueError):
            raise CommandError(f"{name}: arguments must be numbers") from None
        if name == "turn_neck":
            self._neck[key] = values[0]
        elif key in self._body:
            raise CommandError("one body command per cycle")
        else:
            self._body[key] = (name, values)

    def step(self) -> list[str]:
        """Play one cycle."""
        w = self.world
        events: list[str] = []
        if w.mode == "time_over":
            return events
        if w.mode != "play_on":
            # Any stoppage ends the offsides of the last kick (rcssserver's OffsideRef::playModeChange),
            # before the set piece's kick makes new ones: a forward beyond their line at a shot that
            # went out was called at our next kick-off (and, cleared at a step's end, after half time).
            self._offside = {Side.LEFT: set(), Side.RIGHT: set()}
        body, self._body = self._body, {}
        neck, self._neck = self._neck, {}
        w.said, self._said = tuple((side, number, text) for (side, number), text in self._said.items()), {}
        if w.mode in ("before_kick_off", "half_time"):
            self._moves_only(body)
            self._stopped += 1
            if self._stopped >= w.params.auto_kick_off_cycles:
                self._stopped = 0
                referee.set_mode(w, f"kick_off_{w.kick_off_side.value}")
                events.append(f"kick off {w.kick_off_side.value}")
            return events
        if w.mode in ("goal_l", "goal_r"):  # (not goal_kick_*: a set piece, played on below)
            if w.time - w.mode_since >= w.params.goal_pause_cycles:
                conceding = Side(w.mode[-1]).other
                referee.place_for_kick_off(w, conceding)
                referee.set_mode(w, f"kick_off_{conceding.value}")
                events.append(f"kick off {conceding.value}")
            else:
                self._moves_only(body)
            referee.advance_clock(w)
            return events
        for key, angle in neck.items():
            physics.turn_neck(w, w.players[key], angle)
            w.players[key].counts[_TURN_NECK] += 1
        keys = list(body)
        self.rng.shuffle(keys)  # no side gets to kick first by its number
        for p in w.players.values():
            if p.frozen > 0:  # a tackle's aftermath: no body command counts
                p.frozen -= 1
                body.pop(p.key, None)
        keys = [key for key in keys if key in body]
        for key in keys:
            name, args = body[key]
            event = self._apply(w.players[key], name, args)
            if event:
                events.append(event)
        held = referee.set_piece_side(w) is not None
        if held:
            w.ball.vx = w.ball.vy = 0.0  # the ball lies still until the side that has it kicks
        physics.move_objects(w, self.rng)
        if w.mode == "play_on":
            event = referee.check_ball(w)
            if event:
                events.append(event)
        referee.keep_opponents_away(w)
        if referee.set_piece_side(w) is not None and w.time - w.mode_since > w.params.set_piece_timeout:
            referee.set_mode(w, "play_on")  # nobody took it: drop ball
            events.append("drop ball")
        if w.last_touch is not None and w.mode == "play_on":
            self.stats["possession"][w.last_touch[0]] += 1
        event = referee.advance_clock(w)
        if event:
            events.append(event)
        return events

    def _moves_only(self, body: dict) -> None:
        for key, (name, args) in body.items():
            if name == "move":
                self._move(self.world.players[key], *args)
                self.world.players[key].counts[_MOVE] += 1

    def _move(self, p: SimPlayer, x: float, y: float) -> None:
        """Place a player in its own half (x given for the left side, as rcssserver's move)."""
        half = self.world.params
        x = max(-half.field_length / 2, min(-0.5, x)) * p.side.sign
        y = max(-half.field_width / 2, min(half.field_width / 2, y)) * p.side.sign
        p.x, p.y, p.vx, p.vy = x, y, 0.0, 0.0

    def _apply(self, p: SimPlayer, name: str, args: tuple[float, ...]) -> str | None:
        w = self.world
        if name == "dash":
            physics.dash(w, p, *args)
            p.counts[_DASH] += 1
            p.dashed_at = w.time
        elif name == "turn":
            physics.turn(w, p, args[0])
            p.counts[_TURN] += 1
        elif name == "move":
            pass  # as in rcssserver, a move counts only before a kick-off or after a goal (step() does those)
        elif name in ("kick", "tackle"):
            return self._touch(p, name, args)
        elif name == "catch" and w.mode == "play_on" and physics.catch(w, p, args[0]):
            p.counts[_CATCH] += 1
            passer, w.last_touch = w.last_touch, p.key
            if w.params.back_passes and passer is not None and passer[0] is p.side and passer != p.key:
                # As rcssserver's CatchRef: a team-mate's kick caught is a back pass, an indirect
                # free kick to the other side where it was caught (out of the goal area).
                referee.start_set_piece(
                    w, "indirect_free_kick", p.side.other, *referee.out_of_goal_area(w, w.ball.x, w.ball.y)
                )
                return f"back pass {p.side.value} {passer[1]}"
            referee.start_set_piece(w, "free_kick", p.side, w.ball.x, w.ball.y)
            return f"catch {p.side.value} {p.number}"
        return None

    def _touch(self, p: SimPlayer, name: str, args: tuple[float, ...]) -> str | None:
        w = self.world
        piece_side = referee.set_piece_side(w)
        if piece_side is not None and piece_side is not p.side:
            return None  # opponents may not play the ball in a set piece
        if piece_side is None and self._taker == (p.key, w.mode_since) and physics.kickable(w, p):
            # As rcssserver: a set piece's taker may not touch the ball again before another player.
            self._taker = None
            referee.start_set_piece(w, "free_kick", p.side.other, w.ball.x, w.ball.y)
            return f"free kick fault {p.side.value} {p.number}"
        if p.number in self._offside[p.side] and physics.kickable(w, p):
            self._offside = {Side.LEFT: set(), Side.RIGHT: set()}
            referee.start_set_piece(w, "free_kick", p.side.other, p.x, p.y)
            return f"offside {p.side.value} {p.number}"
        if name == "kick":
            touched = physics.kick(w, p, *args, rng=self.rng)
            p.counts[_KICK] += touched
        elif foul := self._foul(p):
            return foul
        else:
            touched = physics.tackle(w, p, args[0], self.rng)
            p.counts[_TACKLE] += 1
        if not touched:
            return None
        w.last_touch = p.key
        if w.indirect:  # the indirect free kick's ball may score once a second player has touched it
            w.indirect_kicker = w.indirect_kicker or p.key
            w.indirect = w.indirect_kicker == p.key
        self._taker = None
        self.stats["kicks"][p.side] += 1
        shot = referee.is_shot(w, p.side)
        if shot:
            self.stats["shots"][p.side] += 1
        # As rcssserver's OffsideRef: no offside from a goal kick, a kick-in or a corner kick.
        no_offside = w.mode.startswith(("goal_kick", "kick_in", "corner_kick"))
        self._offside[p.side] = set() if no_offside else referee.offside_players(w, p.side, p.number)
        self._offside[p.side.other] = set()
        if piece_side is not None:
            referee.set_mode(w, "play_on")
            self._taker = (p.key, w.mode_since)
        return f"shot {p.side.value} {p.number}" if shot else None

    def _foul(self, p: SimPlayer) -> str | None:
        """rcssserver's foul charge: a tackle through an opponent who has the ball and dashed lately
        (:func:`physics.foul_risk`), seen by the referee with ``foul_detect_probability``, is the
        other side's free kick where the tackler stood, an indirect one in his own penalty area."""
        w = self.world
        fouled = [o for o in physics.foul_risk(w, p) if w.time - o.dashed_at <= 1]
        if not any(self.rng.random() < w.params.foul_detect_probability for _ in fouled):
            return None
        p.frozen = w.params.tackle_cycles - 1
        p.counts[_TACKLE] += 1
        piece = "indirect_free_kick" if physics.in_own_penalty_area(w, p) else "free_kick"
        referee.start_set_piece(w, piece, p.side.other, *referee.foul_spot(w, p))
        return f"foul {p.side.value} {p.number}"

    def counts(self) -> dict[str, list[int]]:
        """Each player's counted commands (``"l9"``: rcssserver's counters, see ``SimPlayer.counts``)."""
        return {f"{p.side.value}{p.number}": list(p.counts) for p in self.world.players.values()}

    def snapshot(self) -> dict:
        """The true state of this cycle as plain data (the match log's and the state topic's format)."""
        w = self.world
        b: SimBall = w.ball
        snap = {
            "t": w.time,
            "mode": w.mode,
            "half": w.half,
            "score": [w.score[Side.LEFT], w.score[Side.RIGHT]],
            "ball": [round(b.x, 3), round(b.y, 3), round(b.vx, 3), round(b.vy, 3)],
            "players": [
                [
                    p.side.value,
                    p.number,
                    round(p.x, 3),
                    round(p.y, 3),
                    round(p.vx, 3),
                    round(p.vy, 3),
                    round(p.body, 2),
                    round(p.neck, 2),
                    round(p.stamina),
                    int(p.goalie),
                    p.ptype,
                ]
                for p in w.players.values()
            ],
        }
        if w.types:
            snap["types"] = [w.types_seed, len(w.types)]
        if w.said:
            snap["said"] = [[side.value, number, text] for side, number, text in w.said]
        return snap
