"""Start the ComMAg with its default parameters (full ROS 2 installs: `ros2 launch cf_commag commag.launch.py`)."""

from pathlib import Path

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import LifecycleNode


def generate_launch_description() -> LaunchDescription:
    params = Path(get_package_share_directory("cf_commag")) / "config" / "commag.yaml"
    return LaunchDescription(
        [
            DeclareLaunchArgument("params_file", default_value=str(params)),
            LifecycleNode(
                package="cf_commag",
                executable="commag",
                name="commag",
                namespace="",
                parameters=[LaunchConfiguration("params_file")],
                respawn=True,  # it restores its registry: a ComMAg that dies comes back with every registration
                respawn_delay=1.0,
                output="screen",
            ),
        ]
    )
