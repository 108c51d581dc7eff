"""Send each robot of the fleet to its next waypoint."""
import rclpy
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import NavigateToPose
from rclpy.action import ActionClient
from rclpy.node import Node

WAYPOINTS = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]


class WaypointFollower(Node):
    def __init__(self):
        super().__init__("waypoint_follower")
        self.declare_parameter("map_frame", "map")
        self.navigate = ActionClient(self, NavigateToPose, "navigate_to_pose")
        self.goal_pub = self.create_publisher(PoseStamped, "current_goal", 10)

    def send(self, x, y):
        goal = NavigateToPose.Goal()
        goal.pose.header.frame_id = self.get_parameter("map_frame").value
        goal.pose.pose.position.x = x
        goal.pose.pose.position.y = y
        self.goal_pub.publish(goal.pose)
        return self.navigate.send_goal_async(goal)


def main(args=None):
    follower = WaypointFollower()
    rclpy.init(args=args)
    for x, y in WAYPOINTS:
        rclpy.spin_until_future_complete(follower, follower.send(x, y))
    follower.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
