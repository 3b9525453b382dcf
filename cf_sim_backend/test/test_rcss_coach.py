"""The coach's choice of heterogeneous player types (pure): the real server's types, read as it sends them."""

from __future__ import annotations

import socket
import threading

import pytest

from cf_sim_backend.player_types import ORDER, PlayerType, choose_types
from cf_sim_backend.rcss.coach import player_type, run
from cf_sim_backend.rcss.protocol import parse

# Three of the types rcssserver 19 sent in a recorded match (shared rcss traces), as sent.
TYPE_0 = (
    "(player_type (id 0)(player_speed_max 1.05)(stamina_inc_max 45)(player_decay 0.4)(inertia_moment 5)"
    "(dash_power_rate 0.006)(player_size 0.3)(kickable_margin 0.7)(kick_rand 0.1)(extra_stamina 50)"
    "(effort_max 1)(effort_min 0.6)(kick_power_rate 0.027)(foul_detect_probability 0.5)"
    "(catchable_area_l_stretch 1))"
)
TYPE_4 = (
    "(player_type (id 4)(player_speed_max 1.05)(stamina_inc_max 51.6732)(player_decay 0.373568)"
    "(inertia_moment 4.33921)(dash_power_rate 0.0048878)(player_size 0.3)(kickable_margin 0.679198)"
    "(kick_rand 0.0791982)(extra_stamina 52.8109)(effort_max 0.988757)(effort_min 0.588757))"
)
TYPE_7 = (
    "(player_type (id 7)(player_speed_max 1.05)(stamina_inc_max 46.0382)(player_decay 0.4656)"
    "(inertia_moment 6.64)(dash_power_rate 0.00582696)(player_size 0.3)(kickable_margin 0.7017)"
    "(kick_rand 0.1017)(extra_stamina 61.162)(effort_max 0.955352)(effort_min 0.555352))"
)


def read(text: str) -> PlayerType:
    return player_type(parse(text))


def make(type_id: int, speed: float, stamina: float = 45.0) -> PlayerType:
    return PlayerType(type_id, speed, stamina)


def test_a_types_top_speed_is_what_full_dashes_reach():
    assert read(TYPE_0).speed == pytest.approx(1.0)  # 100 * 0.006 * 1 / (1 - 0.4)
    assert read(TYPE_4).speed == pytest.approx(0.7718, abs=1e-3)  # a slow type: 0.77 m/cycle
    assert read(TYPE_7).speed == pytest.approx(1.0418, abs=1e-3)
    fast = TYPE_7.replace("(dash_power_rate 0.00582696)", "(dash_power_rate 0.0070)")
    assert read(fast).speed == pytest.approx(1.05)  # capped at player_speed_max


def test_goalkeeper_keeps_the_default_type_and_the_spine_gets_the_fastest():
    types = [make(0, 1.0), make(1, 0.84), make(2, 1.03), make(3, 0.90), make(4, 1.04), make(5, 0.75)]
    chosen = choose_types(types, list(range(1, 12)))
    assert chosen[1] == 0
    assert chosen[ORDER[0]] == 4 and chosen[ORDER[1]] == 2 and chosen[ORDER[2]] == 3 and chosen[ORDER[3]] == 1
    assert chosen[ORDER[4]] == 5  # the slowest go last
    assert len(chosen) == 6, "each type once (pt_max 1): the other players keep what the referee gives them"
    assert sorted(chosen.values()) == [0, 1, 2, 3, 4, 5]


def test_of_two_as_fast_the_type_that_recovers_more_stamina_and_pt_max_is_honoured():
    types = [make(0, 1.0), make(1, 0.95, 40.0), make(2, 0.95, 50.0)]
    assert choose_types(types, [1, 10, 3])[10] == 2
    twice = choose_types(types, [1, 10, 3, 4, 9], pt_max=2)
    assert list(twice.values()).count(2) == 2 and twice[1] == 0 and twice[9] == 1


def test_a_small_team_and_numbers_outside_the_order():
    types = [make(t, 1.0 - t / 100) for t in range(18)]
    assert choose_types(types, [1, 2]) == {1: 0, 2: 1}
    assert choose_types(types, [2, 12], goalie=1) == {2: 0, 12: 1}  # no goalkeeper: the default type is free


def test_the_coach_talks_to_a_server_over_udp_and_bad_datagrams_lose_nothing():
    """The test plays the server's side of the online coach's conversation, in rcssserver's own words,
    on a real UDP socket, with garbage and a stranger's datagram in between; the real server is in
    test/test_rcss_server.py."""
    server = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    server.bind(("127.0.0.1", 0))
    server.settimeout(5.0)
    stranger = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    stranger.bind(("127.0.0.2", 0))
    heard: list[str] = []

    def serve():
        def say(text, to):
            server.sendto(text.encode() + b"\0", to)

        data, peer = server.recvfrom(4096)
        heard.append(data.rstrip(b"\0").decode())
        stranger.sendto(b"(init r ok)\0", peer)  # another host on the network: not the server
        for junk in ("(((", "42", "(player_type (id x))", "\xff"):
            say(junk, peer)
        say("(init l ok)", peer)
        say("(player_param (subs_max 3)(pt_max 1)(allow_mult_default_type 0))", peer)
        stranger.sendto(b"(player_param (pt_max 5))\0", peer)  # taken, the fastest type would go to all
        for i in range(18):  # type i is faster the higher i is, but type 17's dash rate is bad
            rate = "oops" if i == 17 else f"{0.0045 + 0.0001 * i:.4f}"
            say(
                TYPE_0.replace("(id 0)", f"(id {i})").replace("(dash_power_rate 0.006)", f"(dash_power_rate {rate})"),
                peer,
            )
        while True:
            data, peer = server.recvfrom(4096)
            text = data.rstrip(b"\0").decode()
            heard.append(text)
            if text == "(bye)":
                return
            _, number, type_id = text.strip("()").split()
            say(f"(ok change_player_type {number} {type_id})" if number != "3" else "(warning no_subs_left)", peer)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    chosen, answers = run("CF", "127.0.0.1", server.getsockname()[1], players=3, timeout=3.0)
    thread.join(5.0)
    server.close()
    stranger.close()
    assert heard[0] == "(init CF (version 19))" and heard[-1] == "(bye)"
    assert chosen == {1: 0, 3: 16, 2: 15}  # 17 was unreadable; 3 (a centre back) before 2
    assert answers == {1: "ok", 3: "no_subs_left", 2: "ok"}
