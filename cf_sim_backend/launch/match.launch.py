"""A whole match on the embedded simulator, as `make demo` plays it (full ROS 2: `ros2 launch cf_sim_backend match.launch.py`).

Starts the ComMAg (respawned if it dies), the gateway, both teams' perception, action and decision
components (one process each, started one after another so that the ones already running keep
their leases on a small machine), then the simulator. Parameters are the demo's.

Arguments: players (per side, default 3), half_cycles (600), cycle_period (0.1 s = real time),
seed (0), lease (2.0 s), stagger (0.6 s between component starts), gateway_port (7700),
match_log (empty: none). Ctrl-C stops everything (components deregister first).
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction, TimerAction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

TEAMS = {"l": "blue", "r": "red"}
ROLES = {"perception": "cf_sim_backend", "action": "cf_sim_backend", "decision": "cf_decision"}


def _arg(context, name: str) -> str:
    return LaunchConfiguration(name).perform(context)


def _match(context):
    players = int(_arg(context, "players"))
    lease = float(_arg(context, "lease"))
    stagger = float(_arg(context, "stagger"))
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
    simulator = Node(
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
    actions.append(TimerAction(period=delay + 3.0, actions=[simulator]))
    return actions


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription(
        [
            DeclareLaunchArgument("players", default_value="3", description="players per side"),
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
