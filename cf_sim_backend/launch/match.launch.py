"""A whole match on the embedded simulator, as `make demo` plays it (full ROS 2: `ros2 launch cf_sim_backend match.launch.py`).

Starts the ComMAg (respawned if it dies), the gateway, both teams' perception, action and decision
components, then the simulator. Parameters are the demo's. ``layout`` chooses the processes:
``team`` (default: one component container per team, the ``players`` executable), ``player``
(a container per player) or ``process`` (each component its own process, started one after
another so that the ones already running keep their leases on a small machine).

Arguments: players (per side, default 11), layout (team), half_cycles (600), cycle_period
(0.1 s = real time), seed (0), lease (2.0 s), stagger (0.6 s between process starts),
gateway_port (7700), match_log (empty: none). Ctrl-C stops everything (components deregister first).
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction, TimerAction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

TEAMS = {"l": "blue", "r": "red"}
ROLES = {"perception": "cf_sim_backend", "action": "cf_sim_backend", "decision": "cf_decision"}


def _arg(context, name: str) -> str:
    return LaunchConfiguration(name).perform(context)


def _containers(players: int, lease: float, stagger: float, per_player: bool) -> tuple[list, float]:
    actions, delay = [], 2.0  # the ComMAg first
    for side, team in TEAMS.items():
        groups = [[n] for n in range(1, players + 1)] if per_player else [list(range(1, players + 1))]
        for numbers in groups:
            name = f"{team}_{numbers[0]}_players" if per_player else f"{team}_players"
            params = {"side": side, "team": team, "team_size": players, "numbers": numbers, "lease": lease}
            node = Node(package="cf_sim_backend", executable="players", name=name, parameters=[params], output="log")
            actions.append(TimerAction(period=delay, actions=[node]))
            delay += stagger * (2 if per_player else 1)
    return actions, delay


def _match(context):
    players = int(_arg(context, "players"))
    lease = float(_arg(context, "lease"))
    stagger = float(_arg(context, "stagger"))
    layout = _arg(context, "layout")
    if layout not in ("team", "player", "process"):
        raise ValueError(f"layout must be team, player or process, not {layout!r}")
    if layout != "process":
        actions, delay = _containers(players, lease, stagger, per_player=layout == "player")
    else:
        actions, delay = _components(players, lease, stagger)
    actions.append(TimerAction(period=delay + 3.0, actions=[_simulator(context, players)]))
    return actions


def _components(players: int, lease: float, stagger: float) -> tuple[list, float]:
    actions, delay = [], 2.0  # the ComMAg first
    for side, team in TEAMS.items():
        for number in range(1, players + 1):
            for role, package in ROLES.items():
                params = {"team": team, "number": number, "lease": lease}
                if role == "decision":
                    params["team_size"] = players
                else:
                    params["side"] = side
                node = Node(
                    package=package,
                    executable=role,
                    name=f"{team}_{number}_{role}",
                    parameters=[params],
                    output="log",
                )
                actions.append(TimerAction(period=delay, actions=[node]))
                delay += stagger
    return actions, delay


def _simulator(context, players: int) -> Node:
    return Node(
        package="cf_sim_backend",
        executable="sim",
        name="sim",
        parameters=[
            {
                "left_size": players,
                "right_size": players,
                "half_cycles": int(_arg(context, "half_cycles")),
                "cycle_period": float(_arg(context, "cycle_period")),
                "auto_kick_off_cycles": 30,
                "seed": int(_arg(context, "seed")),
                "match_log": _arg(context, "match_log"),
            }
        ],
        output="screen",
    )


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription(
        [
            DeclareLaunchArgument("players", default_value="11", description="players per side"),
            DeclareLaunchArgument("layout", default_value="team", description="team, player or process"),
            DeclareLaunchArgument("half_cycles", default_value="600", description="cycles per half"),
            DeclareLaunchArgument("cycle_period", default_value="0.1", description="seconds per cycle"),
            DeclareLaunchArgument("seed", default_value="0", description="the simulator's random seed"),
            DeclareLaunchArgument("lease", default_value="2.0", description="every component's lease (s)"),
            DeclareLaunchArgument("stagger", default_value="0.6", description="seconds between component starts"),
            DeclareLaunchArgument("gateway_port", default_value="7700", description="TCP port of the gateway"),
            DeclareLaunchArgument("match_log", default_value="", description="match log path (JSON lines)"),
            Node(
                package="cf_commag",
                executable="commag",
                name="commag",
                parameters=[{"backoff_initial": 0.3, "startup_grace": 15.0}],
                respawn=True,  # it keeps its registrations across a restart
                respawn_delay=1.0,
                output="screen",
            ),
            Node(
                package="cf_commag",
                executable="gateway",
                name="gateway",
                parameters=[{"port": LaunchConfiguration("gateway_port")}],
                output="screen",
            ),
            OpaqueFunction(function=_match),
        ]
    )
