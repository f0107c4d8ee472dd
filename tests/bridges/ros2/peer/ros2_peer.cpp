// ros2_peer: a DDS participant built on eProsima Fast DDS (the middleware of rmw_fastrtps, ROS 2's
// default), standing in for an independent ROS 2 node in rescuesim's ROS 2 interop tests. It
// knows nothing of rescuesim: its types come from its own IDL (ros2_peer_types.idl) and it speaks
// only the ROS 2 conventions (rt/ topics, pkg::msg::dds_::Type_ names, ros_discovery_info).
//
//   ros2_peer --domain N [--mode drive|bad] [--timeout SECONDS]
//
// drive: reads /scan, /odom, /camera/color/image_raw, /clock and ros_discovery_info, then
//        publishes /cmd_vel linear.x = 0.3 for 2 s and measures how far /odom moved; joins
//        /tf_static late (transient local) to see that it was kept for late joiners.
// bad:   publishes a NaN Twist, a Twist-named sample with 8 stray bytes and a head command of
//        the wrong length for 1.5 s, and measures how far /odom moved (it should not).
// Fast DDS is configured from FASTRTPS_DEFAULT_PROFILES_FILE. The report is one JSON line on
// stdout; the exit code is 0 when the run got far enough to report, 1 otherwise.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "ros2_peer_types.h"
#include "ros2_peer_typesPubSubTypes.h"

namespace fdds = eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(const builtin_interfaces::msg::dds_::Time_& t) { return t.sec() + 1e-9 * t.nanosec(); }

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "\"";
}

/// One participant with helpers to make typed readers and writers.
class Participant {
 public:
  explicit Participant(int domain) {
    participant_ = fdds::DomainParticipantFactory::get_instance()->create_participant(domain, fdds::PARTICIPANT_QOS_DEFAULT);
    if (participant_ == nullptr) {
      std::fprintf(stderr, "ros2_peer: cannot create a Fast DDS participant on domain %d\n", domain);
      std::exit(2);
    }
    subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
    publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  }
  ~Participant() {
    participant_->delete_contained_entities();
    fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }

  template <class PubSubType>
  fdds::DataReader* reader(const std::string& topic, fdds::ReliabilityQosPolicyKind reliability, int depth,
                          bool transient_local = false) {
    fdds::DataReaderQos q = fdds::DATAREADER_QOS_DEFAULT;
    q.reliability().kind = reliability;
    q.durability().kind = transient_local ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS : fdds::VOLATILE_DURABILITY_QOS;
    q.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
    q.history().depth = depth;
    return subscriber_->create_datareader(make_topic<PubSubType>(topic), q);
  }

  template <class PubSubType>
  fdds::DataWriter* writer(const std::string& topic, const char* type_name = nullptr) {
    fdds::DataWriterQos q = fdds::DATAWRITER_QOS_DEFAULT;
    q.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
    q.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
    q.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
    q.history().depth = 10;
    return publisher_->create_datawriter(make_topic<PubSubType>(topic, type_name), q);
  }

 private:
  template <class PubSubType>
  fdds::Topic* make_topic(const std::string& name, const char* type_name = nullptr) {
    fdds::TypeSupport type(new PubSubType());
    if (type_name) type->setName(type_name);
    type.register_type(participant_);
    fdds::Topic* t = participant_->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (t == nullptr) {
      std::fprintf(stderr, "ros2_peer: cannot create topic %s\n", name.c_str());
      std::exit(2);
    }
    return t;
  }

  fdds::DomainParticipant* participant_ = nullptr;
  fdds::Subscriber* subscriber_ = nullptr;
  fdds::Publisher* publisher_ = nullptr;
};

/// Takes every waiting sample of `reader` into `sample`, calling `f(sample, info)` for each.
template <class T, class F>
void take_all(fdds::DataReader* reader, F f) {
  T sample;
  fdds::SampleInfo info;
  while (reader->take_next_sample(&sample, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
    if (info.valid_data) f(sample, info);
  }
}

int matched(fdds::DataWriter* w) {
  fdds::PublicationMatchedStatus st;
  w->get_publication_matched_status(st);
  return st.current_count;
}

struct Options {
  int domain = 0;
  std::string mode = "drive";
  double timeout = 20;
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--domain") o.domain = std::atoi(argv[i + 1]);
    else if (k == "--mode") o.mode = argv[i + 1];
    else if (k == "--timeout") o.timeout = std::atof(argv[i + 1]);
  }
  const bool drive = o.mode == "drive";

  Participant p(o.domain);
  using namespace sensor_msgs::msg::dds_;
  auto* scan_r = p.reader<LaserScan_PubSubType>("rt/scan", fdds::BEST_EFFORT_RELIABILITY_QOS, 5);  // like SensorDataQoS
  auto* odom_r = p.reader<nav_msgs::msg::dds_::Odometry_PubSubType>("rt/odom", fdds::RELIABLE_RELIABILITY_QOS, 50);
  auto* image_r = drive ? p.reader<Image_PubSubType>("rt/camera/color/image_raw", fdds::RELIABLE_RELIABILITY_QOS, 2) : nullptr;
  auto* clock_r = p.reader<rosgraph_msgs::msg::dds_::Clock_PubSubType>("rt/clock", fdds::BEST_EFFORT_RELIABILITY_QOS, 1);
  auto* info_r = p.reader<rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_PubSubType>(
      "ros_discovery_info", fdds::RELIABLE_RELIABILITY_QOS, 1, true);
  auto* cmd_w = p.writer<geometry_msgs::msg::dds_::Twist_PubSubType>("rt/cmd_vel");
  fdds::DataWriter* head_w = nullptr;
  fdds::DataWriter* wrong_w = nullptr;
  std::unique_ptr<Participant> rogue;  // a Twist_ of another shape needs a participant of its own
  if (!drive) {
    head_w = p.writer<std_msgs::msg::dds_::Float64MultiArray_PubSubType>("rt/head/command");
    rogue = std::make_unique<Participant>(o.domain);
    wrong_w = rogue->writer<rescuesim_peer::WrongTwistPubSubType>("rt/cmd_vel", "geometry_msgs::msg::dds_::Twist_");
  }

  // what was seen
  struct {
    int count = 0;
    std::size_t ranges = 0;
    std::string frame;
    double angle_min = 0, angle_max = 0, increment = 0;
  } scan;
  struct {
    int count = 0;
    std::string frame, child;
    double t = 0, x = 0, y = 0, vx = 0;
    double cruise_time = 0, cruise_dx = 0;  ///< while driving, between samples both at >= 0.25 m/s
  } odom;
  bool driving = false;
  struct {
    int count = 0;
    unsigned width = 0, height = 0, step = 0;
    std::size_t bytes = 0;
    std::string encoding, frame;
  } image;
  struct {
    int count = 0;
    bool increasing = true;
    double first = -1, last = -1;
  } clock;
  std::set<std::string> nodes;
  int node_writers = 0, node_readers = 0;
  bool gid_is_writer_participant = false, gid_padding_zero = true, scan_writer_listed = false;
  std::vector<std::array<unsigned char, 16>> listed_writers;

  auto poll = [&] {
    take_all<LaserScan_>(scan_r, [&](const LaserScan_& m, const fdds::SampleInfo&) {
      ++scan.count;
      scan.ranges = m.ranges().size();
      scan.frame = m.header().frame_id();
      scan.angle_min = m.angle_min(), scan.angle_max = m.angle_max(), scan.increment = m.angle_increment();
    });
    take_all<nav_msgs::msg::dds_::Odometry_>(odom_r, [&](const nav_msgs::msg::dds_::Odometry_& m, const fdds::SampleInfo&) {
      const double t = seconds(m.header().stamp()), x = m.pose().pose().position().x(), vx = m.twist().twist().linear().x();
      if (driving && odom.count > 0 && odom.vx >= 0.25 && vx >= 0.25 && t > odom.t) {
        odom.cruise_time += t - odom.t;
        odom.cruise_dx += x - odom.x;
      }
      ++odom.count;
      odom.frame = m.header().frame_id();
      odom.child = m.child_frame_id();
      odom.t = seconds(m.header().stamp());
      odom.x = m.pose().pose().position().x();
      odom.y = m.pose().pose().position().y();
      odom.vx = m.twist().twist().linear().x();
    });
    if (image_r) {
      take_all<Image_>(image_r, [&](const Image_& m, const fdds::SampleInfo&) {
        ++image.count;
        image.width = m.width(), image.height = m.height(), image.step = m.step();
        image.bytes = m.data().size();
        image.encoding = m.encoding();
        image.frame = m.header().frame_id();
      });
    }
    take_all<rosgraph_msgs::msg::dds_::Clock_>(clock_r, [&](const rosgraph_msgs::msg::dds_::Clock_& m, const fdds::SampleInfo&) {
      const double t = seconds(m.clock());
      if (clock.count > 0 && t <= clock.last) clock.increasing = false;
      if (clock.count == 0) clock.first = t;
      clock.last = t;
      ++clock.count;
    });
    using rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_;
    take_all<ParticipantEntitiesInfo_>(info_r, [&](const ParticipantEntitiesInfo_& m, const fdds::SampleInfo& info) {
      // the participant Gid is the GUID of the participant that wrote it, padded with zeros
      const auto& prefix = info.sample_identity.writer_guid().guidPrefix;
      gid_is_writer_participant = std::memcmp(m.gid().data().data(), prefix.value, 12) == 0;
      for (std::size_t i = 16; i < 24; ++i) gid_padding_zero = gid_padding_zero && m.gid().data()[i] == 0;
      for (const auto& n : m.node_entities_info_seq()) {
        const std::string ns = n.node_namespace().c_str();
        nodes.insert(ns + (ns.empty() || ns.back() != '/' ? "/" : "") + n.node_name().c_str());
        node_writers = static_cast<int>(n.writer_gid_seq().size());
        node_readers = static_cast<int>(n.reader_gid_seq().size());
        for (const auto& g : n.writer_gid_seq()) {
          std::array<unsigned char, 16> v{};
          std::memcpy(v.data(), g.data().data(), 16);
          listed_writers.push_back(v);
        }
      }
    });
  };
  auto run_for = [&](double s, auto&& each) {
    const auto end = Clock::now() + std::chrono::duration<double>(s);
    while (Clock::now() < end) {
      poll();
      each();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  };

  // wait for the simulation: its odometry and scans flowing, our command writers matched
  const auto give_up = Clock::now() + std::chrono::duration<double>(o.timeout);
  auto ready = [&] {
    const bool writers = matched(cmd_w) > 0 && (drive || (matched(head_w) > 0 && matched(wrong_w) > 0));
    return odom.count > 0 && scan.count > 0 && writers && !nodes.empty() && (!drive || image.count > 0);
  };
  while (!ready() && Clock::now() < give_up) {
    poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const bool was_ready = ready();
  // /tf_static was published once, at the start: a late, transient-local reader still gets it
  fdds::DataReader* tf_static_r = nullptr;
  if (was_ready && drive) {
    tf_static_r = p.reader<tf2_msgs::msg::dds_::TFMessage_PubSubType>("rt/tf_static", fdds::RELIABLE_RELIABILITY_QOS, 1, true);
  }
  struct {
    int count = 0;
    std::size_t transforms = 0;
    bool laser = false;
  } tf_static;
  const double x0 = odom.x, y0 = odom.y, t0 = odom.t;
  int commands = 0;
  double vx_driving = 0;
  if (was_ready) {
    auto next = Clock::now();
    geometry_msgs::msg::dds_::Twist_ twist;
    if (drive) {
      twist.linear().x(0.3);
    } else {
      twist.linear().x(std::numeric_limits<double>::quiet_NaN());
    }
    rescuesim_peer::WrongTwist wrong;
    wrong.values().fill(0.3);
    std_msgs::msg::dds_::Float64MultiArray_ head;
    head.data({0.1, 0.2});
    driving = true;
    run_for(drive ? 2.0 : 1.5, [&] {
      if (Clock::now() < next) return;
      next += std::chrono::milliseconds(50);
      cmd_w->write(&twist);
      if (!drive) {
        wrong_w->write(&wrong);
        head_w->write(&head);
      }
      ++commands;
    });
    vx_driving = odom.vx;
    driving = false;
  }
  const double x1 = odom.x, y1 = odom.y, t1 = odom.t;
  if (was_ready && drive) {
    geometry_msgs::msg::dds_::Twist_ stop;
    cmd_w->write(&stop);
  }
  run_for(0.5, [] {});
  if (tf_static_r) {
    const auto until = Clock::now() + std::chrono::seconds(3);
    while (tf_static.count == 0 && Clock::now() < until) {
      take_all<tf2_msgs::msg::dds_::TFMessage_>(tf_static_r, [&](const tf2_msgs::msg::dds_::TFMessage_& m, const fdds::SampleInfo&) {
        ++tf_static.count;
        tf_static.transforms = m.transforms().size();
        for (const auto& t : m.transforms()) {
          tf_static.laser = tf_static.laser || (t.header().frame_id() == "base_link" && t.child_frame_id() == "laser");
        }
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  // which writer sent our scans: its GUID should be among the node's writers
  fdds::SubscriptionMatchedStatus sm;
  scan_r->get_subscription_matched_status(sm);
  std::array<unsigned char, 16> scan_writer{};
  std::memcpy(scan_writer.data(), static_cast<const unsigned char*>(sm.last_publication_handle.value), 16);
  for (const auto& w : listed_writers) scan_writer_listed = scan_writer_listed || w == scan_writer;

  std::string node_list;
  for (const auto& n : nodes) {
    if (!node_list.empty()) node_list += ',';
    node_list += json_string(n);
  }
  std::printf("{\"mode\":%s,\"ready\":%s,\"commands\":%d,"
              "\"scan\":{\"count\":%d,\"ranges\":%zu,\"frame\":%s,\"angle_min\":%.6f,\"angle_max\":%.6f,\"angle_increment\":%.8f},"
              "\"odom\":{\"count\":%d,\"frame\":%s,\"child\":%s,\"t0\":%.6f,\"t1\":%.6f,\"dx\":%.6f,\"dy\":%.6f,\"vx_driving\":%.6f,"
              "\"cruise_time\":%.6f,\"cruise_dx\":%.6f},"
              "\"image\":{\"count\":%d,\"width\":%u,\"height\":%u,\"step\":%u,\"bytes\":%zu,\"encoding\":%s,\"frame\":%s},"
              "\"clock\":{\"count\":%d,\"increasing\":%s,\"first\":%.6f,\"last\":%.6f},"
              "\"tf_static\":{\"count\":%d,\"transforms\":%zu,\"laser\":%s},"
              "\"discovery\":{\"nodes\":[%s],\"writers\":%d,\"readers\":%d,\"gid_is_writer_participant\":%s,"
              "\"gid_padding_zero\":%s,\"scan_writer_listed\":%s}}\n",
              json_string(o.mode).c_str(), was_ready ? "true" : "false", commands, scan.count, scan.ranges, json_string(scan.frame).c_str(),
              scan.angle_min, scan.angle_max, scan.increment, odom.count, json_string(odom.frame).c_str(), json_string(odom.child).c_str(),
              t0, t1, x1 - x0, y1 - y0, vx_driving, odom.cruise_time, odom.cruise_dx, image.count, image.width, image.height, image.step,
              image.bytes, json_string(image.encoding).c_str(), json_string(image.frame).c_str(), clock.count,
              clock.increasing ? "true" : "false", clock.first, clock.last, tf_static.count, tf_static.transforms,
              tf_static.laser ? "true" : "false", node_list.c_str(), node_writers, node_readers,
              gid_is_writer_participant ? "true" : "false", gid_padding_zero ? "true" : "false", scan_writer_listed ? "true" : "false");
  std::fflush(stdout);
  return was_ready ? 0 : 1;
}
