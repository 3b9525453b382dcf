"""Does our team play the same way on two back-ends? One analysis of each one's matches, side by side.

    python tools/compare_backends.py --a embedded DIR [DIR ...] --b rcssserver DIR [DIR ...] [--teams CF CFB]

A DIR is a match directory as ``tools/rcss_match.py --out`` (``rcss_series``: its ``match-N``) or
``bench/eval_team.py --out`` writes it: a game log (``*.rcg``) and each decision component's log
(``logs-TEAM/``). Every team named by ``--teams`` that played in a match is counted (``CF CFB``: both
sides of our team against itself, the fairest comparison, since the opponent is then the same on
both back-ends). For each back-end it prints how the play was shared out: what our players did
with the ball (``tools/rcss_ball_use.py``'s reasons, both halves together) as a share of all their
kicks in play, and how often each kept the ball; then how much of the one mix is played another
way in the other (half the sum of the shares' differences), and per match the kicks in play per
1000 cycles, the kept share, the shots (kicks from within 25 m of the goal) and where the ball was.
If the same decision code plays the same way, the shares on the two back-ends are close; where
they part, one back-end's physics or perception differs from the other's (docs/simulator.md).
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import Outcome, ball_use, game, game_log
from rcss_series import kick_events, shots_of, team_names, territory_of

TOP = 12  # reasons listed; the rest are summed as "other"


@dataclass
class BackEnd:
    """What one back-end's matches add up to, over every team counted."""

    name: str
    uses: dict[str, Outcome] = field(default_factory=lambda: defaultdict(Outcome))
    cycles: int = 0  # play-on cycles, once per team counted (kicks per cycle are per team)
    kicks: int = 0
    shots: int = 0
    held: list[int] = field(default_factory=lambda: [0, 0, 0])  # cycles the team had the ball, by third
    teams: int = 0

    def add(self, match: Path, team: str) -> None:
        frames, side, _ = game(match, team)
        for (why, _half), o in ball_use(match, team).items():
            self.uses[why].add(o)
        self.cycles += sum(1 for _, mode, _, _ in frames if mode == "play_on")
        self.kicks += sum(1 for i, s, *_ in kick_events(frames) if s == side and frames[i][1] == "play_on")
        self.shots += shots_of(frames)[side]
        us = territory_of(frames, side)["us"]
        self.held = [a + b for a, b in zip(self.held, us.held, strict=True)]
        self.teams += 1

    def judged(self) -> int:
        """Kicks in play put down to a reason and judged kept or lost."""
        return sum(o.kept + o.lost for o in self.uses.values()) or 1


def teams_in(match: Path, wanted: list[str]) -> list[str]:
    names = team_names(game_log(match)) or ()
    return [t for t in wanted if t in names]


def share(n: int, of: int) -> str:
    return f"{n / of:.0%}" if of else "-"


def reason_table(a: BackEnd, b: BackEnd) -> str:
    total = {
        k: (a.uses[k].kept + a.uses[k].lost) / a.judged() + (b.uses[k].kept + b.uses[k].lost) / b.judged()
        for k in set(a.uses) | set(b.uses)
    }
    order = sorted(total, key=lambda k: -total[k])
    rows = [
        f"| with the ball | share of kicks, {a.name} | {b.name} | kept, {a.name} | {b.name} |",
        "|---|---:|---:|---:|---:|",
    ]

    def cells(names: list[str]) -> str:
        out = []
        for side in (a, b):
            n = sum(side.uses[k].kept + side.uses[k].lost for k in names)
            out.append(share(n, side.judged()))
        for side in (a, b):
            n = sum(side.uses[k].kept + side.uses[k].lost for k in names)
            out.append(f"{share(sum(side.uses[k].kept for k in names), n)} of {n}")
        return " | ".join(out)

    for why in order[:TOP]:
        rows.append(f"| {why} | {cells([why])} |")
    if order[TOP:]:
        rows.append(f"| other ({len(order) - TOP} reasons) | {cells(order[TOP:])} |")
    return "\n".join(rows)


def share_difference(a: BackEnd, b: BackEnd) -> float:
    """How far apart the two back-ends' ways of playing the ball are: half the sum, over the reasons,
    of the difference of their shares of the kicks (0: the same mix, 1: nothing in common)."""
    reasons = set(a.uses) | set(b.uses)
    return (
        sum(
            abs((a.uses[k].kept + a.uses[k].lost) / a.judged() - (b.uses[k].kept + b.uses[k].lost) / b.judged())
            for k in reasons
        )
        / 2
    )


def figures_table(a: BackEnd, b: BackEnd) -> str:
    rows = [f"| per team and match | {a.name} | {b.name} |", "|---|---:|---:|"]

    def line(label: str, fn) -> None:
        rows.append(f"| {label} | {fn(a)} | {fn(b)} |")

    line("teams counted", lambda s: str(s.teams))
    rows.append(f"| the mix of ways above: share of kicks played another way | {share_difference(a, b):.0%} | |")
    line("kicks in play per 1000 play-on cycles", lambda s: f"{1000 * s.kicks / max(1, s.cycles):.0f}")
    line("kicks kept (to a team-mate)", lambda s: share(sum(o.kept for o in s.uses.values()), s.judged()))
    line("shots per 1000 play-on cycles", lambda s: f"{1000 * s.shots / max(1, s.cycles):.1f}")
    for i, third in enumerate(("our third", "the middle third", "their third")):
        line(f"had the ball in {third}", lambda s, i=i: share(s.held[i], s.cycles))
    return "\n".join(rows)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--a", nargs="+", required=True, metavar=("NAME", "DIR"), help="a back-end's name, its matches")
    ap.add_argument("--b", nargs="+", required=True, metavar=("NAME", "DIR"), help="the other back-end's")
    ap.add_argument("--teams", nargs="+", default=["CF", "CFB"], help="our teams' names in the game logs")
    args = ap.parse_args()
    sides = []
    for name, *dirs in (args.a, args.b):
        if not dirs:
            ap.error(f"{name}: no match directories")
        side = BackEnd(name)
        for match in map(Path, dirs):
            for team in teams_in(match, args.teams):
                side.add(match, team)
        sides.append(side)
    print(reason_table(*sides))
    print()
    print(figures_table(*sides))
    return 0


if __name__ == "__main__":
    sys.exit(main())
