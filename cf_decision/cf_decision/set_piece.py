"""Our set pieces (ROS-free): who took one, and when he may touch the ball again."""

from __future__ import annotations

from cf_lang.ontology import PlayMode, WorldState

from .situation import Decision, dist, play_mode, xy

OUR_SET_PIECES = frozenset(
    {
        PlayMode.KICK_OFF_OUR,
        PlayMode.KICK_IN_OUR,
        PlayMode.CORNER_KICK_OUR,
        PlayMode.GOAL_KICK_OUR,
        PlayMode.FREE_KICK_OUR,
        PlayMode.INDIRECT_FREE_KICK_OUR,
    }
)
KICKING = frozenset({"shoot", "pass", "dribble", "holdBall", "kick"})  # (a hold-ball touch is a kick)
TOUCHED = 1.5  # m: another player this close to the ball has (or may have) touched it
FRESH_AGE = 1  # cycles: a player seen this long ago is where he was seen (rcssserver: a see every 2 cycles)
TAKER_MEMORY = 100  # cycles after which a set piece's taker plays on as usual


class SetPieceTaker:
    """Remembers that this player took our set piece, until somebody else has touched the ball.

    The rules (rcssserver's free_kick_fault, and the embedded simulator's) forbid the taker a
    second touch before another player's; the decision asks :meth:`may_touch` before it decides
    and tells :meth:`decided` what it chose.
    """

    def __init__(self) -> None:
        self.took_at: int | None = None
        self.spot: tuple[float, float] | None = None  # where the ball lay when the taker chose his kick
        self.mode: PlayMode | None = None  # the set piece he took

    def may_touch(self, state: WorldState) -> bool:
        if self.took_at is None:
            return True
        mode = play_mode(state)
        ball = xy(state.ball.positioning) if state.ball and state.ball.positioning else None
        if mode is self.mode:
            if ball is None or self.spot is None or dist(ball, self.spot) < TOUCHED:
                return True  # not kicked yet
            # Kicked, and the mode lags behind (a goal kick stays one until the ball leaves the area).
        elif mode is not PlayMode.PLAY_ON:
            self.took_at = None  # another stoppage: a new set piece
        # Only players seen just now count: a stale sighting of the opponent who stood at the ball
        # when play stopped would release the taker at once (a free kick fault on rcssserver).
        someone_else = ball is not None and any(
            p.positioning is not None
            and (p.age is None or p.age <= FRESH_AGE)
            and dist(xy(p.positioning), ball) <= TOUCHED
            for p in state.players
        )
        if someone_else or (self.took_at is not None and state.time - self.took_at > TAKER_MEMORY):
            self.took_at = None
        return self.took_at is None

    def decided(self, state: WorldState, decision: Decision) -> None:
        mode = play_mode(state)
        if mode in OUR_SET_PIECES and decision.method in KICKING:
            self.took_at = state.time
            self.spot = xy(state.ball.positioning) if state.ball and state.ball.positioning else None
            self.mode = mode
