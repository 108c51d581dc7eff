"""Record the pose the fleet monitor publishes, for the shift report."""
import rclpy
from geometry_msgs.msg import PoseStamped
from rclpy.node import Node


class PoseRecorder(Node):
    def __init__(self):
        super().__init__("pose_recorder")
        self.poses = []
        # fleet_monitor publishes "robot_pose": ROS names are case-sensitive.
        self.create_subscription(PoseStamped, "Robot_Pose", self.poses.append, 10)


def main(args=None):
    rclpy.init(args=args)
    rclpy.spin(PoseRecorder())
