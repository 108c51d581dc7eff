// Publishes where each robot of the fleet is, for the fleet dashboard.
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include <geometry_msgs/msg/pose_stamped.hpp>
#include <nav_msgs/msg/odometry.hpp>
#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/set_bool.hpp>

using namespace std::chrono_literals;
using std::placeholders::_1;

class FleetMonitor : public rclcpp::Node
{
public:
  explicit FleetMonitor(const rclcpp::NodeOptions& options) : Node("fleet_monitor", options)
  {
    map_frame_ = declare_parameter<std::string>("map_frame", "map");
    const auto odom_topic = declare_parameter<std::string>("odom_topic", "odom");
    pose_pub_ = create_publisher<geometry_msgs::msg::PoseStamped>("robot_pose", 10);
    odom_sub_ = create_subscription<nav_msgs::msg::Odometry>(
      odom_topic, 10, std::bind(&FleetMonitor::odomCallback, this, _1));
    enable_service_ = create_service<std_srvs::srv::SetBool>(
      "enable_reporting", std::bind(&FleetMonitor::enable, this, _1, std::placeholders::_2));
  }

private:
  void odomCallback(const nav_msgs::msg::Odometry::SharedPtr odom)
  {
    if (!enabled_)
    {
      return;
    }
    geometry_msgs::msg::PoseStamped pose;
    pose.header.stamp = odom->header.stamp;
    pose.header.frame_id = map_frame_;
    pose.pose = odom->pose.pose;
    pose_pub_->publish(pose);
  }

  void enable(const std::shared_ptr<std_srvs::srv::SetBool::Request> request,
              std::shared_ptr<std_srvs::srv::SetBool::Response> response)
  {
    enabled_ = request->data;
    response->success = true;
  }

  std::string map_frame_;
  bool enabled_ = true;
  rclcpp::Publisher<geometry_msgs::msg::PoseStamped>::SharedPtr pose_pub_;
  rclcpp::Subscription<nav_msgs::msg::Odometry>::SharedPtr odom_sub_;
  rclcpp::Service<std_srvs::srv::SetBool>::SharedPtr enable_service_;
};

int main(int argc, char** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<FleetMonitor>(rclcpp::NodeOptions()));
  rclcpp::shutdown();
  return 0;
}
