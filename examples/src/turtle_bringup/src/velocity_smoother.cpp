// Smooths teleop commands before they reach the TurtleBot's base.
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

class VelocitySmoother
{
public:
  explicit VelocitySmoother(ros::NodeHandle& nh) : private_nh_("~")
  {
    private_nh_.param("max_accel", max_accel_, 0.5);
    command_sub_ = nh.subscribe("cmd_vel", 10, &VelocitySmoother::commandCallback, this);
    // Every robot of the fleet ends up driving the same base.
    base_pub_ = nh.advertise<geometry_msgs::Twist>("/mobile_base/commands/velocity", 10);
  }

private:
  void commandCallback(const geometry_msgs::Twist::ConstPtr& command)
  {
    geometry_msgs::Twist smoothed = *command;
    smoothed.linear.x = std::min(command->linear.x, last_.linear.x + max_accel_);
    last_ = smoothed;
    base_pub_.publish(smoothed);
  }

  ros::NodeHandle private_nh_;
  ros::Subscriber command_sub_;
  ros::Publisher base_pub_;
  geometry_msgs::Twist last_;
  double max_accel_ = 0.5;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocity_smoother");
  ros::NodeHandle nh;
  VelocitySmoother smoother(nh);
  ros::spin();
  return 0;
}
