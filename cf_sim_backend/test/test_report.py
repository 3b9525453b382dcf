"""The match report: built from a real match log, and rendered by headless Chromium when it is installed.

CI installs Chromium (Debian package `chromium`) and sets CF_REQUIRE_CHROMIUM=1, so there the
rendering check fails rather than skips when the browser is missing.
"""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import pytest

from cf_sim_backend.embedded.chaser import chase_commands
from cf_sim_backend.embedded.matchlog import MatchLog
from cf_sim_backend.embedded.report import read_log, scored, write_report
from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.world import Params, Side


def play_logged_match(path: Path, extra_events: dict[int, str] | None = None, types: int = 1) -> Path:
    """A real 3 v 3 match of chasers, logged; ``extra_events`` adds referee events at given cycles;
    ``types``: heterogeneous player types."""
    sim = Simulator(
        Params(half_cycles=300, auto_kick_off_cycles=2),
        team_sizes=(3, 3),
        team_names=("blue", "red"),
        seed=4,
        player_types=types,
    )
    log = MatchLog(path, sim, 0.1)
    while not sim.finished:
        chase_commands(sim, Side.LEFT)
        chase_commands(sim, Side.RIGHT)
        events = sim.step()
        if extra_events and sim.world.time in extra_events:
            events = [*events, extra_events[sim.world.time]]
        log.cycle(sim.snapshot(), events)
    log.close()
    return path


@pytest.fixture
def report(tmp_path: Path) -> Path:
    play_logged_match(tmp_path / "match.jsonl")
    events = [
        {"t": 0.5, "name": "blue_1_action", "kind": "registered", "state": "healthy", "reason": "registered"},
        {"t": 9.0, "name": "blue_1_action", "kind": "suspect", "state": "suspect", "reason": "missed its lease"},
        {"t": 9.1, "name": "blue_1_action", "kind": "relaunching", "state": "relaunching", "reason": "attempt 1"},
        {"t": 10.0, "name": "blue_1_action", "kind": "relaunched", "state": "healthy", "reason": "back"},
    ]
    return write_report(tmp_path / "match.jsonl", events, tmp_path / "report.html")


def test_report_holds_score_pictures_and_timeline(report: Path):
    text = report.read_text()
    assert text.startswith("<!doctype html>")
    assert text.count("<svg") == 3  # ball heat map and path, trajectories, registry timeline
    assert "blue_1_action: suspect" in text and "polyline" in text
    assert "possession" in text and "Goals:" in text


def test_report_goals_equal_the_score_and_goal_kicks_are_no_goals(tmp_path: Path):
    """A goal kick (``goal kick l``, what the referee logs) is a restart, not a goal."""
    # Chasers never send the ball out over a goal line: add two goal kicks.
    play_logged_match(tmp_path / "match.jsonl", {100: "goal kick l", 400: "goal kick r"})
    _, cycles, end = read_log(tmp_path / "match.jsonl")
    goals = scored(cycles)
    assert len(goals) == sum(end["score"]) > 0
    assert [side for _, side in goals].count("l") == end["score"][0]
    text = write_report(tmp_path / "match.jsonl", [], tmp_path / "report.html").read_text()
    listed = text.split("Goals: ")[1].split(".</p>")[0]
    assert listed.count(" at cycle ") == len(goals) and "kick" not in listed, listed
    assert listed.count("blue at cycle") == end["score"][0]
    assert text.count('r="7"') == len(goals)  # one large circle per goal on the ball picture


def _png_colours(png: bytes) -> int:
    """How many distinct pixel values an RGB(A) PNG screenshot holds (to tell a blank page from a picture)."""
    pos, idat, width, height, channels = 8, b"", 0, 0, 4
    while pos < len(png):
        length, kind = struct.unpack(">I4s", png[pos : pos + 8])
        data = png[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            width, height, _, colour = struct.unpack(">IIBB", data[:10])
            channels = 4 if colour == 6 else 3
        elif kind == b"IDAT":
            idat += data
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels + 1
    rows = [raw[r * stride + 1 : (r + 1) * stride] for r in range(0, height, 7)]
    return len({row[i : i + channels] for row in rows for i in range(0, len(row), channels * 5)})


def _chromium(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        if os.environ.get("CF_REQUIRE_CHROMIUM") == "1":
            pytest.fail("chromium is required here (CF_REQUIRE_CHROMIUM=1) but not installed")
        pytest.skip("chromium is not installed (Debian package: chromium)")
    return subprocess.run(
        [
            browser,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            f"--user-data-dir={tmp_path / 'profile'}",
            *args,
        ],
        check=True,
        capture_output=True,
        timeout=120,
    )


def test_report_renders_in_headless_chromium(report: Path, tmp_path: Path):
    shot = tmp_path / "report.png"
    _chromium(tmp_path, "--window-size=1000,1800", f"--screenshot={shot}", report.as_uri())
    assert shot.exists() and _png_colours(shot.read_bytes()) > 20


def test_the_replay_loads_steps_and_plays_in_headless_chromium_without_script_errors(report: Path, tmp_path: Path):
    """The page's own self-test (``#selftest``): step 41 cycles, play at 8x, record what the canvas showed."""
    dom = _chromium(tmp_path, "--virtual-time-budget=6000", "--dump-dom", report.as_uri() + "#selftest").stdout.decode()
    assert "data-replay-errors" not in dom, re.findall(r'data-replay-errors="[^"]*"', dom)
    found = re.search(r'data-replay-selftest="([^"]*)"', dom)
    assert found, "the replay's self-test did not finish"
    result = json.loads(html.unescape(found[1]))
    assert result["afterSteps"] == 41 and result["afterPlay"] > 41  # stepped, then played on by itself
    assert len({result["first"], result["stepped"], result["played"]}) == 3  # each a different picture
    assert result["events"] >= 1  # the registry events up to that cycle are listed beside it


def test_the_replay_carries_every_cycle_and_the_registry_events_on_the_match_clock(report: Path):
    text = report.read_text()
    data = json.loads(re.search(r'<script type="application/json" id="replay-data">(.*?)</script>', text)[1])
    _, cycles, _ = read_log(report.parent / "match.jsonl")
    assert len(data["frames"]) == len(cycles)
    assert [e[:3] for e in data["events"]] == [
        [5, "blue_1_action", "registered"],
        [90, "blue_1_action", "suspect"],
        [91, "blue_1_action", "relaunching"],
        [100, "blue_1_action", "relaunched"],
    ]
