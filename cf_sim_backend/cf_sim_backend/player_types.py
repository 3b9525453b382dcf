"""Heterogeneous player types as rcssserver 19 makes them, and the types our coach gives out (ROS-free).

rcssserver draws its random types from ``player_param``'s deltas with C++'s ``std::mt19937``
seeded with the match's seed (``HeteroPlayer``): type 0 is the default, types 1..17 are random,
and a trial whose top speed falls outside 0.75..player_speed_max is drawn again. :func:`hetero_types`
draws the same numbers in the same order from the same generator, so the embedded simulator with
seed S plays with the very types rcssserver has with ``random_seed`` S.

:func:`choose_types` is our coach's rule (rcss/coach.py), which the embedded simulator applies
for both sides: the goalkeeper keeps the default type, the others get the fastest types, each
at most ``pt_max`` times, in the order ``ORDER`` gives.
"""

from __future__ import annotations

import dataclasses
import random
from dataclasses import dataclass
from functools import lru_cache

from cf_sim_backend.world import MAX_DASH_POWER, Params, top_speed

TYPE_COUNT = 18  # rcssserver 19's player_types
MAX_TYPES = 100  # more is a malformed request, not a league
ORDER = (10, 3, 4, 9, 11, 7, 2, 5, 6, 8)  # who gets the fastest type first: the spine, then the wings
DEFAULT_TYPE = 0
SPEED_MIN = 0.75  # rcssserver's player_speed_max_min: no type may be slower
_TRIALS = 1000  # rcssserver's MAX_TRIAL: after that many rejected draws a type is the default
_EPS = 1e-10  # rcssserver's EPS

# rcssserver 19's player_param deltas: (low, high) of each draw; a type parameter moves by its
# draw times a factor (``*_delta_factor``). Draws whose low and high are equal take no random number.
DECAY_DELTA = (-0.1, 0.1)  # player_decay; inertia_moment moves 25 times as much
DASH_RATE_DELTA = (-0.0012, 0.0008)  # dash_power_rate (new_*); stamina_inc_max moves -6000 times as much
KICKABLE_DELTA = (-0.1, 0.1)  # kickable_margin; kick_rand moves as much
EXTRA_STAMINA_DELTA = (0.0, 50.0)  # extra_stamina; effort_max and effort_min move -0.004 times as much
CATCH_STRETCH = (1.0, 1.3)  # catchable_area_l_stretch


def _std_mt19937(seed: int) -> random.Random:
    """Python's Mersenne Twister in the state C++'s ``std::mt19937(seed)`` starts from (its
    ``init_genrand``; Python's own seeding differs), so ``getrandbits(32)`` gives the same numbers."""
    state = [seed & 0xFFFFFFFF]
    for i in range(1, 624):
        prev = state[-1]
        state.append((1812433253 * (prev ^ (prev >> 30)) + i) & 0xFFFFFFFF)
    rng = random.Random()
    rng.setstate((3, (*state, 624), None))
    return rng


def _uniform(rng: random.Random, low: float, high: float) -> float:
    """``std::uniform_real_distribution(low, high)`` over a 32-bit engine (libstdc++: two draws make
    one 64-bit fraction); a range of one value takes no draw, as rcssserver's ``delta``."""
    if low == high:
        return low
    fraction = (rng.getrandbits(32) + rng.getrandbits(32) * 2**32) / 2**64
    return low + (high - low) * fraction


def _random_type(rng: random.Random, base: Params) -> Params:
    """One random type, drawn as ``HeteroPlayer()`` draws it (the default type if every trial fails)."""
    for _ in range(_TRIALS):
        decay = _uniform(rng, *DECAY_DELTA)
        dash = _uniform(rng, *DASH_RATE_DELTA)
        kickable = _uniform(rng, *KICKABLE_DELTA)
        extra = _uniform(rng, *EXTRA_STAMINA_DELTA)
        stretch = _uniform(rng, *CATCH_STRETCH)
        drawn = dataclasses.replace(
            base,
            player_decay=base.player_decay + decay,
            inertia_moment=base.inertia_moment + 25.0 * decay,
            dash_power_rate=base.dash_power_rate + dash,
            stamina_inc_max=base.stamina_inc_max - 6000.0 * dash,
            kickable_margin=base.kickable_margin + kickable,
            kick_rand=base.kick_rand + kickable,
            extra_stamina=base.extra_stamina + extra,
            effort_max=base.effort_max - 0.004 * extra,
            effort_min=base.effort_min - 0.004 * extra,
            catchable_area_l_stretch=stretch,
        )
        reached = MAX_DASH_POWER * drawn.dash_power_rate * drawn.effort_max / (1.0 - drawn.player_decay)
        if SPEED_MIN - _EPS < reached < drawn.player_speed_max + _EPS:
            return drawn
    return base


@lru_cache(maxsize=8)
def hetero_types(seed: int, count: int = TYPE_COUNT, base: Params | None = None) -> tuple[Params, ...]:
    """The parameters of types 0..count-1 for ``seed``: type 0 is ``base`` (the default type)."""
    if not 1 <= count <= MAX_TYPES:
        raise ValueError(f"player types: {count} is not 1..{MAX_TYPES}")
    base = base or Params()
    rng = _std_mt19937(seed)
    return (base, *(_random_type(rng, base) for _ in range(1, count)))


@dataclass(frozen=True)
class PlayerType:
    """What the coach weighs of one type."""

    id: int
    speed: float  # m/cycle: the top speed repeated full dashes reach (capped at player_speed_max)
    stamina_inc: float  # stamina recovered per cycle

    @classmethod
    def of(cls, type_id: int, params: Params) -> PlayerType:
        return cls(type_id, params.top_speed, params.stamina_inc_max)

    @classmethod
    def from_values(cls, values: dict[str, float]) -> PlayerType:
        """From rcssserver's ``player_type`` parameters (KeyError: one the coach needs is missing)."""
        speed = top_speed(
            values["player_speed_max"], values["dash_power_rate"], values["player_decay"], values["effort_max"]
        )
        return cls(int(values["id"]), speed, values["stamina_inc_max"])


def choose_types(types: list[PlayerType], players: list[int], goalie: int = 1, pt_max: int = 1) -> dict[int, int]:
    """Shirt number -> type: the goalkeeper the default type, the others in ``ORDER`` (then by number)
    the fastest left (of two as fast, the one that recovers more stamina), each type at most ``pt_max`` times.
    """
    left = {t.id: pt_max for t in types}
    out: dict[int, int] = {}
    if goalie in players and DEFAULT_TYPE in left:
        out[goalie] = DEFAULT_TYPE
        left[DEFAULT_TYPE] -= 1
    ranked = sorted(types, key=lambda t: (-round(t.speed, 3), -t.stamina_inc, t.id))
    order = [n for n in ORDER if n in players] + sorted(n for n in players if n not in ORDER and n != goalie)
    for number in order:
        pick = next((t for t in ranked if left[t.id] > 0), None)
        if pick is None:
            break
        out[number] = pick.id
        left[pick.id] -= 1
    return out
