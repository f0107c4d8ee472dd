#include "msgs/messages.h"

namespace rescuesim::msg {

namespace {
template <class T>
struct Name;
#define RS_MSG_NAME(T, N) \
  template <>             \
  struct Name<T> {        \
    static constexpr const char* value = N; \
  };
RS_MSG_NAME(Clock, "rosgraph_msgs/Clock")
RS_MSG_NAME(LaserScan, "sensor_msgs/LaserScan")
RS_MSG_NAME(Range, "sensor_msgs/Range")
RS_MSG_NAME(Imu, "sensor_msgs/Imu")
RS_MSG_NAME(Twist, "geometry_msgs/Twist")
RS_MSG_NAME(Odometry, "nav_msgs/Odometry")
RS_MSG_NAME(JointState, "sensor_msgs/JointState")
RS_MSG_NAME(TFMessage, "tf2_msgs/TFMessage")
RS_MSG_NAME(PoseStamped, "geometry_msgs/PoseStamped")
RS_MSG_NAME(Path, "nav_msgs/Path")
RS_MSG_NAME(OccupancyGrid, "nav_msgs/OccupancyGrid")
RS_MSG_NAME(Float64MultiArray, "std_msgs/Float64MultiArray")
RS_MSG_NAME(Contacts, "rescuesim_msgs/Contacts")
RS_MSG_NAME(Image, "sensor_msgs/Image")
RS_MSG_NAME(CameraInfo, "sensor_msgs/CameraInfo")
RS_MSG_NAME(PointCloud2, "sensor_msgs/PointCloud2")
RS_MSG_NAME(String, "std_msgs/String")
RS_MSG_NAME(Bool, "std_msgs/Bool")
#undef RS_MSG_NAME
}  // namespace

template <class T>
const char* type_name_of() {
  return Name<T>::value;
}

const char* type_name(const Message& m) {
  return std::visit([](const auto& x) { return Name<std::decay_t<decltype(x)>>::value; }, m);
}

SimTime stamp_of(const Message& m) {
  return std::visit(
      [](const auto& x) -> SimTime {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, Clock>) {
          return x.clock;
        } else if constexpr (requires { x.header.stamp; }) {
          return x.header.stamp;
        } else if constexpr (std::is_same_v<T, TFMessage>) {
          return x.transforms.empty() ? SimTime{} : x.transforms.front().header.stamp;
        } else {
          return SimTime{};
        }
      },
      m);
}

#define RS_INSTANTIATE(T) template const char* type_name_of<T>();
RS_INSTANTIATE(Clock)
RS_INSTANTIATE(LaserScan)
RS_INSTANTIATE(Range)
RS_INSTANTIATE(Imu)
RS_INSTANTIATE(Twist)
RS_INSTANTIATE(Odometry)
RS_INSTANTIATE(JointState)
RS_INSTANTIATE(TFMessage)
RS_INSTANTIATE(PoseStamped)
RS_INSTANTIATE(Path)
RS_INSTANTIATE(OccupancyGrid)
RS_INSTANTIATE(Float64MultiArray)
RS_INSTANTIATE(Contacts)
RS_INSTANTIATE(Image)
RS_INSTANTIATE(CameraInfo)
RS_INSTANTIATE(PointCloud2)
RS_INSTANTIATE(String)
RS_INSTANTIATE(Bool)
#undef RS_INSTANTIATE

}  // namespace rescuesim::msg
