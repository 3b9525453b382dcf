"""Our whole team on a running rcssserver (full ROS 2: `ros2 launch cf_sim_backend rcss_team.launch.py team:=CF`).

rcssserver gives shirt numbers in the order players connect, so the team is started by the
``rcss_team`` executable, which connects the 11 ``rcss_player`` adapters one after another
(number 1 as goalkeeper), then starts the 11 unchanged ``cf_decision`` components, with the
ComMAg in front. Ctrl-C stops all of them. Arguments: team, host, port, players, lease, log_dir,
talk (``say``: within a competition's rules, docs/rcssserver.md).
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

ARGS = {
    "team": ("CommonFramework", "team name on the server"),
    "host": ("127.0.0.1", "the server's host"),
    "port": ("6000", "the server's player port"),
    "players": ("11", "how many players (1..11)"),
    "lease": ("3.0", "lease (s) of every component"),
    "log_dir": ("", "one log file per process (empty: a new temp dir)"),
    "talk": ("say", "say: team-mates talk only through the server's say and hear (the rules); or framework"),
}


def generate_launch_description() -> LaunchDescription:
    arguments = []
    for name in ARGS:
        arguments += [f"--{name.replace('_', '-')}", LaunchConfiguration(name)]
    return LaunchDescription(
        [
            *(DeclareLaunchArgument(n, default_value=d, description=text) for n, (d, text) in ARGS.items()),
            Node(
                package="cf_sim_backend",
                executable="rcss_team",
                arguments=arguments,
                output="screen",
                sigterm_timeout="10",  # it stops its own processes first
            ),
        ]
    )
