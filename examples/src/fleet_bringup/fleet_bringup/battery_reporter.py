"""Publish a low-battery warning when the charge drops below a threshold."""
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import BatteryState
from std_msgs.msg import Bool


class BatteryReporter(Node):
    def __init__(self):
        super().__init__("battery_reporter")
        self.threshold = self.declare_parameter("low_threshold", 0.2).value
        self.low_pub = self.create_publisher(Bool, "battery/low", 10)
        self.create_subscription(BatteryState, "battery/state", self.on_state, 10)

    def on_state(self, state):
        self.low_pub.publish(Bool(data=state.percentage < self.threshold))


def main(args=None):
    rclpy.init(args=args)
    rclpy.spin(BatteryReporter())
    rclpy.shutdown()


if __name__ == "__main__":
    main()
