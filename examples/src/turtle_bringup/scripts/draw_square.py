#!/usr/bin/env python
"""Drive turtle1 along a square, changing the pen colour at every corner."""
import rospy
from geometry_msgs.msg import Twist
from turtlesim.srv import SetPen, TeleportAbsolute

# Built when the module loads, before init_node: rospy then resolves a service name
# without the node's remappings, so a <remap> in the launch file is silently ignored.
teleport = rospy.ServiceProxy('turtle1/teleport_absolute', TeleportAbsolute)


def drive(cmd_pub, linear, angular, seconds):
    twist = Twist()
    twist.linear.x = linear
    twist.angular.z = angular
    end = rospy.Time.now() + rospy.Duration(seconds)
    rate = rospy.Rate(20)
    while rospy.Time.now() < end and not rospy.is_shutdown():
        cmd_pub.publish(twist)
        rate.sleep()


def main():
    rospy.init_node('draw_square')
    side = rospy.get_param('~side', 2.0)
    cmd_pub = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
    rospy.wait_for_service('turtle1/set_pen')
    set_pen = rospy.ServiceProxy('turtle1/set_pen', TeleportAbsolute)
    teleport(5.5, 5.5, 0.0)
    for corner in range(4):
        set_pen(50 * corner, 100, 200, 3, 0)
        drive(cmd_pub, side, 0.0, 1.0)
        drive(cmd_pub, 0.0, 1.5708, 1.0)


if __name__ == '__main__':
    main()
