"""What one player perceives: its view cone, noise growing with distance, in the Framework Language (ROS-free).

Everything is given in the player's own frame, as the ontology defines it:
x towards the opponents' goal, y to the left, angles in radians; teams and
play modes relative (our/opp). For the right side the absolute frame is
turned by 180 degrees.

Seen: objects within half the view width of the head direction (rcssserver's
normal view: 120 degrees), and anything within 3 m (felt, not seen). Noise:
a standard deviation of ``noise`` x distance on positions (own pose: a fixed
small one), reported as sigmas, and of ``noise`` / 4 x distance on the ball's
velocity, VELOCITY_FAR_SIGMA beyond VELOCITY_FAR: the errors our rcssserver
belief has (docs/simulator.md); as much on a player's velocity, told with his number. Beyond 20 m
a player's number is not read, beyond 40 m neither is its team (as rcssserver's see).
"""

from __future__ import annotations

import math
import random

from cf_lang.ontology import (
    AbsolutePositioning,
    Ball,
    Game,
    Heard,
    Player,
    PlayMode,
    RelativePositioning,
    Team,
    Velocity,
    WorldState,
)
from cf_sim_backend.world import Side, SimPlayer, World, direction_deg, distance, norm_deg

VIEW_WIDTH = 120.0
FEEL_DISTANCE = 3.0
NUMBER_FAR = 20.0
TEAM_FAR = 40.0
SELF_SIGMA = 0.2
SELF_SIGMA_YAW = math.radians(2.0)
# Beyond rcssserver's ball_vel_too_far_length its see tells no velocity, and the belief's estimate
# from positions was 0.85 m/cycle off (median) against the game log's truth.
VELOCITY_FAR = 40.0
VELOCITY_FAR_SIGMA = 0.7  # m/cycle


def relative_mode(mode: str, side: Side) -> PlayMode:
    """rcssserver's play mode as seen by ``side``: kick_off_l -> kick_off_our for the left side."""
    if mode.endswith("_l") or mode.endswith("_r"):
        base, who = mode[:-2], Side(mode[-1])
        return PlayMode(f"{base}_{'our' if who is side else 'opp'}")
    return PlayMode(mode)


def to_own_frame(side: Side, x: float, y: float) -> tuple[float, float]:
    return (x, y) if side is Side.LEFT else (-x, -y)


def yaw_in_own_frame(side: Side, degrees: float) -> float:
    return math.radians(norm_deg(degrees if side is Side.LEFT else degrees + 180.0))


def observe(world: World, side: Side, number: int, rng: random.Random, *, noise: float = 0.02) -> WorldState:
    """The world as player ``number`` of ``side`` perceives it this cycle."""
    me = world.player(side, number)
    head = me.head

    def seen(x: float, y: float) -> tuple[bool, float, float]:
        d = distance(me.x, me.y, x, y)
        rel = norm_deg(direction_deg(me.x, me.y, x, y) - head)
        return (abs(rel) <= VIEW_WIDTH / 2 or d <= FEEL_DISTANCE), d, rel

    def noisy(x: float, y: float, d: float) -> tuple[float, float, float]:
        sigma = max(0.01, noise * d)
        nx, ny = x + rng.gauss(0.0, sigma), y + rng.gauss(0.0, sigma)
        ox, oy = to_own_frame(side, nx, ny)
        return _clip(ox, 70.0), _clip(oy, 50.0), sigma

    def noisy_velocity(vx: float, vy: float, spread: float) -> tuple[float, float]:
        """A velocity (m/cycle, absolute) as seen: ``spread`` of noise on each axis, in m/s in the own frame."""
        nvx, nvy = to_own_frame(side, (vx + rng.gauss(0, spread)) * 10, (vy + rng.gauss(0, spread)) * 10)
        return _clip(nvx, 50.0), _clip(nvy, 50.0)

    def told_speed(p: SimPlayer) -> float:
        """m/s: as on rcssserver, a player is told his own type and his team-mates', not the opponents'."""
        return round(world.params_of(p).top_speed * 10, 3)

    sx, sy = to_own_frame(side, me.x + rng.gauss(0, SELF_SIGMA), me.y + rng.gauss(0, SELF_SIGMA))
    vx, vy = to_own_frame(side, me.vx * 10, me.vy * 10)  # m/cycle -> m/s
    myself = Player(
        player_number=number,
        which_team=Team.OUR,
        is_goalie=me.goalie,
        positioning=AbsolutePositioning(
            x=_clip(sx, 70.0),
            y=_clip(sy, 50.0),
            yaw=yaw_in_own_frame(side, me.body + rng.gauss(0, math.degrees(SELF_SIGMA_YAW))),
            sigma_x=SELF_SIGMA,
            sigma_y=SELF_SIGMA,
            sigma_yaw=SELF_SIGMA_YAW,
        ),
        velocity=Velocity(vx=_clip(vx, 50.0), vy=_clip(vy, 50.0)),
        head_angle=math.radians(me.neck),
        stamina=round(me.stamina / world.params.stamina_max, 3),
        top_speed=told_speed(me),
    )

    ball = None
    b = world.ball
    visible, d, rel = seen(b.x, b.y)
    if visible:
        bx, by, sigma = noisy(b.x, b.y, d)
        spread = VELOCITY_FAR_SIGMA if d > VELOCITY_FAR else noise / 4 * d
        bvx, bvy = noisy_velocity(b.vx, b.vy, spread)
        ball = Ball(
            positioning=AbsolutePositioning(x=bx, y=by, sigma_x=sigma, sigma_y=sigma),
            relative=RelativePositioning(
                distance=min(200.0, d), direction=math.radians(norm_deg(rel + me.neck)), sigma_distance=sigma
            ),
            velocity=Velocity(vx=bvx, vy=bvy, sigma_vx=round(spread * 10, 3), sigma_vy=round(spread * 10, 3)),
            age=0,
        )

    others = []
    for p in world.players.values():
        if p is me:
            continue
        visible, d, rel = seen(p.x, p.y)
        if not visible:
            continue
        px, py, sigma = noisy(p.x, p.y, d)
        known = d <= NUMBER_FAR
        velocity = None
        if known:  # as rcssserver's see: a player's velocity comes with his number
            pvx, pvy = noisy_velocity(p.vx, p.vy, noise / 4 * d)
            velocity = Velocity(vx=pvx, vy=pvy)
        others.append(
            Player(
                player_number=p.number if known else None,
                which_team=(Team.OUR if p.side is side else Team.OPP) if d <= TEAM_FAR else None,
                is_goalie=p.goalie if known else None,
                positioning=AbsolutePositioning(
                    x=px, y=py, yaw=yaw_in_own_frame(side, p.body), sigma_x=sigma, sigma_y=sigma
                ),
                relative=RelativePositioning(
                    distance=min(200.0, d), direction=math.radians(norm_deg(rel + me.neck)), sigma_distance=sigma
                ),
                velocity=velocity,
                top_speed=told_speed(p) if known and p.side is side else None,
                age=0,
            )
        )
    game = Game(
        time=world.time,
        play_mode=relative_mode(world.mode, side),
        score_our=world.score[side],
        score_opp=world.score[side.other],
        half=world.half,
    )
    return WorldState(time=world.time, me=myself, ball=ball, players=tuple(others), game=game, heard=heard(world, me))


def heard(world: World, me: SimPlayer) -> tuple[Heard, ...]:
    """The team-mate's say that ``me`` hears this cycle: as on rcssserver (hear capacity 1 a cycle
    from team-mates), the first said within ``audio_cut_dist``; an opponent's is not understood."""
    for side, number, text in world.said:
        speaker = world.players.get((side, number))
        if speaker is None or speaker is me or side is not me.side:
            continue
        if distance(me.x, me.y, speaker.x, speaker.y) <= world.params.audio_cut_dist:
            return (Heard(player_number=number, message=text, time=world.time),)
    return ()


def _clip(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))
