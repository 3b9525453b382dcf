"""The match analysis tools on a small game log written here: kicks put down to the decision's reason."""

from __future__ import annotations

import json
import math
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))

from proctree import run_passing_on
from rcss_ball_use import (
    ball_use,
    game_log,
    keeping_table,
    moves_table,
    reason,
    table,
    territory,
    territory_table,
    zone,
)
from rcss_belief_error import errors as belief_errors
from rcss_belief_error import line_errors
from rcss_belief_error import line_table as believed_line_table
from rcss_belief_error import table as belief_table
from rcss_compare import main as compare_main
from rcss_drill import HOLD, Try, ended_for_them, placement, situations, spread, tries_of
from rcss_drill import table as drill_table
from rcss_goals import goal_rows, goals, summary
from rcss_keeper import HEADER, row, shots
from rcss_match import set_aside_earlier
from rcss_options import best_gain, bin_of, in_behind, line_lanes, line_table, map_table, open_map, open_points, options
from rcss_options import table as options_table
from rcss_picture import body_table, by_body, picture
from rcss_picture import table as picture_table
from rcss_reach_fit import LOSSES, lead, loss_table, set_off, set_off_table
from rcss_reach_fit import kicks as reach_kicks
from rcss_reach_fit import table as reach_table
from rcss_run_on import errors as run_on_errors
from rcss_run_on import table as run_on_table
from rcss_series import (
    GAVE_UP,
    again,
    keeping_of,
    match_stats,
    moves_of,
    play_again_if_unplayed,
    read_rcg,
    row_line,
    top_speeds,
)
from rcss_set_pieces import kind_of, set_pieces
from rcss_set_pieces import table as set_piece_table
from rcss_shots import shots as our_shots
from rcss_shots import table as shots_table

from cf_decision import reach


def show(t: int, ball_x: float, kicks: dict[tuple[str, int], int], where: dict[tuple[str, int], float]) -> str:
    players = " ".join(
        f"(({side} {n}) 0 0x1 {where[(side, n)]} 0 0 0 0 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) "
        f"(c {kicks[(side, n)]} 0 0 0 0 0 0 0 0 0 0 0))"
        for side, n in kicks
    )
    return f"(show {t} ((b) {ball_x} 0 0 0) {players})"


def write_match(tmp: Path) -> Path:
    """CF (left) 9 passes to 10, who pushes the ball twice and loses it to PYRUS 3."""
    kicks = {("l", 9): 0, ("l", 10): 0, ("r", 3): 0}
    where = {("l", 9): 10.0, ("l", 10): 30.0, ("r", 3): 35.0}
    touches = {2: ("l", 9), 5: ("l", 10), 6: ("l", 10), 8: ("r", 3)}
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t in range(1, 20):
        if t in touches:
            kicks[touches[t]] += 1
        lines.append(show(t, float(t), kicks, where))
    (tmp / "m.rcg").write_text("\n".join(lines) + "\n")
    logs = tmp / "logs-CF"
    logs.mkdir()
    (logs / "CF_9_rcss_player.log").write_text("[INFO] [1.0] [CF_9_decision]: t=1 pass: forward pass to team-mate 10\n")
    (logs / "CF_10_rcss_player.log").write_text(
        "[INFO] [1.0] [CF_10_decision]: t=4 dribble: space ahead: carry it (5 cycles)\n"
        "[INFO] [1.0] [CF_10_decision]: t=40 shoot: a free shot\n"  # after the kicks: not theirs
    )
    return tmp


def test_read_rcg_gives_each_player_his_number_and_kicks(tmp_path):
    frames = read_rcg(write_match(tmp_path) / "m.rcg")
    assert len(frames) == 19 and frames[0][1] == "play_on"
    t, _, ball, players = frames[7]
    assert t == 8 and ball == (8.0, 0.0)
    assert players == [("l", 9, 10.0, 0.0, 1), ("l", 10, 30.0, 0.0, 2), ("r", 3, 35.0, 0.0, 1)]
    stats = match_stats(tmp_path / "m.rcg", "l")
    assert stats["shots"] == [2, 0]  # CF 10 kicked twice 22.5 m from their goal
    # Fouls and faults against each side: a tackle's foul and a back pass count, an offside not.
    calls = ["foul_charge_l", "indirect_free_kick_r", "back_pass_r", "free_kick_fault_r", "offside_l", "foul_push_r"]
    rcg = tmp_path / "m.rcg"
    rcg.write_text(rcg.read_text() + "".join(f"(playmode {20 + i} {mode})\n" for i, mode in enumerate(calls)))
    stats = match_stats(rcg, "l")
    assert stats["faults"] == [1, 3] and stats["offsides"] == [1, 0]


def test_every_kick_of_ours_is_put_down_to_its_reason_and_judged_by_the_next_kick(tmp_path):
    use = ball_use(write_match(tmp_path), "CF", after=3)
    passed = use[("forward pass to team-mate", "their half")]
    assert (passed.kept, passed.lost, passed.advance) == (1, 0, [3.0])
    carried = use[("space ahead: carry it", "their half")]
    assert (carried.kept, carried.lost) == (0, 1)  # the first push is his own next touch: not counted
    assert set(use) == {("forward pass to team-mate", "their half"), ("space ahead: carry it", "their half")}
    assert passed.contested_kept + passed.contested_lost == 0  # PYRUS 3 stood 8 m from the ball
    text = table(use, 3)
    assert "| forward pass to team-mate | their half | 1 | 1 | 0 | 100% | 0 of 0 | +3.0 |" in text


def test_kicks_are_split_where_asked_instead_of_at_the_halfway_line(tmp_path):
    use = ball_use(write_match(tmp_path), "CF", after=3, beyond=20.0)
    assert set(use) == {("forward pass to team-mate", "short of 20 m"), ("space ahead: carry it", "beyond 20 m")}
    assert (use[("space ahead: carry it", "beyond 20 m")].lost, zone(-5.0), zone(25.0, 20.0)) == (
        1,
        "our half",
        "beyond 20 m",
    )


def test_a_kick_with_an_opponent_at_the_ball_is_counted_apart(tmp_path):
    """PYRUS 3 stands 1 m from the ball when CF 9 passes (rcssserver adds his touch to ours), and
    cuts it out; the same pass with him 2 m off is not contested."""
    for stands, contested in ((3.0, True), (4.0, False)):
        match = tmp_path / str(stands)
        match.mkdir()
        kicks = {("l", 9): 0, ("l", 10): 0, ("r", 3): 0}
        where = {("l", 9): 1.5, ("l", 10): 30.0, ("r", 3): stands}
        lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
        for t in range(1, 12):
            ball = 2.0 if t <= 2 else 2.0 + 2.0 * (t - 2)
            if t == 3:
                kicks[("l", 9)] += 1
            if t == 8:
                kicks[("r", 3)] += 1
            lines.append(show(t, ball, kicks, where))
        (match / "m.rcg").write_text("\n".join(lines) + "\n")
        (match / "logs-CF").mkdir()
        (match / "logs-CF" / "CF_9_rcss_player.log").write_text(
            "[INFO] [1.0] [CF_9_decision]: t=1 pass: keep it: safe pass to team-mate 10\n"
        )
        o = ball_use(match, "CF", after=3)[("keep it: safe pass to team-mate", "their half")]
        assert (o.kept, o.lost) == (0, 1)
        assert (o.contested_kept, o.contested_lost) == ((0, 1) if contested else (0, 0))
        assert ("| 0 of 1 |" in table({("keep it: safe pass to team-mate", "their half"): o}, 3)) is contested


def test_reasons_lose_their_numbers():
    assert (
        reason("fastest to a contested ball (12 cycles): win it and go") == "fastest to a contested ball: win it and go"
    )
    assert reason("forward pass to team-mate 10") == "forward pass to team-mate"
    assert reason("clear the ball @ target -12.0 25.0 ball -35.2 4.1") == "clear the ball"


def test_where_each_team_had_the_ball_and_won_it_back_by_third_of_the_field(tmp_path):
    where = territory(write_match(tmp_path), "CF")
    # The ball rolls from x=1 to 19 (our frame); CF have it from their first kick (t=2) to PYRUS's (t=8).
    assert where["us"].held == [0, 6, 0] and where["us"].won == [0, 0, 0]  # the first kick wins nothing back
    assert where["them"].held == [0, 10, 2] and where["them"].won == [0, 1, 0]  # past x=17.5: their third
    text = territory_table(where, "PYRUS")
    assert "| us | 0% | 33% | 0% | 0 | 0 | 0 |" in text and "| PYRUS | 0% | 56% | 11% | 0 | 1 | 0 |" in text


def test_each_move_of_ours_is_counted_by_the_third_it_began_in_and_the_furthest_it_reached():
    # (A game log's first frame sets the kick counts.) Our 2 kicks at x=-30 and the ball rolls to
    # -10 before their 7 kicks it back; our 4 wins it at -20 and it rolls to 25, 4 kicks again (the
    # same move), and their 7 kicks it at 25.
    touches = {2: ("l", 2), 5: ("r", 7), 8: ("l", 4), 13: ("l", 4), 14: ("r", 7)}
    ball = {1: -30, 2: -30, 3: -15, 4: -10, 5: -10, 6: -15, 7: -20, 8: -20, 9: -10, 10: 5, 11: 20, 12: 25}
    kicks, frames = {("l", 2): 0, ("l", 4): 0, ("r", 7): 0}, []
    for t in range(1, 17):
        if t in touches:
            kicks[touches[t]] += 1
        frames.append((t, "play_on", (ball.get(t, 25.0), 0.0), [(s, n, 0.0, 0.0, k) for (s, n), k in kicks.items()]))
    assert moves_of(frames, "l") == [[0, 1, 1], [0, 0, 0], [0, 0, 0]]
    swap = {"l": "r", "r": "l"}  # the same match, with us playing from the right
    flipped = [(t, m, (-b[0], b[1]), [(swap[p[0]], *p[1:]) for p in ps]) for t, m, b, ps in frames]
    assert moves_of(flipped, "r") == moves_of(frames, "l")
    text = moves_table(moves_of(frames, "l"))
    assert "| our third | 2 | 0 | 1 | 1 |" in text and "| the middle third | 0 |  | 0 | 0 |" in text


def test_each_teams_kicks_are_counted_by_half_and_kind_and_by_whom_the_ball_went_to_next():
    # t: (kicker, his x, the ball's x this frame); the ball's x the next frame says how fast it left.
    kicks_at = {2: ("l", 2, -30.0), 4: ("l", 4, -20.0), 5: ("l", 4, -20.0), 7: ("r", 7, 10.0), 10: ("l", 2, 5.0)}
    ball = {1: -30.0, 2: -30.0, 3: -28.0, 4: -20.0, 5: -19.5, 6: -17.0, 7: 10.0, 8: 12.0, 9: 14.0, 10: 5.0, 11: 7.0}
    modes = {9: "kick_in_l", 12: "foul_charge_r"}  # 7's kick went out: our throw-in; then they fouled us
    where = {("l", 2): -30.0, ("l", 4): -20.0, ("r", 7): 10.0}
    counts, frames = {key: 0 for key in where}, []
    for t in range(1, 14):
        if t in kicks_at:
            side, number, x = kicks_at[t]
            counts[(side, number)] += 1
            where[(side, number)] = x
        if t == 13:
            counts[("r", 7)] += 1  # their free-kick taker: the kick that ends the pairs
        players = [(s, n, where[(s, n)], 0.0, k) for (s, n), k in counts.items()]
        frames.append((t, modes.get(t, "play_on"), (ball.get(t, 7.0), 0.0), players))
    kept = keeping_of(frames, "l")
    assert kept[("us", "own half", "kick")] == [2, 0, 1, 1]  # 2 to 4 (a team-mate); 4's kick to 7 (theirs)
    assert kept[("us", "own half", "touch")] == [1, 1, 0, 0]  # 4's touch of 0.5 m, then his own kick
    assert kept[("them", "own half", "kick")] == [1, 0, 0, 1]  # out of play: our throw-in
    assert kept[("us", "other half", "kick")] == [1, 0, 1, 0]  # foul_charge_r names the offender: our free kick
    text = keeping_table(kept, "PYRUS")
    assert "| us | its own half | kick | 2 | 0 (0%) | 1 (50%) | 1 (50%) |" in text
    assert "| PYRUS | its own half | kick | 1 | 0 (0%) | 0 (0%) | 1 (100%) |" in text


def test_a_match_played_again_into_its_directory_sets_the_earlier_ones_files_aside(tmp_path):
    assert set_aside_earlier(tmp_path / "new") is None and set_aside_earlier(tmp_path) is None
    (tmp_path / "logs-CF").mkdir()
    (tmp_path / "logs-CF" / "CF_9_rcss_player.log").write_text("t=5 pass: forward pass to team-mate 10\n")
    for name in ("20261127120632-CF_0-vs-HELIOS_base_6.rcg", "server.log", "team-CF.log", "notes.txt"):
        (tmp_path / name).write_text(name)
    aside = set_aside_earlier(tmp_path)
    assert aside == tmp_path / "earlier-1" and (aside / "logs-CF" / "CF_9_rcss_player.log").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["earlier-1", "notes.txt"]  # (not the tool's: left)
    (tmp_path / "20261127130000-CF_1-vs-HELIOS_base_2.rcg").write_text("")
    assert set_aside_earlier(tmp_path) == tmp_path / "earlier-2"
    for name in ("incomplete.rcg", "20261127120000-CF_0-vs-null.rcg", "20261127121000-CF_0-vs-HELIOS_base_5.rcg"):
        (tmp_path / name).write_text("")
    assert game_log(tmp_path).name == "20261127121000-CF_0-vs-HELIOS_base_5.rcg"  # the newest finished one


def test_a_match_the_server_gave_up_on_is_played_again_and_one_that_failed_otherwise_is_not(tmp_path):
    """rcssserver quits a synch-mode match when a client missed 20 cycles running (a slow start beside
    other work): the series plays it again, up to --replays times, and says so in the table."""
    import argparse

    played = []

    def play_one(args, n, logs):
        out = tmp_path / f"match-{n}"
        out.mkdir(exist_ok=True)
        text = logs[len([m for m in played if m == n])]
        played.append(n)
        (out / "server.log").write_text(text)
        if "Exiting" in text or "Segmentation" in text:
            return {"n": n, "error": "exit 1: RuntimeError: rcssserver exited with 1"}
        return {"n": n, "score": [1, 0], "cpu_ms_per_cycle": 100.0, "relaunched": 0, "executed": 1.0}

    args = argparse.Namespace(out=str(tmp_path), replays=1)
    gave_up = f"Someone missed a cycle at 20\n{GAVE_UP}! Exiting\n"
    row = play_again_if_unplayed(args, 1, lambda a, n: play_one(a, n, [gave_up, "ok"]))
    assert row["score"] == [1, 0] and row["replayed"] == 1 and played == [1, 1]
    assert row_line(row).startswith("| 1 (played again) | 1:0 |")
    row = play_again_if_unplayed(args, 2, lambda a, n: play_one(a, n, [gave_up, gave_up, "ok"]))
    assert "error" in row and row["replayed"] == 1 and played.count(2) == 2  # at most --replays times
    row = play_again_if_unplayed(args, 3, lambda a, n: play_one(a, n, ["Segmentation fault", "ok"]))
    assert "error" in row and "replayed" not in row and played.count(3) == 1  # another failure: told, not hidden
    args.replays = 0
    assert "error" in play_again_if_unplayed(args, 4, lambda a, n: play_one(a, n, [gave_up, "ok"]))


def test_tackles_idle_cycles_and_time_in_their_third_are_read_from_the_game_log(tmp_path, capsys):
    """CF 9 has the ball at his feet for 4 cycles and kicks it in one; PYRUS 3 tackles twice, missing once."""

    def player(side, n, x, state, kicks, tackles):
        return f"(({side} {n}) 0 {state:#x} {x} 0 0 0 0 0 (v h 120) (s 8000 1 1 0) (c {kicks} 0 0 0 0 0 0 0 {tackles} 0 0))"

    frames = [  # (ball x, CF 9 kicks, PYRUS 3 tackles, PYRUS 3 state)
        (10.5, 0, 0, 0x1),
        (10.5, 0, 0, 0x1),  # idle: the ball 0.5 m from him, no kick
        (10.5, 0, 1, 0x1001),  # idle again; PYRUS 3's tackle hits
        (20.0, 1, 1, 0x1),  # he kicked it away, into their third (past x=17.5)
        (20.0, 1, 2, 0x2001),  # the ball gone; PYRUS 3's second tackle missed
        (20.0, 1, 2, 0x1),
    ]
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t, (ball, kicks, tackles, state) in enumerate(frames, start=1):
        ours, theirs = player("l", 9, 10.0, 0x1, kicks, 0), player("r", 3, 12.0, state, 0, tackles)
        lines.append(f"(show {t} ((b) {ball} 0 0 0) {ours} {theirs})")
    match = tmp_path / "match-1"
    match.mkdir()
    (match / "m.rcg").write_text("\n".join(lines) + "\n")
    stats = match_stats(match / "m.rcg", "l")
    assert stats["tackles"] == [[0, 0], [1, 2]]
    assert stats["idle"] == [2, 3, 0]  # of the 3 cycles with the ball at his feet (and a next cycle), 2 idle
    assert stats["attacking"] == [1.0, 0.0]  # ours from his kick on, every cycle of it in their third
    row = {"n": 1, "score": [0, 0], "cpu_ms_per_cycle": 1.0, "relaunched": 0, "executed": 1.0}
    (tmp_path / "series.json").write_text(__import__("json").dumps([row]))
    assert again(tmp_path / "match-1", "CF") == 2  # no series there
    assert again(tmp_path, "CF") == 0
    assert "| 1 | 0:0 | 0:0 | 100%:0% | 100%:0% | 0/0:1/2 | 67% of 3, 0 held |" in capsys.readouterr().out


def test_idle_cycles_at_the_ball_while_his_own_tackle_holds_him_are_told_apart(tmp_path):
    """CF 9 idles once with the ball at his feet, tackles, idles twice (held), and 10 cycles on once more (free)."""
    tackles_by_frame = [0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]  # his tackle between frames 2 and 3
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t, tackles in enumerate(tackles_by_frame, start=1):
        ball = 10.5 if t in (1, 2, 3, 4, 13) else 30.0  # at his feet in frames 1-4 and 13 only
        me = f"((l 9) 0 0x1 10.0 0 0 0 0 0 (v h 120) (s 8000 1 1 0) (c 0 0 0 0 0 0 0 0 {tackles} 0 0))"
        lines.append(f"(show {t} ((b) {ball} 0 0 0) {me})")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    # frame 1 idle and free; 2: he tackles; 3 and 4 idle, held (frames 3-12); 13 idle, free again
    assert match_stats(tmp_path / "m.rcg", "l")["idle"] == [4, 5, 2]


def set_piece_log(tmp: Path, cf_side: str) -> Path:
    """CF kicks off from 1 m behind the ball; its 9 takes the pass at x = 20, their 3 wins it at 25."""
    sign = 1.0 if cf_side == "l" else -1.0
    us, them = cf_side, "r" if cf_side == "l" else "l"
    kicks = {(us, 10): 0, (us, 9): 0, (them, 3): 0}
    x, modes = 0.0, {1: f"kick_off_{us}", 2: "play_on", 30: f"kick_in_{them}"}
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)" if us == "l" else "(team 1 PYRUS CF 0 0)"]
    for t in range(1, 31):
        if t in modes:
            lines.append(f"(playmode {t} {modes[t]})")
        if t == 2:
            kicks[(us, 10)] += 1
        elif 2 < t <= 12:
            x += 2.0  # the pass rolls on to 20 m up the field
        elif t == 13:
            kicks[(us, 9)] += 1
        elif t == 20:
            kicks[(them, 3)] += 1
        taker = (-1.0, 0.0) if t < 2 else (-0.4, 0.0)  # he runs on after his kick
        where = {(us, 10): taker, (us, 9): (20.0, 0.0), (them, 3): (25.0, 0.0)}
        players = " ".join(
            f"(({s} {n}) 0 0x1 {sign * x} {y} 0 0 0 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) "
            f"(c {kicks[(s, n)]} 0 0 0 0 0 0 0 0 0 0 0))"
            for (s, n), (x, y) in where.items()
        )
        at = 2.1 if t == 2 else x
        lines.append(f"(show {t} ((b) {sign * at} 0 0 0) {players})")
    (tmp / "m.rcg").write_text("\n".join(lines) + "\n")
    return tmp / "m.rcg"


def test_each_set_piece_of_ours_is_measured_by_its_kick_and_what_came_of_it(tmp_path):
    for side in ("l", "r"):
        rcg = set_piece_log(tmp_path, side)
        (piece,) = set_pieces(rcg, "CF")
        assert piece.kind == "kick_off" and piece.time == 2
        assert abs(piece.speed - 2.1) < 1e-9 and abs(piece.taker_gap - 1.0) < 1e-9  # a weak kick from 1 m
        assert piece.theirs_after == 18 and piece.furthest == 20.0  # theirs at t=20; ours up to 20 m
        assert piece.near_at_loss == (1, 1)  # our 9 and their 3 by the ball at x = 20; our taker 20 m back
        text = set_piece_table([piece], 150)
        assert "| kick_off | 1 | 2.10 | 1.00 | 18 | 20.0 | 1 | 1 : 1 |" in text
    assert kind_of("kick_in_l", "l") == "kick_in" and kind_of("kick_in_r", "l") is None
    assert kind_of("free_kick_fault_l", "l") is None  # a fault is the other side's free kick, not ours


def test_the_opponents_a_decision_believed_are_set_against_the_game_logs_truth(tmp_path):
    match = write_match(tmp_path)  # PYRUS 3 stands at x = 35 (our frame: CF plays left to right)
    (match / "logs-CF" / "CF_9_rcss_player.log").write_text(
        "[INFO] [1.0] [CF_9_decision]: t=2 pass: forward pass to team-mate 10 @ target 30.0 0.0 ball 2.0 0.0 "
        "opp 34.0 0.5 1.0\n"  # believed 1.1 m from where he stands: known
        "[INFO] [1.0] [CF_9_decision]: t=3 pass: forward pass to team-mate 10 @ target 30.0 0.0 ball 3.0 0.0 "
        "opp 20.0 0.0 4.0\n"  # 15 m off: not known
        "[INFO] [1.0] [CF_9_decision]: t=4 pass: safe pass to team-mate 10 @ target 30.0 0.0 ball 4.0 0.0 opp \n"
    )
    rows = picture(match, "CF", near=40.0, within=3.0)
    assert rows == {"forward pass to team-mate": [2, 2, 1], "safe pass to team-mate": [1, 1, 1]}
    assert picture(match, "CF", near=25.0)["forward pass to team-mate"] == [2, 0, 0]  # 31-33 m off the ball
    assert "| forward pass to team-mate | 2 | 2 | 1 | 50% |" in picture_table(rows, 40.0, 3.0)
    # By where the man stood from the decider: 9 at x = 10 faces up the field (body 0), PYRUS 3 25 m ahead.
    around = by_body(match, "CF", near=40.0, within=3.0)
    assert around == {(0, "20 m or more"): [3, 2]}
    assert "| 0-30 | - | - | 2 of 3 (67%) |" in body_table(around, 3.0)


def test_a_man_out_of_sight_is_set_against_the_truth_kept_where_seen_and_run_on(tmp_path):
    """PYRUS 3 runs up the field 1 m a cycle (the game log shows 0.4 m/cycle: after the decay)."""
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t in range(1, 13):
        x = 20.0 + (t - 1)
        lines.append(
            f"(show {t} ((b) 10 0 0 0) ((l 9) 0 0x1 0 0 0 0 0 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0))"
            f" ((r 3) 0 0x1 {x} 0 0.4 0 0 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0)))"
        )
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    rows = run_on_errors(tmp_path, "CF", [2, 10], (5.0, 25.0))
    assert len(rows[2]) == 10 and all(kept == pytest.approx(2.0) for kept, _ in rows[2])
    assert all(ran == pytest.approx(0.1) for _, ran in rows[2])  # 1 + 0.9 m run on, 2 m truly
    assert len(rows[10]) == 2 and all(kept == pytest.approx(10.0) and ran < 4.0 for kept, ran in rows[10])
    assert "| 2 | 10 | 2.00 | 0% | 0.10 | 0% |" in run_on_table(rows)


def players_at(where: dict, kicks_of: dict, goalies: tuple = (("r", 1),)) -> str:
    """A show line's players at (x, y), with their kick counters; ``goalies`` are goalkeepers (state
    0x9, as rcssserver writes it: standing and goalie; 0x2 is a kick)."""
    return " ".join(
        f"(({side} {n}) 0 {'0x9' if (side, n) in goalies else '0x1'} {x} {y} 0 0 0 0 (v h 120) (fp 0 0) "
        f"(s 8000 1 1 130600) (c {kicks_of[(side, n)]} 0 0 0 0 0 0 0 0 0 0))"
        for (side, n), (x, y) in where.items()
    )


def test_the_reach_model_is_replayed_on_the_game_logs_truth_of_each_kick(tmp_path):
    """CF 9 passes 2 m/cycle to 10, 9.5 m on (kept); 10 kicks it on with nobody of ours ahead (lost)."""
    where = {("l", 9): (10.0, 0.0), ("l", 10): (20.0, 0.0), ("r", 3): (40.0, 0.0), ("r", 1): (50.0, 0.0)}
    kicks_of = {key: 0 for key in where}
    touches = {2: ("l", 9), 7: ("l", 10), 12: ("r", 3)}
    ball, velocity = 10.5, 0.0
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t in range(1, 16):
        if t in touches:
            kicks_of[touches[t]] += 1
            velocity = 2.0 if t < 12 else 0.0
        elif t > 2:
            ball, velocity = ball + velocity, velocity * 0.94
        lines.append(f"(show {t} ((b) {ball:.4f} 0 0 0) {players_at(where, kicks_of)})")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    first, second = reach_kicks(tmp_path, "CF")
    assert first.kept and not second.kept and abs(first.velocity[0] - 2.0) < 1e-3
    assert first.opponents[-1] == ((50.0, 0.0), True)  # the goalkeeper, by the game log's state bit
    assert lead(first, 1) >= 4 and lead(second, 1) <= -3  # nobody of ours ahead of the second
    assert lead(first, 3) < lead(first, 1)  # a team-mate who sets off later is there later
    text = reach_table([first, second], [1])
    assert "| 1 cycle | 0/1 (0%) | - | - | - | 1/1 (100%) |" in text
    assert first.lost == "" and second.lost == LOSSES[3]  # nobody of ours came within 2 m of it
    assert f"| {LOSSES[3]} | 1 | 100% |" in loss_table([first, second])


def pass_along_x(tmp_path: Path, where: dict, cycles: int, step=lambda t, where, kicks_of: None) -> None:
    """Write a game log: CF 9 kicks the ball from x = 10.5 at 2 m/cycle along y = 0 in cycle 2;
    ``step(t, where, kicks_of)`` moves players and counts their kicks each cycle."""
    kicks_of = {key: 0 for key in where}
    ball, velocity = 10.5, 0.0
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t in range(1, cycles):
        if t == 2:
            kicks_of[("l", 9)] += 1
            velocity = 2.0
        elif t > 2:
            ball, velocity = ball + velocity, velocity * 0.94
        step(t, where, kicks_of)
        lines.append(f"(show {t} ((b) {ball:.4f} 0 0 0) {players_at(where, kicks_of)})")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize(("mate_y", "their_touch", "how"), [(1.5, 9, 2), (0.5, 9, 1), (9.0, 2, 0)])
def test_a_lost_kick_says_how_near_a_team_mate_came_or_that_an_opponent_kicked_it_at_once(
    tmp_path, mate_y, their_touch, how
):
    """CF 9's kick rolls past CF 10 (standing ``mate_y`` off its line at x = 16); PYRUS 3 kicks it
    in frame ``their_touch`` (2: in the same cycle as CF 9)."""

    def their_kick(t, where, kicks_of):
        kicks_of[("r", 3)] += t == their_touch

    where = {("l", 9): (10.0, 0.0), ("l", 10): (16.0, mate_y), ("r", 3): (30.0, 0.0), ("r", 1): (50.0, 0.0)}
    pass_along_x(tmp_path, where, 14, their_kick)
    (kick,) = reach_kicks(tmp_path, "CF")
    assert not kick.kept and kick.lost == LOSSES[how]


def test_a_receiver_sets_off_in_the_first_cycle_he_moves_towards_the_balls_path(tmp_path):
    """CF 9 passes 2 m/cycle along y = 0; CF 10, 6 m off the line, stands 2 cycles, then runs to it."""

    def run_in(t, where, kicks_of):
        if t >= 5:
            x, y = where[("l", 10)]
            where[("l", 10)] = (x, max(0.5, y - 0.8))

    pass_along_x(tmp_path, {("l", 9): (10.0, 0.0), ("l", 10): (22.0, 6.0), ("r", 3): (45.0, 10.0)}, 16, run_in)
    lags = set_off(tmp_path, "CF")
    assert lags["us"] == {3: 1} and not lags["them"]
    text = set_off_table(lags, "CF")
    assert "| CF | 1 | 0% | 0% | 100% |" in text and "| opponents | 0 | - |" in text


def test_each_sides_top_speed_is_read_from_the_types_its_players_kick_off_with(tmp_path):
    def player_type(i, rate):  # top speed: 100 * rate * 1.0 / (1 - 0.4)
        return f"(player_type (id {i})(player_speed_max 1.05)(stamina_inc_max 45)(player_decay 0.4)" + (
            f"(dash_power_rate {rate})(effort_max 1))"
        )

    def kick_off(t, types):
        players = " ".join(f"(({s} {n}) {ty} 0x1 0 0 0 0 0 0 (v h 120))" for (s, n), ty in types.items())
        return f"(show {t} ((b) 0 0 0 0) {players})"

    before = {("l", 1): 0, ("l", 2): 0, ("l", 3): 0, ("r", 1): 0, ("r", 2): 0, ("r", 3): 0}
    at_kick_off = {("l", 1): 0, ("l", 2): 1, ("l", 3): 2, ("r", 1): 3, ("r", 2): 0, ("r", 3): 3}
    lines = ["ULG6", player_type(0, 0.006), player_type(1, 0.0057), player_type(2, 0.0051), player_type(3, "x")]
    lines += ["(team 0 CF HELIOS 0 0)", kick_off(0, before), kick_off(1, at_kick_off)]
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    # Ours (left): 0.95 and 0.85, the goalkeeper left out; theirs: type 0 (1.0) and 3, unreadable, left out.
    assert top_speeds(tmp_path / "m.rcg", "l") == [0.9, 1.0]
    assert top_speeds(tmp_path / "m.rcg", "r") == [1.0, 0.9]
    (tmp_path / "m.rcg").write_text("ULG6\n" + kick_off(1, at_kick_off) + "\n")
    assert top_speeds(tmp_path / "m.rcg", "l") is None  # a log without types


def write_one_kick(tmp_path: Path, where: dict) -> None:
    """A game log of five cycles in play, everyone standing ``where``; CF 9 kicks the ball (at 0.5, 0) at t = 2."""
    kicks_of = {key: 0 for key in where}
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    for t in range(1, 6):
        kicks_of[("l", 9)] += t == 2
        lines.append(f"(show {t} ((b) 0.5 0 0 0) {players_at(where, kicks_of)})")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")


def test_the_truth_of_each_kick_says_how_far_up_a_ball_reached_a_team_mate_first(tmp_path):
    """CF 9 on the ball in the middle, CF 10 25 m up with nobody near: a ball gains 20 m or more."""
    where = {("l", 9): (0.0, 0.0), ("l", 10): (25.0, 0.0), ("r", 3): (-30.0, 20.0), ("r", 1): (50.0, 0.0)}
    write_one_kick(tmp_path, where)
    counts = options(tmp_path, "CF")
    assert counts == {("middle third", "20 m or more"): 1}
    assert "| middle third | 1 | 0 | 0 | 0 | 0 | 1 |" in options_table(counts)
    # Twelve men 3 m round the ball: every way is theirs.
    ring = [reach.Runner((3.0 * math.cos(k * math.pi / 6), 3.0 * math.sin(k * math.pi / 6))) for k in range(12)]
    assert best_gain((0.0, 0.0), [(25.0, 0.0)], ring, 2.7, 2) is None and bin_of(None) == "none"
    assert bin_of(-3.0) == "< 0 m" and bin_of(12.0) == "10-20 m"


def test_the_map_says_where_a_team_mate_standing_would_have_been_found(tmp_path):
    """CF 9 kicks from the middle; PYRUS 3 stands on the point (10, 0): a team-mate there is not open,
    one 10 m to the side of him is, and points behind the ball or beyond 40 m are out of range."""
    where = {("l", 9): (0.0, 0.0), ("r", 3): (10.0, 0.0), ("r", 1): (50.0, 0.0)}
    write_one_kick(tmp_path, where)
    in_range, seen = open_map(tmp_path, "middle third", "CF", margin=1)
    assert in_range[(10, 0)] == 1 and seen[(10, 0)] == 0
    assert seen[(10, 10)] == 1
    assert in_range[(-10, 0)] == 0 and in_range[(45, 0)] == 0
    assert open_map(tmp_path, "our third", "CF") == ({}, {})
    assert "| 0 | - |" in map_table(in_range, seen)  # x = -50: never in range
    # Nobody else on the field: every point in range is open.
    reachable, open_ = open_points((0.0, 0.0), [], 1)
    assert reachable == open_ and (20, 0) in open_


def test_the_line_view_says_where_a_ball_in_behind_their_line_was_there(tmp_path):
    """CF 9 kicks from the middle; PYRUS's line is its man 2 at (20, -20) (its keeper is the last man);
    CF 10 stands on the line at y = 20, CF 11 at y = -21. The lane behind the defender is closed, its
    mirror open."""
    where = {("l", 9): (0.0, 0.0), ("l", 10): (18.5, 20.0), ("l", 11): (18.0, -21.0)}
    where |= {("r", 2): (20.0, -20.0), ("r", 1): (50.0, 0.0)}
    write_one_kick(tmp_path, where)
    lanes = line_lanes(tmp_path, "middle third", "CF", margin=1)
    assert lanes[("kicks", 20)] == 1 and lanes[("open", 20)] == 1 and lanes[("ours", 20)] == 1
    assert lanes[("his", 20)] == 1  # and the ball in behind was there for him, from where he stood
    assert lanes[("ours", -20)] == 1 and lanes[("his", -20)] == 0  # on the line, behind which their man is
    assert lanes[("open", 25)] == 1 and lanes[("ours", 25)] == 0  # open, but nobody of ours there
    assert lanes[("open", -25)] == 0  # the defender at (20, -20) has that ball first
    assert "| 20 | 1 | 100 | 100 | 1 |" in line_table(lanes)
    assert line_lanes(tmp_path, "our third", "CF") == {}
    # Straight ahead of the ball a pass meets him before the line: to his feet, not in behind.
    assert not in_behind((0.5, 0.0), [], 20.0, (19.5, 0.0), 1) and in_behind((0.5, 0.0), [], 20.0, (19.5, 25.0), 1)
    # One opponent only: no line to stand on.
    alone = tmp_path / "alone"
    alone.mkdir()
    write_one_kick(alone, {("l", 9): (0.0, 0.0), ("r", 1): (50.0, 0.0)})
    assert line_lanes(alone, "middle third", "CF") == {}


def goals_match(tmp: Path) -> Path:
    """CF (left) scores from 8 m after winning the ball in PYRUS's third; PYRUS scores from its kick-off,
    the shot touched by CF 2 on its way in. Each goalkeeper flagged as one (state 0x9)."""
    at = {("l", 1): (-50.0, 0.0), ("l", 2): (-45.0, 0.0), ("l", 9): (40.0, 5.0), ("l", 10): (0.0, 0.0)}
    at |= {("r", 1): (51.0, 0.0), ("r", 4): (35.0, 0.0), ("r", 9): (-38.0, -2.0)}
    kicks = dict.fromkeys(at, 0)
    ball = {t: (float(t) * 3.0, 0.0) for t in range(1, 40)}
    ball |= {9: (40.0, 5.0), 11: (45.0, 3.0), 21: (0.0, 0.0), 24: (-40.0, -2.0)}
    touches = {3: ("l", 10), 6: ("l", 9), 8: ("r", 4), 10: ("l", 9), 12: ("l", 9)}
    touches |= {22: ("r", 9), 25: ("r", 9), 27: ("l", 2)}
    modes = {1: "kick_off_l", 3: "play_on", 15: "goal_l", 20: "kick_off_r", 22: "play_on", 29: "goal_r"}
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)"]
    for t in range(1, 32):
        if t in modes:
            lines.append(f"(playmode {t} {modes[t]})")
        if t in touches:
            kicks[touches[t]] += 1
        players = " ".join(
            f"(({side} {n}) 0 {'0x9' if n == 1 else '0x1'} {x} {y} 0 0 0 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) "
            f"(c {kicks[(side, n)]} 0 0 0 0 0 0 0 0 0 0))"
            for (side, n), (x, y) in at.items()
        )
        lines.append(f"(show {t} ((b) {ball[t][0]} {ball[t][1]} 0 0) {players})")
    match = tmp / "match-1"
    match.mkdir()
    (match / "m.rcg").write_text("\n".join(lines) + "\n")
    return match


def test_each_goal_is_put_down_to_its_shot_the_keeper_and_how_the_move_began(tmp_path):
    ours, theirs = goals(goals_match(tmp_path))
    assert (ours.ours, ours.time, ours.scorer, ours.shot, ours.touched) == (True, 15, 9, (45.0, 3.0), "")
    assert math.isclose(ours.distance, math.hypot(7.5, 3.0)) and math.isclose(ours.keeper_off, 1.5)
    # CF lost the ball at t=8 and won it back at (40, 5): two kicks, 6 cycles to the goal.
    assert (ours.kicks, ours.cycles, ours.began) == (2, 6, "won in the attacking third")
    # PYRUS's frame: x towards CF's goal. Its move began with its kick-off; CF 2 touched the shot.
    assert (theirs.ours, theirs.scorer, theirs.shot, theirs.touched) == (False, 9, (40.0, 2.0), "2")
    assert math.isclose(theirs.distance, math.hypot(12.5, 2.0)) and math.isclose(theirs.keeper_off, 2.5)
    assert (theirs.kicks, theirs.cycles, theirs.began) == (2, 8, "kick_off")
    assert "| 15 | us | 9 | 45.0, 3.0 | 8.1 | - | 1.5 | 2 | 6 |" in goal_rows([ours])
    text = summary([ours, theirs])
    assert "| for us | 1 | 1 | 0 | 0 | 0 | 1 | 0 | 0 | 2 | 6 |" in text
    assert "| against us | 1 | 0 | 1 | 0 | 1 | 0 | 0 | 0 | 2 | 8 |" in text


def test_an_embedded_match_is_read_by_the_same_tools_and_set_beside_another_back_ends(tmp_path):
    """bench/eval_team.py --out writes what rcss_match --out does: the tools read either back-end."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
    from compare_backends import BackEnd, figures_table, reason_table, share_difference, teams_in
    from eval_team import play

    play(3, 5, 300, opponent="ours", out=tmp_path)
    match = tmp_path / "match-3"
    said = (match / "logs-CF").glob("*.log")
    assert any("_decision]: t=" in log.read_text() for log in said)  # the decisions' own log lines
    frames = read_rcg(next(match.glob("*.rcg")))
    assert sum(kicks for *_, kicks in frames[-1][3]) > 0  # the game log counts the kicks
    uses = ball_use(match, "CF")
    assert sum(o.kept + o.lost for o in uses.values()) > 0
    assert "?" not in {why for why, _ in uses}  # every kick in play put down to a logged reason
    assert teams_in(match, ["CF", "CFB", "X"]) == ["CF", "CFB"]
    a, b = BackEnd("embedded"), BackEnd("again")
    for side in (a, b):
        for team in ("CF", "CFB"):
            side.add(match, team)
    rows = reason_table(a, b).splitlines()
    assert rows[0].startswith("| with the ball | share of kicks, embedded | again |")
    assert all(r.split(" | ")[1] == r.split(" | ")[2] for r in rows[2:])  # the same matches: the same shares
    assert "| teams counted | 2 | 2 |" in figures_table(a, b)
    assert share_difference(a, b) == pytest.approx(0.0)
    b.uses.clear()
    b.uses["something else"].kept = 1
    assert share_difference(a, b) == pytest.approx(1.0)


def test_what_a_decision_believed_of_the_ball_is_set_against_the_game_logs_truth(tmp_path):
    """The right side's player (his frame: x and y turned round) believed the ball 0.5 m off and its
    velocity 0.1 m/cycle off; a remembered ball (age 2) and a still one are not counted."""
    lines = ["ULG6", "(team 1 PYRUS CF 0 0)", "(playmode 1 play_on)"]
    lines += [f"(show {t} ((b) {10.0 - t} 3 -1.0 0.5) ((r 9) 0 0x1 20 3 0 0 0 0))" for t in range(1, 6)]
    lines.append("(show 6 ((b) 4 3 0 0) ((r 9) 0 0x1 20 3 0 0 0 0))")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    logs = tmp_path / "logs-CF"
    logs.mkdir()

    def request(t, ball, v, age=0):  # the ball in his frame: (-x, y) of the server's; velocity in m/s
        return (
            f"[INFO] [1.0] [CF_9_decision]: request t={t} pass: forward pass to team-mate 10 | me -20.0 3.0 | "
            f"ball {ball[0]} {ball[1]} v {v[0]} {v[1]} age {age} | claims 9:0 | passes  | (exec Player pass)"
        )

    (logs / "CF_9_rcss_player.log").write_text(
        "\n".join(
            [
                request(2, (-7.5, 3.0), (10.0, 5.0)),  # truth: (-8, 3), (1.0, 0.5) m/cycle: 0.5 m off, velocity exact
                request(3, (-7.0, 3.0), (11.0, 5.0)),  # velocity 0.1 m/cycle off
                request(4, (-6.0, 3.0), (10.0, 5.0), age=2),  # remembered: not counted
                request(6, (-4.0, 3.0), (0.0, 0.0)),  # a still ball: not counted
            ]
        )
        + "\n"
    )
    found = belief_errors(tmp_path)
    assert [(round(e.distance, 1), round(e.position, 2), round(e.velocity, 2)) for e in found] == [
        (12.5, 0.5, 0.0),
        (13.0, 0.0, 0.1),
    ]
    rows = belief_table(found)
    assert rows[2].startswith("| 10-20 m | 2 | 0.25 | 0.050 |")


def test_the_believed_offside_line_and_where_a_forward_sent_to_it_stood_are_set_against_the_truth(tmp_path):
    """CF plays on the right (its frame turns x round): PYRUS's second-last man stands at server
    x = -20, so their line is at 20 in CF's frame, then -25 (25). CF's 9, sent to the line, believed
    it at 19 and stood 3 m short, then believed 25.5 and stood 0.5 m beyond it (offside); after a
    pause, his request still in force, 1 m short; then he was sent elsewhere. 7, not sent there,
    counts only for the line; a request logged before the line was (no ``line``) or in a pause
    tells no line."""
    lines = ["ULG6", "(team 1 PYRUS CF 0 0)", "(playmode 1 play_on)"]

    def show(t, second_last, nine):
        where = {("l", 1): (-50.0, 0.0), ("l", 2): (second_last, 5.0), ("l", 3): (-5.0, 0.0)}
        where |= {("r", 9): (nine, 10.0), ("r", 7): (10.0, 0.0)}
        return f"(show {t} ((b) 0 0 0 0) {players_at(where, dict.fromkeys(where, 0), goalies=(('l', 1),))})"

    lines += [show(2, -20.0, -17.0), show(3, -25.0, -25.5), "(playmode 4 foul_charge_l)", show(4, -25.0, -25.5)]
    lines += ["(playmode 5 play_on)", show(5, -25.0, -24.0), show(6, -25.0, -20.0)]
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    logs = tmp_path / "logs-CF"
    logs.mkdir()

    def request(number, t, why, line):
        told = f" | line {line}" if line is not None else ""
        return (
            f"[INFO] [1.0] [CF_{number}_decision]: request t={t} moveTo: {why} | me 17.0 -10.0 | "
            f"ball 0.0 0.0 v 0.0 0.0 age 0{told} | claims  | passes  | (exec Player moveTo)"
        )

    on_line = "forward: on their last line"
    (logs / "CF_9_rcss_player.log").write_text(
        "\n".join(
            [
                request(9, 2, on_line, "19.0"),
                request(9, 3, on_line + ", watch the ball", "25.5"),
                request(9, 3, on_line, None),  # logged before the line was
                request(9, 4, on_line, "25.0"),  # a pause: no line counted, but it stays in force
                request(9, 6, "forward: hold position", "25.0"),
                request(7, 2, "midfielder: hold position", "20.0"),
            ]
        )
        + "\n"
    )
    found, short = line_errors(tmp_path)
    assert [(e.believed, e.true) for e in found] == [(19.0, 20.0), (25.5, 25.0), (25.0, 25.0), (20.0, 20.0)]
    assert short == [3.0, -0.5, 1.0]  # cycles 2, 3 and 5
    assert believed_line_table(found, short)[2] == "| 4 | 0.25 | 0.50 | 3 | 1.0 | -0.5 to 3.0 |"


def write_shot(tmp_path: Path, keeper: tuple[float, float], aim_y: float) -> Path:
    """PYRUS 9 shoots from (-35, 0) at 2.5 m/cycle towards (-52.5, aim_y); CF's goalkeeper stands
    still at ``keeper``; the referee calls the goal once the ball is over the line."""
    where = {("l", 1): keeper, ("r", 9): (-35.5, 0.0)}
    kicks_of = {key: 0 for key in where}
    lines = ["ULG6", "(team 1 CF PYRUS 0 0)", "(playmode 1 play_on)"]
    x, y, mode = -35.0, 0.0, "play_on"
    heading = math.atan2(aim_y, -17.5)
    vx, vy = 2.5 * math.cos(heading), 2.5 * math.sin(heading)
    for t in range(1, 14):
        if t == 2:
            kicks_of[("r", 9)] += 1
        if t >= 2:
            x, y, vx, vy = x + vx, y + vy, vx * reach.BALL_DECAY, vy * reach.BALL_DECAY
        if x < -52.5 and mode == "play_on":
            mode = "goal_r"
            lines.append(f"(playmode {t} goal_r)")
        lines.append(f"(show {t} ((b) {x} {y} 0 0) {players_at(where, kicks_of, goalies=(('l', 1),))})")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    return tmp_path


def test_the_keeper_tool_tells_a_shot_he_could_reach_from_one_nobody_could(tmp_path):
    """A shot into the corner with our goalkeeper 6 m across the goal is not his to reach (a goal),
    though it is from his guard spot on the line to the ball; one straight at him is his."""
    (far := tmp_path / "far").mkdir()
    (near := tmp_path / "near").mkdir()
    wide = shots(write_shot(far, (-51.0, -6.0), 6.0))
    assert len(wide) == 1 and wide[0].goal and not wide[0].reached and not wide[0].late and wide[0].from_spot
    assert wide[0].off_spot > 5.0
    straight = shots(write_shot(near, (-50.0, 0.0), 0.0))
    assert len(straight) == 1 and straight[0].reached and straight[0].late and straight[0].from_spot
    assert "| far | 1 | 1 | 0 | 0 | 1 |" in row("far", wide) and HEADER.startswith("| match |")
    assert row("none", []) == "| none | 0 | 0 | - | - | - | - |"


def test_the_keeper_tool_tells_a_shot_he_had_only_by_setting_off_at_once(tmp_path):
    """Our goalkeeper at (-50, 1.5), facing up the field: a shot from (-35, 0) into the goal 5 m to
    the other side of the middle is his if he sets off as it is struck (moved as rcssserver moves
    him), not a cycle later; 6.5 m across, not even at once."""
    (near := tmp_path / "near").mkdir()
    (far := tmp_path / "far").mkdir()
    (shot,) = shots(write_shot(near, (-50.0, 1.5), -5.0))
    assert shot.reached and not shot.late
    (wide,) = shots(write_shot(far, (-50.0, 3.0), -6.0))
    assert not wide.reached


# A child that, sent SIGTERM, writes which signal it got (its clean-up) and leaves.
CLEANS_UP = textwrap.dedent(
    """
    import pathlib, signal, sys, time
    def clean_up(signum, _frame):
        pathlib.Path(sys.argv[1]).write_text(str(signum))
        sys.exit(0)
    signal.signal(signal.SIGTERM, clean_up)
    pathlib.Path(sys.argv[2]).write_text("up")
    time.sleep(120)
    """
)


def test_a_series_stopped_by_sigterm_passes_it_to_the_match_and_waits_for_its_clean_up(tmp_path):
    """rcss_series runs each match (and rcss_match its network namespace) through run_passing_on: a
    SIGTERM to the series reaches the match, which stops the server and both teams before the series
    ends. (subprocess.run sent the match SIGKILL: its server and the opponent's players ran on.)"""
    child, cleaned, up = tmp_path / "child.py", tmp_path / "cleaned", tmp_path / "up"
    child.write_text(CLEANS_UP)
    parent = tmp_path / "parent.py"
    tools = Path(__file__).resolve().parents[1] / "tools"
    parent.write_text(
        f"import sys\nsys.path.insert(0, {str(tools)!r})\nfrom proctree import run_passing_on\n"
        f"run_passing_on([sys.executable, {str(child)!r}, {str(cleaned)!r}, {str(up)!r}])\n"
    )
    series = subprocess.Popen([sys.executable, str(parent)])
    deadline = time.monotonic() + 60
    while not up.exists():
        assert series.poll() is None and time.monotonic() < deadline, "the child never came up"
        time.sleep(0.05)
    series.send_signal(signal.SIGTERM)
    assert series.wait(timeout=60) == 128 + signal.SIGTERM
    assert cleaned.read_text() == str(int(signal.SIGTERM))  # the child cleaned up before the parent left


def test_a_match_past_its_time_gets_sigterm_to_clean_up_before_the_series_goes_on(tmp_path):
    child, cleaned, up = tmp_path / "child.py", tmp_path / "cleaned", tmp_path / "up"
    child.write_text(CLEANS_UP)
    with pytest.raises(subprocess.TimeoutExpired):
        run_passing_on([sys.executable, str(child), str(cleaned), str(up)], timeout=10.0)
    assert cleaned.read_text() == str(int(signal.SIGTERM))
    done = run_passing_on([sys.executable, "-c", "print('ok')"], stdout=subprocess.PIPE, text=True)
    assert (done.returncode, done.stdout) == (0, "ok\n")


def drill_frames() -> list:
    """Two kick-off tries as a drill's game log holds them (the trainer's before_kick_off is not logged).

    Everyone stands at the ball. Try 1 (given at game time 1): CF 10 kicks off at 2, CF 9 kicks at
    x 28.5 and again at 30 (24 and 22.5 m from their goal: two shots), PYRUS 3 kicks at 33, CF 9 wins
    it back at 36 (a third shot); goal_l at 40. Try 2 (given at 40, the clock standing still there;
    it begins at 41): CF 10 kicks off at 42, PYRUS 3 takes it at 45 at x 4; goal_r at 60.
    """
    kicks = {("l", 9): 0, ("l", 10): 0, ("r", 3): 0}
    frames, ball = [], 0.0
    touches = {2: ("l", 10), 20: ("l", 9), 30: ("l", 9), 33: ("r", 3), 36: ("l", 9), 42: ("l", 10), 45: ("r", 3)}
    for t in range(1, 61):
        mode = "kick_off_l" if t in (1, 41) else "goal_l" if t == 40 else "goal_r" if t == 60 else "play_on"
        if t in touches:
            kicks[touches[t]] += 1
        ball = 0.0 if t in (1, 41) else min(30.0, ball + 1.5) if t < 41 else min(5.0, ball + 1.0)
        if t == 40:
            frames.append((40, "play_on", (ball, 0.0), [(s, n, ball, 0.0, k) for (s, n), k in kicks.items()]))
        frames.append((t, mode, (ball, 0.0), [(s, n, ball, 0.0, k) for (s, n), k in kicks.items()]))
    return frames


def test_a_drill_is_cut_into_its_tries_by_the_set_pieces_the_trainer_gave():
    tries = tries_of(drill_frames(), "l", "kick_off", [1, 40])
    assert tries == [
        Try(start=1, taken=True, furthest=30.0, kept=31, shots=3, won_there=1, goals_for=1, goals_against=0),
        Try(start=41, taken=True, furthest=4.0, kept=3, shots=0, won_there=0, goals_for=0, goals_against=1),
    ]
    text = drill_table(tries, "our kick-off")
    assert "| 1:1 | 1 | 3 | 1 | 0 | 17.0 m | 17 | 1 |" in text and "2 tries taken of 2" in text
    # Seen from the other side, the same log has no kick-off of "ours".
    assert tries_of(drill_frames(), "r", "kick_off", [1, 40]) == []


def test_a_try_ends_when_the_ball_is_given_to_them_and_an_offence_names_the_offender():
    """We are the left side: their free kick or an offence of ours ends a try; their foul does not."""
    for mode in ("free_kick_r", "kick_in_r", "goal_kick_r", "offside_l", "foul_charge_l", "back_pass_l"):
        assert ended_for_them(mode), mode
    for mode in ("free_kick_l", "kick_in_l", "goal_r", "goal_l", "foul_charge_r", "offside_r", "play_on"):
        assert not ended_for_them(mode), mode


def replay_game_log(where: Path) -> Path:
    """CF plays on the right (attacking -x). Its 9 kicks in play at 5 (ball at x -20: our frame 20),
    6 (too soon after), 50 (x -30: 30) and 80 (x +10: our half); PYRUS 3 kicks at 20; a kick at a
    kick-in (60) does not count."""
    kicks = {("l", 3): 0, ("r", 9): 0}
    touches = {5: ("r", 9), 6: ("r", 9), 20: ("l", 3), 50: ("r", 9), 60: ("r", 9), 80: ("r", 9)}
    ball_x = {4: -20.0, 5: -20.0, 49: -30.0, 59: -30.0, 79: 10.0}
    lines = ["ULG6", "(team 1 PYRUS CF 0 0)", "(playmode 1 play_on)"]
    for t in range(1, 90):
        if t == 59:
            lines.append(f"(playmode {t} kick_in_r)")
        if t == 61:
            lines.append(f"(playmode {t} play_on)")
        if t in touches:
            kicks[touches[t]] += 1
        x = ball_x.get(t, 0.0)
        players = (
            f"((l 3) 0 0x1 {x - 2} 4 0.5 0 170 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) (c {kicks[('l', 3)]} 0 0 0 0 0 0 0 0 0 0)) "
            f"((r 9) 0 0x1 {x + 0.5} -3 -0.4 0.2 -170 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) (c {kicks[('r', 9)]} 0 0 0 0 0 0 0 0 0 0))"
        )
        lines.append(f"(show {t} ((b) {x} -2.5 -1 0.25) {players})")
    rcg = where / "m.rcg"
    rcg.write_text("\n".join(lines) + "\n")
    return rcg


def test_a_replay_drill_takes_the_moments_before_our_kicks_in_the_zone_and_places_everyone_as_then(tmp_path):
    """The kicks of ``replay_game_log``. Everyone is placed as at the time before each kick, turned
    round so that CF is the left side, as in a drill."""
    rcg = replay_game_log(tmp_path)
    found = situations(rcg, "CF", (0.0, 52.5))
    assert [s.source for s in found] == ["m.rcg@4", "m.rcg@49"]
    first = found[0]
    assert (first.ball.x, first.ball.y, first.ball.vx, first.ball.vy) == (20.0, 2.5, 1.0, -0.25)
    mine, his = first.ours[9], first.theirs[3]
    assert (mine.x, mine.y, mine.vx, mine.vy, mine.body) == (19.5, 3.0, 0.4, -0.2, 10.0)
    assert (his.x, his.y, his.body) == (22.0, -4.0, -10.0)
    assert situations(rcg, "CF", (0.0, 25.0)) == [first]
    theirs = situations(rcg, "PYRUS", (-52.5, 52.5))  # the left side's: as the game log has it
    assert [(s.source, s.ours[3].x, s.ours[3].body) for s in theirs] == [("m.rcg@19", -2.0, 170.0)]
    assert placement(first, "CF", "PYRUS", moving=False) == [
        "(move (player CF 9) 19.5 3 10 0 0)",
        "(move (player PYRUS 3) 22 -4 -10 0 0)",
        "(move (ball) 20 2.5 0 0 0)",
    ]
    assert placement(first, "CF", "PYRUS", moving=True)[-1] == "(move (ball) 20 2.5 0 1 -0.25)"
    assert spread([1, 2, 3, 4], 2) == [1, 3] and spread([1, 2], 3) == [1, 2, 1] and HOLD > 0


def test_a_replay_drill_lists_how_many_moments_each_game_log_holds_without_a_server(tmp_path):
    """``--list``: the moments per match directory and in all, then stop (no --server given)."""
    one, two, empty = tmp_path / "match-1", tmp_path / "match-2", tmp_path / "match-3"
    for d in (one, two, empty):
        d.mkdir()
    replay_game_log(one)
    replay_game_log(two)
    (empty / "e.rcg").write_text("ULG6\n(team 1 PYRUS CF 0 0)\n(playmode 1 play_on)\n")
    tool = Path(__file__).resolve().parents[1] / "tools" / "rcss_drill.py"
    args = ["--drill", "replay", "--from", str(one), str(two), str(empty), "--list", "--server", ""]
    done = subprocess.run([sys.executable, str(tool), *args, "--zone", "25", "52.5"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        f"{one}: 1",
        f"{two}: 1",
        f"{empty}: 0",
        "2 moments with the ball at x 25..52.5 in 3 game logs, 2 with any",
    ]
    done = subprocess.run([sys.executable, str(tool), *args, "--zone", "0", "52.5"], capture_output=True, text=True)
    assert done.stdout.splitlines()[-1] == "4 moments with the ball at x 0..52.5 in 3 game logs, 2 with any"
    kick_off = subprocess.run([sys.executable, str(tool), "--list", "--server", ""], capture_output=True, text=True)
    assert kick_off.returncode == 2 and "--drill replay" in kick_off.stderr  # nothing to count: said, not ignored


def test_each_shot_of_ours_tells_its_touches_speed_aim_where_it_crosses_and_what_came_of_it(tmp_path):
    """CF plays on the right (its frame turns x round; y as the server's). 9 chooses a shot at
    t=2, touches the ball at t=3 and shoots at t=4 from (35, 2) in CF's frame at 3.0 m/cycle, 2
    degrees left of his aim: a goal. 10 chooses one at t=20, but PYRUS 3 kicks first: never kicked.
    10 chooses another at t=30 and shoots at t=31 from (40, 0) at 2.0 m/cycle into their keeper's
    hands: PYRUS gets a free kick with its goalkeeper at the ball."""
    decay = reach.BALL_DECAY
    where = {("l", 1): (-51.0, 0.0), ("l", 3): (-20.0, 10.0), ("r", 9): (-34.5, 2.0), ("r", 10): (-39.5, 0.0)}
    kicks_of = dict.fromkeys(where, 0)
    lines = ["ULG6", "(team 1 PYRUS CF 0 0)", "(playmode 1 play_on)"]
    aim = math.atan2(-6.2 - 2.0, 53.5 - 35.0)
    way = aim + math.radians(2.0)
    ball = {1: (-34.8, 2.0, 0.0, 0.0), 2: (-34.8, 2.0, 0.0, 0.0), 3: (-35.0, 2.0, 0.0, 0.0)}
    x, y = -35.0, 2.0
    vx, vy = -3.0 * math.cos(way), 3.0 * math.sin(way)  # the server's frame: x turned round
    for t in range(4, 12):
        x, y = x + vx, y + vy
        vx, vy = vx * decay, vy * decay
        ball[t] = (x, y, vx, vy)
    ball |= {t: (-30.0, 5.0, 0.0, 0.0) for t in range(12, 31)}
    ball |= {30: (-40.0, 0.0, 0.0, 0.0), 31: (-42.0, 0.0, -2.0 * decay, 0.0), 32: (-43.88, 0.0, 0.0, 0.0)}
    touches = {3: ("r", 9), 4: ("r", 9), 21: ("l", 3), 31: ("r", 10)}
    for t in range(1, 36):
        if t in touches:
            kicks_of[touches[t]] += 1
        if t == 8:
            lines.append("(playmode 8 goal_r)")
        if t == 12:
            lines.append("(playmode 12 play_on)")
        if t == 33:
            lines.append("(playmode 33 free_kick_l)")
            where[("l", 1)] = (-44.5, 0.5)
        bx, by, bvx, bvy = ball.get(t, ball[32])
        lines.append(f"(show {t} ((b) {bx} {by} {bvx} {bvy}) {players_at(where, kicks_of, goalies=(('l', 1),))})")
    (tmp_path / "m.rcg").write_text("\n".join(lines) + "\n")
    logs = tmp_path / "logs-CF"
    logs.mkdir()
    choice = "[INFO] [1.0] [CF_{}_decision]: t={} shoot: {} @ target 53.5 {} ball 35.0 2.0 opp 50.0 0.0 0.5\n"
    (logs / "CF_9_rcss_player.log").write_text(choice.format(9, 2, "a hopeful shot (the ball comes: 1 cycles)", -6.2))
    (logs / "CF_10_rcss_player.log").write_text(
        choice.format(10, 20, "a free shot", 3.1) + choice.format(10, 30, "a free shot", 0.0)
    )
    found, missed = our_shots(tmp_path)
    assert missed == 1
    goal, caught = found
    assert (goal.time, goal.number, goal.why, goal.touches, goal.outcome) == (4, 9, "a hopeful shot", 1, "goal")
    assert goal.distance == pytest.approx(math.hypot(17.5, 2.0))
    assert goal.speed == pytest.approx(3.0) and goal.off == pytest.approx(2.0)
    assert goal.cross == pytest.approx(2.0 + math.tan(way) * 17.5)
    assert (caught.number, caught.touches, caught.outcome) == (10, 0, "keeper")
    assert caught.speed == pytest.approx(2.0) and caught.cross == pytest.approx(0.0)
    seen = math.degrees(math.atan2(7.01 - 2.0, 17.5) + math.atan2(7.01 + 2.0, 17.5))  # between the posts
    assert goal.seen == pytest.approx(seen, abs=0.05) and caught.seen > seen  # (nearer, in the middle)
    rows = shots_table(found, missed)
    assert rows[-2].startswith("\n2 shots (1 choices never kicked): 1 goals, 2 on a way between the posts")
    assert rows[-1] == (
        f"by distance: within 16 m: 1 shots, 0 goals (goal seen {caught.seen:.0f} degrees, median); "
        f"16-20 m: 1 shots, 1 goals (goal seen {seen:.0f} degrees, median)"
    )


def _drill_out(path: Path, furthest: list[float]) -> Path:
    tries = [
        {
            "start": 100 * i,
            "taken": True,
            "furthest": f,
            "kept": 30,
            "shots": int(f > 40.0),
            "won_there": 0,
            "goals_for": 0,
            "goals_against": 0,
        }
        for i, f in enumerate(furthest)
    ]
    path.mkdir()
    (path / "drill.json").write_text(json.dumps({"drill": "kick-off", "tries": tries}))
    return path


def test_two_codes_drills_are_set_side_by_side_with_what_chance_alone_gives(tmp_path, capsys):
    low = _drill_out(tmp_path / "low", [10.0] * 25 + [20.0] * 5)  # 5 of 30 into their third
    high = _drill_out(tmp_path / "high", [10.0] * 5 + [20.0] * 24 + [45.0])  # 25 of 30, one shot
    again = _drill_out(tmp_path / "again", [10.0] * 25 + [20.0] * 5)
    assert compare_main(["--a", str(low), "--b", str(high), "--resamples", "2000"]) == 0
    rows = {
        r.split("|")[1].strip(): [c.strip() for c in r.split("|")[2:-1]]
        for r in capsys.readouterr().out.splitlines()
        if r.startswith("| ")
    }
    a, b, diff, interval, p = rows["into their third"]
    assert (a, b, diff) == ("17%", "83%", "+67%") and float(p) < 0.01
    lo, hi = (float(x.rstrip("%")) for x in interval.split(" .. "))
    assert 0 < lo < 67 < hi
    assert rows["with a shot"][:2] == ["0%", "3%"]
    # The same tries on both sides: no difference, and chance gives as much every time.
    assert compare_main(["--a", str(low), "--b", str(again), "--resamples", "500"]) == 0
    same = next(r for r in capsys.readouterr().out.splitlines() if r.startswith("| into their third"))
    assert same.split("|")[4].strip() == "+0%" and same.split("|")[6].strip() == "1.00"
    # A series is not set beside a drill, and a directory with neither is refused.
    series = tmp_path / "series"
    series.mkdir()
    (series / "series.json").write_text(
        json.dumps([{"score": [0, 3], "shots": [1, 30], "possession": [0.3, 0.7], "attacking": [0.02, 0.3]}])
    )
    assert compare_main(["--a", str(low), "--b", str(series)]) == 2
    assert compare_main(["--a", str(tmp_path), "--b", str(series)]) == 2
    assert compare_main(["--a", str(series), "--b", str(series), "--resamples", "100"]) == 0
    out = capsys.readouterr().out
    assert "| goals against | 3.00 | 3.00 | +0.00 |" in out and "offsides" not in out  # (not written then)
    match = {"score": [1, 3], "shots": [2, 30], "possession": [0.3, 0.7], "attacking": [0.02, 0.3], "offsides": [2, 0]}
    (series / "series.json").write_text(json.dumps([match, match]))
    assert compare_main(["--a", str(series), "--b", str(series), "--resamples", "100"]) == 0
    assert "| our offsides | 2.0 | 2.0 | +0.0 |" in capsys.readouterr().out
