#pragma once
/// A Cyclone DDS domain participant whose writers and readers carry serialised samples: the
/// bridge hands in XCDR1 bytes (with the encapsulation header) made by msgs/serialize.h and takes
/// out the bytes other participants sent. Topics are typed by descriptors compiled from
/// idl/*.idl, so Cyclone checks every sample against the ROS 2 type before it goes out and
/// drops received samples that do not fit it. Cyclone's types stay in dds_participant.cpp.

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "bridges/ros2/ros2_conventions.h"

namespace rescuesim::ros2 {

class DdsParticipant {
 public:
  /// Joins `domain` with `user_data` in the participant's USER_DATA QoS. Throws Error saying
  /// why when Cyclone refuses (bad domain id, bad CYCLONEDDS_URI, no usable network interface).
  DdsParticipant(int domain, const std::string& user_data);
  ~DdsParticipant();
  DdsParticipant(const DdsParticipant&) = delete;
  DdsParticipant& operator=(const DdsParticipant&) = delete;

  /// True when idl/ has a descriptor for the DDS type name ("sensor_msgs::msg::dds_::LaserScan_").
  static bool knows_type(const std::string& dds_type);

  /// A writer on DDS topic `topic`; returns its index. Throws Error for unknown types and DDS failures.
  int create_writer(const std::string& topic, const std::string& dds_type, const EndpointQos& qos);
  /// The writer of rmw_dds_common ParticipantEntitiesInfo on ros_discovery_info, with Gids of `gid_bytes`.
  int create_discovery_writer(std::size_t gid_bytes);
  /// A reader on DDS topic `topic`; returns its index. Wakes wait() when data arrives.
  int create_reader(const std::string& topic, const std::string& dds_type, const EndpointQos& qos);

  /// Publishes one serialised sample. False, with `error` set, when Cyclone refuses it (bytes that
  /// do not fit the topic's type, a writer timing out on a full reliable history).
  bool write(int writer, std::span<const std::uint8_t> cdr, std::string* error);
  /// Takes every sample waiting on reader `reader`, in arrival order, calling `f` with its bytes.
  void take(int reader, const std::function<void(std::span<const std::uint8_t>)>& f);
  /// Blocks until a reader has data, wake() is called, or `timeout` passes.
  void wait(std::chrono::milliseconds timeout);
  /// Ends a wait() in progress (or the next one) early; callable from any thread.
  void wake();

  Guid participant_guid() const;
  Guid writer_guid(int writer) const;
  Guid reader_guid(int reader) const;
  /// Readers currently matched with writer `writer`, for diagnostics.
  int matched_readers(int writer) const;
  /// Writers currently matched with reader `reader`.
  int matched_writers(int reader) const;

 private:
  struct Endpoint {
    std::int32_t topic;
    std::int32_t entity;
  };
  std::int32_t participant_ = 0;
  std::int32_t waitset_ = 0;
  std::int32_t guard_ = 0;
  std::vector<Endpoint> writers_, readers_;

  std::int32_t make_topic(const std::string& topic, const std::string& dds_type, std::size_t gid_bytes = 0);
};

}  // namespace rescuesim::ros2
