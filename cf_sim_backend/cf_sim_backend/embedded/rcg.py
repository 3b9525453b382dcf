"""The embedded simulator's match log as an rcssserver game log (``.rcg``, version 6). ROS-free.

rcssmonitor and soccerwindow2 replay ``.rcg`` files, so a match of the embedded simulator can be
watched in the tools RoboCup teams already use:

    python -m cf_sim_backend.embedded.rcg match.jsonl match.rcg

The format is what rcssserver 19 writes (``ULG6``; a recorded sample is in the tests): a header
line, ``server_param``, ``player_param`` and ``player_type`` lines, then ``playmode`` and ``team``
lines when they change and one ``show`` line per cycle. rcssserver's frame is ours with the y
axis (and so every angle) mirrored: its y grows towards the bottom of the monitor.
"""

from __future__ import annotations

import sys
from pathlib import Path

from cf_sim_backend.embedded.report import read_log
from cf_sim_backend.player_types import hetero_types
from cf_sim_backend.world import COUNTED, Params

# Every play mode rcssserver 19 names (its PLAYMODE_STRINGS), in order.
RCSS_PLAYMODES = (  # noqa: SIM905 - fifty names read better as text
    "before_kick_off time_over play_on kick_off_l kick_off_r kick_in_l kick_in_r free_kick_l free_kick_r "
    "corner_kick_l corner_kick_r goal_kick_l goal_kick_r goal_l goal_r drop_ball offside_l offside_r "
    "penalty_kick_l penalty_kick_r first_half_over pause human_judge foul_charge_l foul_charge_r foul_push_l "
    "foul_push_r foul_multiple_attack_l foul_multiple_attack_r foul_ballout_l foul_ballout_r back_pass_l "
    "back_pass_r free_kick_fault_l free_kick_fault_r catch_fault_l catch_fault_r indirect_free_kick_l "
    "indirect_free_kick_r penalty_setup_l penalty_setup_r penalty_ready_l penalty_ready_r penalty_taken_l "
    "penalty_taken_r penalty_miss_l penalty_miss_r penalty_score_l penalty_score_r illegal_defense_l "
    "illegal_defense_r"
).split()
_OUR_MODES = {"half_time": "first_half_over"}  # the only name of ours rcssserver does not have

STAND, GOALIE = 0x1, 0x8  # rcssserver's player state bits
STAMINA_MAX = 8000


def _num(value: float) -> str:
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def server_param(field: dict, cycle_seconds: float) -> str:
    """The parameters a monitor reads (field and object sizes, timing); the rest keep its defaults."""
    params = {
        "goal_width": field.get("goal_width", 14.02),
        "ball_size": 0.085,
        "player_size": 0.3,
        "kickable_margin": 0.7,
        "catchable_area_l": 1.2,
        "catchable_area_w": 1,
        "stamina_max": STAMINA_MAX,
        "simulator_step": round(cycle_seconds * 1000),
        "visible_angle": 90,
    }
    return "(server_param " + "".join(f"({k} {_num(v)})" for k, v in params.items()) + ")"


def player_param(types: int = 1, seed: int = -1) -> str:
    return f"(player_param (player_types {types})(pt_max 1)(random_seed {seed})(subs_max 3))"


# A type's parameters in the order rcssserver 19 writes them (foul_detect_probability is fixed).
TYPE_FIELDS = (
    "player_speed_max",
    "stamina_inc_max",
    "player_decay",
    "inertia_moment",
    "dash_power_rate",
    "player_size",
    "kickable_margin",
    "kick_rand",
    "extra_stamina",
    "effort_max",
    "effort_min",
    "kick_power_rate",
)


def player_type(type_id: int = 0, params: Params | None = None) -> str:
    """A ``player_type`` line, its numbers to six significant digits as rcssserver writes them."""
    params = params or Params()
    values = {name: getattr(params, name) for name in TYPE_FIELDS}
    values["foul_detect_probability"] = 0.5
    values["catchable_area_l_stretch"] = params.catchable_area_l_stretch
    text = "".join(f"({k} {v:.6g})" for k, v in values.items())
    return f"(player_type (id {type_id}){text})"


def rcss_mode(mode: str) -> str:
    """Our play mode as rcssserver names it."""
    return _OUR_MODES.get(mode, mode)


def show(cycle: dict) -> str:
    """One cycle as a ``show`` line: the ball, then every player (rcssserver's frame)."""
    bx, by, bvx, bvy = cycle["ball"]
    parts = [f"(show {cycle['t']} ((b) {_num(bx)} {_num(-by)} {_num(bvx)} {_num(-bvy)})"]
    counts = cycle.get("counts", {})  # (logs written before the counters have none)
    for row in sorted(cycle["players"], key=lambda p: (p[0], p[1])):
        side, number, x, y, vx, vy, body, neck, stamina, goalie, *ptype = row  # (older logs: no type)
        state = STAND | (GOALIE if goalie else 0)
        c = " ".join(str(n) for n in counts.get(f"{side}{number}", [0] * len(COUNTED)))
        parts.append(
            f" (({side} {number}) {ptype[0] if ptype else 0} {state:#x} {_num(x)} {_num(-y)} {_num(vx)} {_num(-vy)} {_num(-body)} {_num(-neck)}"
            f" (v h 90) (fp 0 0) (s {_num(stamina)} 1 1 130600) (c {c}))"
        )
    return "".join(parts) + ")"


def export(log_path: Path, out: Path) -> Path:
    """Write the match log at ``log_path`` as a version 6 game log at ``out``."""
    header, cycles, _ = read_log(log_path)
    teams = header.get("teams", {"l": "left", "r": "right"})
    seed, count = cycles[0].get("types", (-1, 1)) if cycles else (-1, 1)
    types = hetero_types(seed, count) if count > 1 else (Params(),)
    lines = [
        "ULG6",
        server_param(header.get("field", {}), header.get("cycle_seconds", 0.1)),
        player_param(count, seed),
        *(player_type(type_id, params) for type_id, params in enumerate(types)),
    ]
    mode = team = None
    last_t = None
    for cycle in cycles:
        t = cycle["t"]
        if cycle["mode"] != mode:
            mode = cycle["mode"]
            lines.append(f"(playmode {t} {rcss_mode(mode)})")
        score = tuple(cycle["score"])
        if score != team:
            team = score
            names = (teams.get("l", "left"), teams.get("r", "right"))
            lines.append(f"(team {t} {names[0]} {names[1]} {score[0]} {score[1]})")
        if t != last_t:  # time stands still before a kick-off: one show per cycle of the game clock
            last_t = t
            lines.append(show(cycle))
    out.write_text("\n".join(lines) + "\n", encoding="ascii")
    return out


if __name__ == "__main__":
    source = Path(sys.argv[1])
    print(export(source, Path(sys.argv[2]) if len(sys.argv) > 2 else source.with_suffix(".rcg")))
