// Warns when the TurtleBot's battery runs low.
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>

// Built before main() runs: roscpp aborts before anything is printed.
ros::NodeHandle nh;
ros::Publisher low_battery_pub;

void batteryCallback(const sensor_msgs::BatteryState::ConstPtr& state)
{
  if (state->percentage < 0.2)
  {
    low_battery_pub.publish(*state);
  }
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "battery_monitor");
  low_battery_pub = nh.advertise<sensor_msgs::BatteryState>("battery/low", 1, true);
  ros::Subscriber battery_sub = nh.subscribe("battery_state", 10, batteryCallback);
  ros::spin();
  return 0;
}
