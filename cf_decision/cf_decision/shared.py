"""What team-mates see, shared (ROS-free).

Each decision component tells the team-mates who may play the ball next (:func:`told_to`), every
cycle, where its player is and the opponents he saw this cycle (:func:`to_tell`: a WorldState, the
Framework Language's word for what one player perceives). Each merges what it heard into its own
picture where that is surer (:func:`merged`). A player's own position is known to a few
decimetres, his picture of a team-mate behind him may be seconds old; and against HELIOS base most
of our passes lost from our half were chosen on a picture in which the man who cut them out was
more than 2 m from where he stood (docs/performance.md, session 41), while a team-mate nearer him
had just seen him. With the words such misses fell from 23% to 5-9% (session 42).
"""

from __future__ import annotations

from collections.abc import Iterable

from cf_lang.ontology import Player, Team, WorldState

from .set_piece import OUR_SET_PIECES
from .situation import UNSEEN_DRIFT, dist, play_mode, xy

TELL_SIGMA = 2.0  # m: an opponent seen this cycle is told when his position is this sure
HEARD_AGE = 2  # cycles (of game time, and of the hearer's perceptions): what a team-mate told is used this long
SAME_MAN = 2.0  # m: a player without a number this near a told one (plus the growth) is him
MOST_TOLD = 22  # players read from one word (a word with more is cut: what is kept stays bounded)
# A word goes to the team-mates who claim the ball within this many cycles: the ones who choose a
# pass next. Reading one costs a receiver about 0.5 ms (eight men); told to all ten, every cycle,
# the words cost our team 35-40 ms of CPU a cycle, told so about none (docs/performance.md, session 42).
WORD_ETA = 10


def told_to(claims: dict[int, int]) -> set[int]:
    """The team-mates a word goes to: those whose latest claim on the ball is WORD_ETA cycles or less."""
    return {number for number, eta in claims.items() if eta <= WORD_ETA}


class Heard:
    """The latest word of each team-mate, and which of them are recent: heard within HEARD_AGE of my
    perceptions (while the clock stops at a set piece, a word's game time stays fresh and its
    count does not)."""

    def __init__(self) -> None:
        self.words: dict[int, tuple[WorldState, int]] = {}  # team-mate number -> (word, perceptions then)
        self.perceptions = 0

    def perceived(self) -> None:
        """Count one perception of mine."""
        self.perceptions += 1

    def keep(self, number: int, word: WorldState) -> None:
        self.words[number] = (word, self.perceptions)

    def recent(self) -> list[WorldState]:
        return [word for word, at in self.words.values() if self.perceptions - at <= HEARD_AGE]


def to_tell(state: WorldState) -> WorldState | None:
    """What I tell team-mates this cycle: my player where he believes he is, and the opponents with a
    number he saw this cycle within TELL_SIGMA; None before he knows who and where he is."""
    me = state.me
    if me is None or me.positioning is None or me.player_number is None:
        return None
    seen = tuple(
        Player(player_number=p.player_number, which_team=Team.OPP, is_goalie=p.is_goalie, positioning=p.positioning)
        for p in state.players
        if p.which_team is Team.OPP
        and p.player_number is not None
        and p.positioning is not None
        and (p.age or 0) == 0
        and _sigma(p) <= TELL_SIGMA
    )
    myself = Player(
        player_number=me.player_number, which_team=Team.OUR, positioning=me.positioning, top_speed=me.top_speed
    )
    return WorldState(time=state.time, me=myself, players=seen)


def merged(state: WorldState, heard: Iterable[WorldState]) -> tuple[WorldState, int]:
    """My picture with team-mates' words merged in, and how many players it took from them.

    A told player (a team-mate where he said he was, an opponent a team-mate saw) replaces mine of
    the same team and number when his position is surer: its sigma, grown UNSEEN_DRIFT a cycle since
    it was told, is smaller than mine; without sigmas, when it is fresher. One I did not have is
    added, and a player without a number believed within SAME_MAN of him is taken to be him (the
    rcss belief keeps a man seen too far to read his number as such). Words older than HEARD_AGE
    cycles, or from the future, are passed over; my own player is never replaced. At our set piece
    only team-mates' own places are taken: the taker has time to look (``with_ball.unseen_near``),
    and a man told from 20-30 m off is rougher than his own look (our set-piece passes from our half
    were kept 81% of the time before the words, 63-73% with them at every mode: session 42).
    """
    players, taken = list(state.players), 0
    own_places_only = play_mode(state) in OUR_SET_PIECES
    mine = state.me.player_number if state.me else None
    index = {(p.which_team, p.player_number): i for i, p in enumerate(players) if p.player_number is not None}
    for word in heard:
        late = state.time - word.time
        if not 0 <= late <= HEARD_AGE:
            continue
        sightings = () if own_places_only else word.players[:MOST_TOLD]
        for told in ((word.me,) if word.me else ()) + sightings:
            if told.positioning is None or told.player_number is None or told.which_team is None:
                continue
            key = (told.which_team, told.player_number)
            if key == (Team.OUR, mine):
                continue
            sigma = None if told.positioning.sigma_x is None else told.positioning.sigma_x + UNSEEN_DRIFT * late
            age = (told.age or 0) + late
            same = index.get(key)
            if same is not None and not _surer(sigma, age, players[same]):
                continue
            # (Built only when taken: pydantic models are dear, and ten words a cycle are merged.)
            now = told.model_copy(
                update={
                    "positioning": told.positioning.model_copy(update={"sigma_x": sigma, "sigma_y": sigma}),
                    "age": age,
                    "relative": None,
                    "velocity": None,
                }
            )
            if same is not None:
                # (His type's top speed, a goalkeeper's flag: what I knew of him stays.)
                keep = players[same]
                players[same] = now.model_copy(
                    update={"top_speed": keep.top_speed or now.top_speed, "is_goalie": keep.is_goalie or now.is_goalie}
                )
            else:
                gate = SAME_MAN + UNSEEN_DRIFT * late
                players = [p for p in players if not _unnamed_near(p, now, gate)]
                players.append(now)
                index = {
                    (p.which_team, p.player_number): i for i, p in enumerate(players) if p.player_number is not None
                }
            taken += 1
    if not taken:
        return state, 0
    return state.model_copy(update={"players": tuple(players)}), taken


def _sigma(p: Player) -> float:
    return p.positioning.sigma_x if p.positioning and p.positioning.sigma_x is not None else 0.0


def _surer(sigma: float | None, age: int, mine: Player) -> bool:
    if mine.positioning is None:
        return True
    if sigma is not None and mine.positioning.sigma_x is not None:
        return sigma < mine.positioning.sigma_x
    return age < (mine.age or 0)


def _unnamed_near(p: Player, told: Player, gate: float) -> bool:
    return (
        p.player_number is None
        and p.which_team in (None, told.which_team)
        and p.positioning is not None
        and dist(xy(p.positioning), xy(told.positioning)) <= gate
    )
