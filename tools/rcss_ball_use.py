"""What our players did with the ball on rcssserver, and what came of it: one table row per reason.

    python tools/rcss_ball_use.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--after 30] [--beyond X]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --out DIR`` writes (``rcss_series``: its
``match-N``): the server's game log (``*.rcg``) and our players' logs, where each decision
component logs every new way of playing the ball (``[CF_9_decision]: t=314 pass: forward pass
to team-mate 10``). Each kick of ours in play is put down to the reason its player's decision
last logged (within ``--after`` cycles before it; "?" if none), in our half or theirs (``--beyond X``:
beyond X m up the field from the halfway line or short of it, e.g. 30 for their goal's end), and judged
by the next kick: a team-mate's (kept) or an opponent's (lost); the kicker's own next touch
(a dribble's next push, a collecting touch) is not counted. A column says how many of those kicks
had an opponent at the ball (within CONTESTED of it the cycle before: his kick or tackle meets
ours) and how many of them were kept. The last column is how far up the field the ball was
``--after`` cycles later, on average (negative: back towards our goal). This is how
docs/performance.md counts what loses the ball.

A second table says where on the field each team had the ball (the share of play-on cycles
after its last kick, by the ball's third of the field, thirds counted from our goal) and where
it won the ball back (its first kick after the other team's).

A third table says how far our moves got: each move (our kicks from the first after one of
theirs, in play or at our set piece, to their next kick) by the third it began in and the
furthest third the ball reached meanwhile.

A fourth sets each team's kicks in play beside the other's (``rcss_series.keeping_of``): by the
half they were kicked in and whether the ball left slower than 1.2 m/cycle (a touch) or faster
(a kick), what came next: the kicker's own kick again, a team-mate's, or the opponents' (a ball
kicked out of play counts by whom the referee gave it to).
"""

from __future__ import annotations

import argparse
import functools
import itertools
import math
import re
import sys
from collections import defaultdict
from collections.abc import Container, Iterator
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_series import (
    Territory,
    keeping_of,
    kick_events,
    moves_of,
    newest_game_log,
    read_rcg,
    side_of,
    territory_of,
)

CONTESTED = 1.2  # m: an opponent this near the ball kicks or tackles it as we kick it (rcssserver adds both)
_DECISION = re.compile(r"\[(\w+?)_(\d+)_decision\]: t=(\d+) (\w+): (.*)")
_NUMBERS = re.compile(r"(?<![\w-])-?\d+(\.\d+)?")


@dataclass
class Outcome:
    kept: int = 0
    lost: int = 0
    advance: list[float] = field(default_factory=list)
    contested_kept: int = 0  # of the kept and lost: those kicked with an opponent at the ball
    contested_lost: int = 0

    def add(self, other: Outcome) -> None:
        """Count ``other``'s kicks in too (another match's, for the same reason)."""
        self.kept += other.kept
        self.lost += other.lost
        self.advance += other.advance
        self.contested_kept += other.contested_kept
        self.contested_lost += other.contested_lost


def reason(text: str) -> str:
    """A logged reason without its numbers (nor the aim after `` @ ``): ``fastest to the ball (12 cycles)`` ->
    ``fastest to the ball``."""
    text = text.split(" @ ")[0]
    words = " ".join(_NUMBERS.sub("", re.sub(r"\(.*?\)", "", text)).split())
    return re.sub(r" ([:,])", r"\1", words)


def logged(match: Path, team: str, pattern: re.Pattern, cycles: Container[int] | None = None) -> Iterator[re.Match]:
    """``pattern``'s matches in the log lines of ``team``'s decisions in one match (``logs-TEAM/``, as
    rcss_match writes them), at the cycles in ``cycles`` (None: at any). The pattern's group 1 is
    the team's name, group 3 the cycle (``[TEAM_N_decision]: ... t=T``)."""
    for log in sorted(match.glob(f"logs-{team}/*.log")):
        for text in log.read_text(errors="replace").splitlines():
            m = pattern.search(text)
            if m and m.group(1) == team and (cycles is None or int(m.group(3)) in cycles):
                yield m


def decisions(match: Path, team: str) -> dict[int, list[tuple[int, str]]]:
    """Shirt number -> [(time, reason)] from our players' logs (``logs-TEAM/``, as rcss_match writes them)."""
    out: dict[int, list[tuple[int, str]]] = defaultdict(list)
    for m in logged(match, team, _DECISION):
        out[int(m.group(2))].append((int(m.group(3)), reason(m.group(5))))
    for entries in out.values():
        entries.sort()
    return out


def game_log(match: Path) -> Path:
    """A match directory's game log (``*.rcg``, ``newest_game_log``); FileNotFoundError if it has none."""
    rcg = newest_game_log(match)
    if rcg is None:
        raise FileNotFoundError(f"no game log (*.rcg) in {match}")
    return rcg


@functools.lru_cache(maxsize=4)
def game(match: Path, team: str, counters: bool = False) -> tuple[list, str, float]:
    """A match's frames (read once; ``counters``: as ``read_rcg`` gives them), our side, and +1 or -1:
    the way our attack goes along x."""
    rcg = game_log(match)
    side = side_of(rcg, team)
    return read_rcg(rcg, counters), side, 1.0 if side == "l" else -1.0


def ball_use(
    match: Path, team: str = "CF", after: int = 30, beyond: float | None = None
) -> dict[tuple[str, str], Outcome]:
    """(reason, where) -> what came of our kicks in play in one match; where: "our half" | "their half",
    or with ``beyond``, "beyond X m" | "short of X m" (metres up the field from the halfway line)."""
    frames, side, forward = game(match, team)
    said = decisions(match, team)
    out: dict[tuple[str, str], Outcome] = defaultdict(Outcome)
    for (i, s, number, x, _), (_, s2, number2, _, _) in itertools.pairwise(kick_events(frames)):
        t, mode, ball, _ = frames[i]
        if s != side or mode != "play_on" or (s2, number2) == (s, number):
            continue
        before = [why for when, why in said.get(number, []) if t - after <= when <= t]
        where = zone(forward * x, beyond)
        o = out[(before[-1] if before else "?", where)]
        kept = s2 == side
        o.kept, o.lost = o.kept + kept, o.lost + (not kept)
        if contested(frames[max(0, i - 1)], side):
            o.contested_kept, o.contested_lost = o.contested_kept + kept, o.contested_lost + (not kept)
        o.advance.append(forward * (frames[min(len(frames) - 1, i + after)][2][0] - ball[0]))
    return out


def zone(x: float, beyond: float | None = None) -> str:
    """Where a kick ``x`` m up the field from the halfway line was taken: our half or theirs, or
    beyond ``beyond`` m or short of it."""
    if beyond is None:
        return "our half" if x < 0 else "their half"
    return f"beyond {beyond:g} m" if x > beyond else f"short of {beyond:g} m"


def contested(frame: tuple, our_side: str) -> bool:
    """An opponent within CONTESTED of the ball in this frame."""
    (bx, by), players = frame[2], frame[3]
    return any(p[0] != our_side and math.hypot(p[2] - bx, p[3] - by) <= CONTESTED for p in players)


def territory(match: Path, team: str = "CF") -> dict[str, Territory]:
    """Where each team ("us", "them") had the ball and won it back, in thirds seen from our goal."""
    frames, side, _ = game(match, team)
    return territory_of(frames, side)


def territory_table(where: dict[str, Territory], opponent: str = "them") -> str:
    rows = [
        "| team | had the ball in our third | middle third | their third | won it in our third | middle third "
        "| their third |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    total = sum(sum(t.held) for t in where.values()) or 1
    for key, name in (("us", "us"), ("them", opponent)):
        t = where[key]
        rows.append(
            f"| {name} | " + " | ".join(f"{n / total:.0%}" for n in t.held) + " | " + " | ".join(map(str, t.won)) + " |"
        )
    return "\n".join(rows)


def moves(match: Path, team: str = "CF") -> list[list[int]]:
    """Our moves by the third each began in and the furthest third the ball reached (``moves_of``)."""
    frames, side, _ = game(match, team)
    return moves_of(frames, side)


def moves_table(counts: list[list[int]]) -> str:
    rows = ["| our moves begun in | moves | got no further than our third | the middle third | reached their third |"]
    rows.append("|---|---:|---:|---:|---:|")
    for begun, (name, row) in enumerate(zip(("our third", "the middle third", "their third"), counts, strict=True)):
        cells = ["" if k < begun else str(n) for k, n in enumerate(row)]  # (a move gets at least as far as it began)
        rows.append(f"| {name} | {sum(row)} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def keeping(match: Path, team: str = "CF") -> dict[tuple[str, str, str], list[int]]:
    """How each team kept the ball it kicked (``keeping_of``)."""
    frames, side, _ = game(match, team)
    return keeping_of(frames, side)


def keeping_table(counts: dict[tuple[str, str, str], list[int]], opponent: str = "them") -> str:
    rows = ["| team | kicked in | kind | kicks | then his own again | a team-mate's | theirs (lost) |"]
    rows.append("|---|---|---|---:|---:|---:|---:|")
    for team, name in (("us", "us"), ("them", opponent)):
        for half in ("own half", "other half"):
            for kind in ("touch", "kick"):
                n, own, mate, lost = counts.get((team, half, kind), (0, 0, 0, 0))
                if n:
                    shares = " | ".join(f"{k} ({k / n:.0%})" for k in (own, mate, lost))
                    where = "its own half" if half == "own half" else "the other's half"
                    rows.append(f"| {name} | {where} | {kind} | {n} | {shares} |")
    return "\n".join(rows)


def table(outcomes: dict[tuple[str, str], Outcome], after: int) -> str:
    rows = [
        "| with the ball | where | kicks | to a team-mate | lost | kept share | an opponent at the ball: kept "
        f"| ball advance after {after} cycles (m) |",
        "|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for (why, half), o in sorted(outcomes.items(), key=lambda kv: -(kv[1].kept + kv[1].lost)):
        n = o.kept + o.lost
        advance = sum(o.advance) / len(o.advance)
        at_ball = f"{o.contested_kept} of {o.contested_kept + o.contested_lost}"
        rows.append(f"| {why} | {half} | {n} | {o.kept} | {o.lost} | {o.kept / n:.0%} | {at_ball} | {advance:+.1f} |")
    return "\n".join(rows)


def match_parser(doc: str) -> argparse.ArgumentParser:
    """The command line every match analysis tool starts from: match directories and ``--team``."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("matches", nargs="+", type=Path, help="match directories (rcss_match.py --out)")
    ap.add_argument("--team", default="CF", help="our team's name in the game log")
    return ap


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--after", type=int, default=30, help="cycles: how long a reason holds, when the advance is read")
    ap.add_argument(
        "--beyond", type=float, help="m up the field from the halfway line: the first table splits there, not at halves"
    )
    args = ap.parse_args()
    total: dict[tuple[str, str], Outcome] = defaultdict(Outcome)
    where = {"us": Territory(), "them": Territory()}
    reached = [[0, 0, 0] for _ in range(3)]
    kept: dict[tuple[str, str, str], list[int]] = defaultdict(lambda: [0, 0, 0, 0])
    for match in args.matches:
        for key, row in keeping(match, args.team).items():
            kept[key] = [a + b for a, b in zip(kept[key], row, strict=True)]
        reached = [
            [a + b for a, b in zip(r, m, strict=True)] for r, m in zip(reached, moves(match, args.team), strict=True)
        ]
        for key, o in ball_use(match, args.team, args.after, args.beyond).items():
            total[key].add(o)
        for key, t in territory(match, args.team).items():
            where[key].held = [a + b for a, b in zip(where[key].held, t.held, strict=True)]
            where[key].won = [a + b for a, b in zip(where[key].won, t.won, strict=True)]
    print(table(total, args.after))
    print()
    print(territory_table(where))
    print()
    print(moves_table(reached))
    print()
    print(keeping_table(kept))
    return 0


if __name__ == "__main__":
    sys.exit(main())
