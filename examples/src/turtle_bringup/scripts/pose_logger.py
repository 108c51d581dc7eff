#!/usr/bin/env python
"""Log where turtle1 is, once a second."""
import rospy
from turtlesim.msg import Pose


class PoseLogger(object):
    def __init__(self):
        self.last = None
        rospy.Subscriber('turtle1/pose', Pose, self.on_pose, queue_size=1)
        rospy.Timer(rospy.Duration(1.0), self.report)

    def on_pose(self, pose):
        self.last = pose

    def report(self, _event):
        if self.last is not None:
            rospy.loginfo('turtle1 at (%.2f, %.2f)', self.last.x, self.last.y)


if __name__ == '__main__':
    rospy.init_node('pose_logger')
    PoseLogger()
    rospy.spin()
