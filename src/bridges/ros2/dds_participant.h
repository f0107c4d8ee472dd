#pragma once
/// A Cyclone DDS domain participant whose writers and readers carry serialised samples: the
/// bridge hands in XCDR1 bytes (with the encapsulation header) made by msgs/serialize.h and takes
/// out the bytes other participants sent. Topics are typed by descriptors compiled from
/// idl/*.idl, so Cyclone checks every sample against the ROS 2 type before it goes out and
/// drops received samples that do not fit it. Raw endpoints (create_raw_writer/reader) take any
/// DDS type name and carry bytes unchecked both ways, for service and action types that have no
/// IDL here: whoever decodes them validates. Cyclone's types stay in dds_participant.cpp.
///
/// Threads: every method may be called from any thread (endpoints may be added while others
/// write and take); one endpoint is written or taken by one thread at a time.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
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

  /// How a reader's data wakes its taker: through wait() (the participant's one waitset, for
  /// the thread that serves every such reader) or only through wait_reader() (a client's reply
  /// reader, which must not wake a loop that never takes from it).
  enum class Wake { participant, own };

  /// A writer on DDS topic `topic`; returns its index. `user_data` goes in the writer's USER_DATA
  /// QoS (none when empty). Throws Error for unknown types and DDS failures.
  int create_writer(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                    const std::string& user_data = {});
  /// The writer of rmw_dds_common ParticipantEntitiesInfo on ros_discovery_info, with Gids of `gid_bytes`.
  int create_discovery_writer(std::size_t gid_bytes);
  /// A reader on DDS topic `topic`; returns its index. Wakes wait() when data arrives.
  int create_reader(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                    const std::string& user_data = {});
  /// A writer of any DDS type `dds_type` (no IDL): write() sends the bytes as they are.
  int create_raw_writer(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                        const std::string& user_data = {});
  /// A reader of any DDS type `dds_type` (no IDL): take() gives the bytes as they arrived,
  /// unchecked, but for Cyclone's own framing.
  int create_raw_reader(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                        const std::string& user_data = {}, Wake wake = Wake::participant);

  /// Deletes a writer or a reader (a robot deleted while running): its index stays taken;
  /// write() on it fails, take() gives nothing and it matches nobody.
  void delete_writer(int writer);
  void delete_reader(int reader);

  /// Publishes one serialised sample. False, with `error` set, when Cyclone refuses it (bytes that
  /// do not fit the topic's type, a writer timing out on a full reliable history).
  bool write(int writer, std::span<const std::uint8_t> cdr, std::string* error);
  /// Takes every sample waiting on reader `reader`, in arrival order, calling `f` with its bytes.
  void take(int reader, const std::function<void(std::span<const std::uint8_t>)>& f);
  /// Where a taken sample came from.
  struct SampleInfo {
    std::uint64_t publication_handle = 0;  ///< the sending writer, for matched_writer_user_data()
    std::int64_t source_timestamp_ns = 0;  ///< the writer's clock (ns since the epoch)
  };
  /// take(), with each sample's SampleInfo.
  void take_with_info(int reader, const std::function<void(std::span<const std::uint8_t>, const SampleInfo&)>& f);
  /// Blocks until a reader of Wake::participant has data, wake() is called, or `timeout` passes.
  void wait(std::chrono::milliseconds timeout);
  /// Ends a wait() in progress (or the next one) early; callable from any thread.
  void wake();
  /// Blocks until reader `reader` (of Wake::own) has data or `timeout` passes; true when it has data.
  bool wait_reader(int reader, std::chrono::milliseconds timeout);

  Guid participant_guid() const;
  Guid writer_guid(int writer) const;
  Guid reader_guid(int reader) const;
  /// The writer's local instance handle (rmw_cyclonedds's request header guid is this number).
  std::uint64_t writer_instance_handle(int writer) const;
  /// Readers currently matched with writer `writer`, for diagnostics.
  int matched_readers(int writer) const;
  /// Writers currently matched with reader `reader`.
  int matched_writers(int reader) const;
  /// GUIDs of the readers matched with `writer`.
  std::vector<Guid> matched_reader_guids(int writer) const;
  /// USER_DATA of every reader matched with `writer` (an empty string for those without).
  std::vector<std::string> matched_reader_user_data(int writer) const;
  /// USER_DATA of every writer matched with `reader`.
  std::vector<std::string> matched_writer_user_data(int reader) const;
  /// USER_DATA of the writer `publication_handle` (SampleInfo) matched with `reader`, or nullopt
  /// when that writer is no longer matched (gone).
  std::optional<std::string> matched_writer_user_data(int reader, std::uint64_t publication_handle) const;

  /// The next number for a client or service id on this participant (1, 2, ...), as rmw_cyclonedds
  /// counts them per context.
  std::uint32_t next_client_service_counter();

 private:
  struct Endpoint {
    std::int32_t topic;
    std::int32_t entity;
    std::int32_t own_waitset = 0;  ///< readers of Wake::own
  };
  std::int32_t participant_ = 0;
  std::int32_t waitset_ = 0;
  std::int32_t guard_ = 0;
  mutable std::mutex mutex_;  ///< guards the endpoint lists and the counter
  std::vector<Endpoint> writers_, readers_;
  std::uint32_t client_service_counter_ = 0;

  std::int32_t make_topic(const std::string& topic, const std::string& dds_type, std::size_t gid_bytes = 0);
  std::int32_t make_raw_topic(const std::string& topic, const std::string& dds_type);
  int add_writer(const std::string& topic, std::int32_t t, const EndpointQos& qos, const std::string& user_data);
  int add_reader(const std::string& topic, std::int32_t t, const EndpointQos& qos, const std::string& user_data, Wake wake);
  Endpoint writer(int index) const;
  Endpoint reader(int index) const;
};

}  // namespace rescuesim::ros2
