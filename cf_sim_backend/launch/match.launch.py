"""A whole match on the embedded simulator (full ROS 2 installs: `ros2 launch cf_sim_backend match.launch.py`).

Starts the ComMAg, the simulator and, for every player of both teams, its perception and action
components. Arguments: players (per side, default 11), cycle_period, seed.
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def _players(context):
    count = int(LaunchConfiguration("players").perform(context))
    nodes = []
    for side in ("l", "r"):
        for number in range(1, count + 1):
            for role in ("perception", "action"):
                nodes.append(
                    Node(
                        package="cf_sim_backend",
                        executable=role,
                        name=f"{role}_{side}{number}",
                        parameters=[{"side": side, "number": number}],
                    )
                )
    return nodes


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription(
        [
            DeclareLaunchArgument("players", default_value="11"),
            DeclareLaunchArgument("cycle_period", default_value="0.1"),
            DeclareLaunchArgument("seed", default_value="0"),
            Node(package="cf_commag", executable="commag", name="commag"),
            Node(
                package="cf_sim_backend",
                executable="sim",
                name="sim",
                parameters=[
                    {
                        "left_size": LaunchConfiguration("players"),
                        "right_size": LaunchConfiguration("players"),
                        "cycle_period": LaunchConfiguration("cycle_period"),
                        "seed": LaunchConfiguration("seed"),
                    }
                ],
            ),
            OpaqueFunction(function=_players),
        ]
    )
