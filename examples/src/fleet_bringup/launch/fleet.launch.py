"""Bring up one robot of the fleet: its nodes in the robot's namespace."""
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node, PushRosNamespace
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    robot = LaunchConfiguration("robot")
    remappings = [("/tf", "tf"), ("/tf_static", "tf_static")]
    follower_params = PathJoinSubstitution(
        [FindPackageShare("fleet_bringup"), "config", "waypoint_follower.yaml"]
    )
    return LaunchDescription([
        DeclareLaunchArgument("robot", default_value="robot2"),
        GroupAction([
            PushRosNamespace(robot),
            Node(
                package="fleet_bringup",
                executable="waypoint_follower",
                name="waypoint_follower",
                parameters=[follower_params, {"map_frame": "map"}],
                remappings=remappings,
            ),
            Node(
                package="fleet_bringup",
                executable="battery_reporter",
                name="batteryReporter",
                parameters=[{"low_treshold": 0.15}],
            ),
        ]),
    ])
