"""The match log exported as an rcssserver game log, checked against one rcssserver 19 wrote (ROS-free).

``data/rcssserver-19.rcg`` is the start of a real game log (rcssserver 19.0.0, ``ULG6``, two of our
players against one, a few cycles): the export must have the same lines, with the same shapes,
that monitors read from it.
"""

from __future__ import annotations

from pathlib import Path

from test_report import play_logged_match

from cf_lang.sexp import Symbol, loads
from cf_sim_backend.embedded.rcg import RCSS_PLAYMODES, export
from cf_sim_backend.embedded.report import read_log

SAMPLE = Path(__file__).parent / "data" / "rcssserver-19.rcg"


def lines_of(path: Path) -> tuple[str, list]:
    text = path.read_text(encoding="ascii").splitlines()
    return text[0], [loads(line) for line in text[1:]]


def keys(line: list) -> set[str]:
    return {item[0].name for item in line[1:]}


def shape(x):
    """The structure of a value: lists kept, numbers as 'n', hex states as 'hex', sides as 'side'."""
    if isinstance(x, list):
        return [shape(i) for i in x]
    if isinstance(x, (int, float)):
        return "n"
    name = x.name if isinstance(x, Symbol) else x
    if name.startswith("0x"):
        return "hex"
    return "side" if name in ("l", "r") else name


def players(show: list) -> list:
    return [p for p in show[2:] if isinstance(p[0], list) and p[0][0] != Symbol("b")]


def test_the_export_has_what_a_real_game_log_has_in_the_same_shapes(tmp_path: Path):
    _, real = lines_of(SAMPLE)
    play_logged_match(tmp_path / "match.jsonl")
    head, ours = lines_of(export(tmp_path / "match.jsonl", tmp_path / "match.rcg"))
    assert head == "ULG6"

    def first(lines, kind):
        return next(line for line in lines if line[0] == Symbol(kind))

    for kind in ("server_param", "player_param", "player_type"):  # only parameters the server has
        assert keys(first(ours, kind)) <= keys(first(real, kind)), kind
    real_show, our_show = first(real, "show"), first(ours, "show")
    assert shape(our_show[2]) == shape(real_show[2])  # the ball
    connected = next(p for p in players(real_show) if shape(p)[2] == "hex")
    assert all(shape(p) == shape(connected) for p in players(our_show))
    assert {line[2].name for line in ours if line[0] == Symbol("playmode")} <= set(RCSS_PLAYMODES)
    numbers = [[shape(x) == "n" for x in first(lines, "team")] for lines in (ours, real)]
    assert numbers[0] == numbers[1]  # (team <time> <left> <right> <score l> <score r>)


def test_positions_are_mirrored_into_the_servers_frame_one_show_per_cycle(tmp_path: Path):
    play_logged_match(tmp_path / "match.jsonl")
    _, cycles, _ = read_log(tmp_path / "match.jsonl")
    _, ours = lines_of(export(tmp_path / "match.jsonl", tmp_path / "match.rcg"))
    shows = [line for line in ours if line[0] == Symbol("show")]
    assert [s[1] for s in shows] == sorted({c["t"] for c in cycles})
    last = cycles[-1]
    show = shows[-1]
    ball = show[2]
    assert (ball[1], ball[2]) == (round(last["ball"][0], 4), round(-last["ball"][1], 4))
    side, number, x, y, *_ = sorted(last["players"])[0]
    entry = next(p for p in players(show) if p[0] == [Symbol(side), number])
    assert (entry[3], entry[4]) == (round(x, 4), round(-y, 4))
    goalie = next(p for p in players(show) if p[0] == [Symbol("l"), 1])
    assert goalie[2] == Symbol("0x9")  # standing goalkeeper, as rcssserver writes it


def test_the_players_counters_are_the_commands_the_simulator_carried_out(tmp_path: Path):
    play_logged_match(tmp_path / "match.jsonl")
    _, _, end = read_log(tmp_path / "match.jsonl")
    _, ours = lines_of(export(tmp_path / "match.jsonl", tmp_path / "match.rcg"))
    last = [line for line in ours if line[0] == Symbol("show")][-1]
    for side in ("l", "r"):
        counts = [next(x for x in p[1:] if isinstance(x, list) and x[0] == Symbol("c"))[1:] for p in players(last)]
        mine = [c for p, c in zip(players(last), counts, strict=True) if p[0][0] == Symbol(side)]
        # The chasers only kick (no tackles), so their kick counters add up to the side's kicks.
        assert sum(c[0] for c in mine) == end["stats"]["kicks"][side] > 0
        assert all(c[1] > 0 for c in mine)  # every chaser dashed
        assert len(mine[0]) == 12  # all of rcssserver's counters
