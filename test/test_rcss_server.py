"""Our unchanged team on a real rcssserver (synch mode): runs when RCSSSERVER names the server's binary.

rcssserver is built from source next to the project (docs/rcssserver.md) and is in no package
registry, so CI has none and these tests are skipped there, with that reason. They drive
tools/rcss_match.py: the server, the ComMAg, 11 rcss_player adapters and 11 cf_decision components
(optionally a second instance of our team as the opponent), all in a private network namespace.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from cf_sim_backend.player_types import choose_types

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
from rcss_series import kick_off_types, newest_game_log, read_rcg

SERVER = os.environ.get("RCSSSERVER", "")
MATCH = Path(__file__).resolve().parents[1] / "tools" / "rcss_match.py"

pytestmark = pytest.mark.skipif(
    not SERVER or not os.access(SERVER, os.X_OK),
    reason="RCSSSERVER does not name an rcssserver binary (it is built from source: docs/rcssserver.md)",
)


def play(tmp_path: Path, *args: str) -> dict:
    argv = [sys.executable, str(MATCH), "--server", SERVER, "--out", str(tmp_path / "match"), *args]
    done = subprocess.run(argv, capture_output=True, text=True, timeout=1500)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_a_short_synch_match_ends_cleanly_and_our_players_kick_the_ball(tmp_path):
    summary = play(tmp_path, "--players", "11", "--cycles", "300")
    assert summary["team_exit_codes"] == [0] and summary["server_exit_code"] == 0
    players = summary["players"]
    assert sorted(p["number"] for p in players) == list(range(1, 12))
    for p in players:
        assert p["mode"] == "time_over" and p["cycles"] >= 295, p
        assert p["bad_messages"] == 0 and not [e for e in p["server_errors"] if "illegal" in e], p
        assert p["body_commands"] > 0, p
    assert sum(p["kicks"] for p in players) > 0  # kicks that reached the ball, counted by the server


def test_two_instances_of_our_team_play_each_other_each_with_its_coach(tmp_path):
    # (talking over the framework, the other way than the default's)
    argv = (
        "--players",
        "5",
        "--opponents",
        "5",
        "--cycles",
        "200",
        "--seed",
        "42",
        "--game-log",
        "--talk",
        "framework",
    )
    summary = play(tmp_path, *argv)
    assert summary["team_exit_codes"] == [0, 0] and summary["server_exit_code"] == 0
    sides = {p["team"]: p["side"] for p in summary["players"]}
    assert sides == {"CF": "l", "CFB": "r"}
    for team in ("CF", "CFB"):
        kicks = sum(p["kicks"] for p in summary["players"] if p["team"] == team)
        assert kicks > 0, f"{team} never reached the ball"
    # Each team's coach chose its players' types before the referee's kick-off: what the server's
    # game log shows them playing as, and what each adapter believes it is, is the coach's choice.
    types, played = kick_off_types(next((tmp_path / "match").glob("*.rcg")))
    assert len(types) == 18
    wanted = choose_types(list(types.values()), [1, 2, 3, 4, 5])
    for p in summary["players"]:
        assert played[(p["side"], p["number"])] == wanted[p["number"]] == p["player_type"], p
        # ... and the top speed its WorldState tells is that type's; it knows its team-mates' types.
        assert p["top_speed"] == pytest.approx(types[wanted[p["number"]]].speed * 10, abs=0.001), p
        assert {n: p["mate_types"].get(str(n), 0) for n in wanted} == wanted, p


def test_team_mates_hear_each_others_passes_through_the_servers_say(tmp_path):
    """The default talk is the rules' (--talk say): a pass is said through the server, and the
    team-mates' decisions await it, as their request logs show (``passes P>R@T``)."""
    summary = play(tmp_path, "--players", "11", "--cycles", "400", "--log-requests")
    assert summary["team_exit_codes"] == [0] and summary["server_exit_code"] == 0
    heard = set()
    for log in (tmp_path / "match" / "logs-CF").glob("CF_*_rcss_player.log"):
        me = int(log.name.split("_")[1])
        for line in log.read_text(errors="replace").splitlines():
            if "request t=" in line and " | passes " in line:
                passes = line.split(" | passes ", 1)[1].split(" | ", 1)[0].split()
                heard |= {(me, int(p.split(">")[0])) for p in passes if int(p.split(">")[0]) != me}
    assert heard, "no decision ever awaited a team-mate's pass"
    for p in summary["players"]:
        assert not [e for e in p["server_errors"] if "say" in e or "illegal" in e], p


def test_a_killed_adapter_is_relaunched_and_takes_its_player_over_mid_match(tmp_path):
    summary = play(tmp_path, "--players", "5", "--cycles", "300", "--kill", "3@100")
    assert summary["killed"]["pid"] is not None and summary["killed"]["cycle"] >= 100
    assert summary["team_exit_codes"] == [0] and summary["server_exit_code"] == 0
    assert summary["relaunched"] == 1 and summary["withdrawn"] == 0
    # The stats of the relaunched process: back at the first stoppage after its relaunch (the server
    # reconnects players only outside play_on), it played on to the end.
    three = next(p for p in summary["players"] if p["number"] == 3)
    assert three["mode"] == "time_over" and three["cycles"] >= 20 and three["body_commands"] > 0
    assert all(p["mode"] == "time_over" for p in summary["players"])


DRILL = Path(__file__).resolve().parents[1] / "tools" / "rcss_drill.py"


def test_a_drill_sets_our_free_kick_up_again_and_again_and_counts_each_try(tmp_path):
    out = tmp_path / "drill"
    argv = [sys.executable, str(DRILL), "--server", SERVER, "--out", str(out), "--players", "3"]
    argv += ["--drill", "free-kick", "--at", "20", "10", "--tries", "3", "--window", "20"]
    done = subprocess.run(argv, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "3 tries taken of 3" in done.stdout, done.stdout
    result = json.loads((out / "drill.json").read_text())
    assert len(result["starts"]) == 3 and result["team_exit_codes"] == [0]
    # Each try began where the trainer put the ball (ours is the left side: x up the field).
    assert all(t["taken"] and t["furthest"] >= 20.0 for t in result["tries"]), result["tries"]


def test_a_replay_drill_puts_everyone_where_an_earlier_game_log_had_them_and_plays_on(tmp_path):
    """A crafted game log: CF 2 kicks at (25, -10) with CFB's two men near; each try begins there."""
    old = tmp_path / "old"
    old.mkdir()
    at = {
        ("l", 1): (-45.0, 0.0),
        ("l", 2): (24.5, -10.0),
        ("l", 3): (10.0, 5.0),
        ("r", 1): (48.0, 0.0),
        ("r", 2): (30.0, -8.0),
    }
    lines = ["ULG6", "(team 1 CF CFB 0 0)", "(playmode 1 play_on)"]
    for t in range(1, 8):
        players = " ".join(
            f"(({side} {n}) 0 0x1 {x} {y} 0 0 0 0 (v h 120) (fp 0 0) (s 8000 1 1 130600) (c {int(t >= 5 and (side, n) == ('l', 2))} 0 0 0 0 0 0 0 0 0 0))"
            for (side, n), (x, y) in at.items()
        )
        lines.append(f"(show {t} ((b) 25 -10 0 0) {players})")
    (old / "m.rcg").write_text("\n".join(lines) + "\n")
    out = tmp_path / "drill"
    argv = [sys.executable, str(DRILL), "--server", SERVER, "--out", str(out), "--players", "3", "--opponents", "2"]
    argv += ["--opponent", "CFB", "--drill", "replay", "--from", str(old), "--tries", "2", "--window", "20"]
    done = subprocess.run(argv, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "replay of 1 situations" in done.stdout, done.stdout
    result = json.loads((out / "drill.json").read_text())
    assert result["situations"] == ["m.rcg@4", "m.rcg@4"] and len(result["starts"]) == 2
    frames = {f[0]: f for f in read_rcg(newest_game_log(out)) if f[1] == "play_on"}
    for start in result["starts"]:
        _, _, ball, players = frames[start]  # the last step held: everyone within a step of his place
        assert abs(ball[0] - 25.0) < 1.5 and abs(ball[1] + 10.0) < 1.5, (start, ball)
        for side, n, x, y, _ in players:
            assert abs(x - at[(side, n)][0]) < 1.5 and abs(y - at[(side, n)][1]) < 1.5, (start, side, n, x, y)
