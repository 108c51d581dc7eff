// Republishes wheel odometry in the frames the navigation stack expects.
#include <ros/ros.h>
#include <nav_msgs/Odometry.h>

namespace
{
const std::string kOdomFrame = "odom";
constexpr char kBaseFrame[] = "base_footprint";
}  // namespace

class OdomRelay
{
public:
  OdomRelay(ros::NodeHandle& nh, ros::NodeHandle& private_nh)
  {
    private_nh.param<std::string>("odom_topic", odom_topic_, "wheel/odom");
    odom_pub_ = nh.advertise<nav_msgs::Odometry>("odom", 50);
    wheel_sub_ = nh.subscribe(odom_topic_, 50, &OdomRelay::wheelCallback, this);
  }

private:
  void wheelCallback(const nav_msgs::Odometry::ConstPtr& wheel)
  {
    nav_msgs::Odometry odom = *wheel;
    odom.header.frame_id = kOdomFrame;
    odom.child_frame_id = kBaseFrame;
    odom_pub_.publish(odom);
  }

  std::string odom_topic_;
  ros::Publisher odom_pub_;
  ros::Subscriber wheel_sub_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "odom_relay");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  OdomRelay relay(nh, private_nh);
  ros::spin();
  return 0;
}
