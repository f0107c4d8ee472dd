// Serialised samples through Cyclone DDS 0.10. Topics are created from idlc descriptors (so the
// DDS type name, the matching and Cyclone's checks follow the hand-written IDL). Cyclone 0.10
// has no public way to get a topic's sertype (dds_get_entity_sertype came later), so a sample
// is written as a serdata of a minimal "raw bytes" sertype of our own: dds_writecdr sees the
// type differs from the writer's and converts it with the writer's own from_ser_iov, which
// copies and validates the bytes. Received samples are the default serdata of the reader's
// type; their bytes come out through ddsi_serdata_to_ser.

#include "bridges/ros2/dds_participant.h"

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

#include <array>
#include <cstring>
#include <map>
#include <mutex>
#include <string_view>

#include "core/error.h"

#include "ros2_messages.h"
#include "ros_discovery_humble.h"
#include "ros_discovery_iron.h"

namespace rescuesim::ros2 {

namespace {

// the descriptors idlc made from idl/ros2_messages.idl, by DDS type name
#define RS_DDS_TYPE(pkg, type) {#pkg "::msg::dds_::" #type "_", &pkg##_msg_dds__##type##__desc}
const std::map<std::string_view, const dds_topic_descriptor_t*>& descriptors() {
  static const std::map<std::string_view, const dds_topic_descriptor_t*> table = {
      RS_DDS_TYPE(rosgraph_msgs, Clock),       RS_DDS_TYPE(sensor_msgs, LaserScan),
      RS_DDS_TYPE(sensor_msgs, Range),         RS_DDS_TYPE(sensor_msgs, Imu),
      RS_DDS_TYPE(geometry_msgs, Twist),       RS_DDS_TYPE(nav_msgs, Odometry),
      RS_DDS_TYPE(sensor_msgs, JointState),    RS_DDS_TYPE(tf2_msgs, TFMessage),
      RS_DDS_TYPE(geometry_msgs, PoseStamped), RS_DDS_TYPE(nav_msgs, Path),
      RS_DDS_TYPE(nav_msgs, OccupancyGrid),    RS_DDS_TYPE(std_msgs, Float64MultiArray),
      RS_DDS_TYPE(rescuesim_msgs, Contacts),   RS_DDS_TYPE(sensor_msgs, Image),
      RS_DDS_TYPE(sensor_msgs, CameraInfo),    RS_DDS_TYPE(sensor_msgs, PointCloud2),
      RS_DDS_TYPE(std_msgs, String), RS_DDS_TYPE(std_msgs, Bool),
  };
  return table;
}
#undef RS_DDS_TYPE

// ParticipantEntitiesInfo with 16-byte Gids (Iron on) comes from a module of its own, so C can
// hold both layouts; on the wire it goes by the one DDS type name ROS uses
const dds_topic_descriptor_t& iron_discovery_descriptor() {
  static const dds_topic_descriptor_t& d = rescuesim_iron_rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc;
  static const dds_topic_descriptor_t renamed{d.m_size,  d.m_align, d.m_flagset, d.m_nkeys,
                                              kDiscoveryType, d.m_keys, d.m_nops, d.m_ops,
                                              d.m_meta, d.type_information, d.type_mapping,
                                              d.restrict_data_representation};
  return renamed;
}

std::string why(dds_return_t rc) { return dds_strretcode(rc); }

// a serialised sample that only borrows the caller's bytes, for the duration of one dds_writecdr
struct RawSample {
  ddsi_serdata base;
  const std::uint8_t* bytes;
  std::uint32_t size;
};

const RawSample& raw(const ddsi_serdata* d) { return *reinterpret_cast<const RawSample*>(d); }

uint32_t raw_get_size(const ddsi_serdata* d) { return raw(d).size; }
void raw_free(ddsi_serdata*) {}  // lives on the writing thread's stack
void raw_to_ser(const ddsi_serdata* d, size_t off, size_t sz, void* buf) { std::memcpy(buf, raw(d).bytes + off, sz); }
ddsi_serdata* raw_to_ser_ref(const ddsi_serdata* d, size_t off, size_t sz, ddsrt_iovec_t* ref) {
  ref->iov_base = const_cast<std::uint8_t*>(raw(d).bytes + off);
  ref->iov_len = static_cast<ddsrt_iov_len_t>(sz);
  return ddsi_serdata_ref(d);
}
void raw_to_ser_unref(ddsi_serdata* d, const ddsrt_iovec_t*) { ddsi_serdata_unref(d); }

// the "raw bytes" sertype: never attached to a topic, only the source of dds_writecdr's conversion
ddsi_sertype& raw_sertype() {
  static ddsi_serdata_ops serdata_ops = [] {
    ddsi_serdata_ops o{};
    o.get_size = raw_get_size;
    o.free = raw_free;
    o.to_ser = raw_to_ser;
    o.to_ser_ref = raw_to_ser_ref;
    o.to_ser_unref = raw_to_ser_unref;
    return o;
  }();
  static ddsi_sertype_ops sertype_ops = [] {
    ddsi_sertype_ops o{};
    o.version = ddsi_sertype_v0;
    return o;
  }();
  static ddsi_sertype type;
  static std::once_flag once;
  std::call_once(once, [] { ddsi_sertype_init(&type, "rescuesim::raw_cdr", &sertype_ops, &serdata_ops, true); });
  return type;
}

// RAII for a dds_qos_t
struct Qos {
  dds_qos_t* q = dds_create_qos();
  ~Qos() { dds_delete_qos(q); }
};

void apply(const EndpointQos& e, dds_qos_t* q) {
  dds_qset_reliability(q, e.reliability == Reliability::reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_durability(q, e.durability == Durability::transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  dds_qset_history(q, DDS_HISTORY_KEEP_LAST, e.depth);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(q, 1, &xcdr1);
}

Guid guid_of(dds_entity_t e) {
  dds_guid_t g;
  Guid out{};
  if (dds_get_guid(e, &g) == DDS_RETCODE_OK) std::memcpy(out.data(), g.v, out.size());
  return out;
}

}  // namespace

DdsParticipant::DdsParticipant(int domain, const std::string& user_data) {
  Qos qos;
  dds_qset_userdata(qos.q, user_data.data(), user_data.size());
  participant_ = dds_create_participant(static_cast<dds_domainid_t>(domain), qos.q, nullptr);
  if (participant_ < 0) {
    const char* uri = std::getenv("CYCLONEDDS_URI");
    throw Error("ROS 2 bridge: Cyclone DDS could not create a participant on domain " + std::to_string(domain) + " (" +
                why(participant_) + ")" +
                (uri ? std::string("; check the configuration in CYCLONEDDS_URI=") + uri
                     : std::string("; is a network interface up? CYCLONEDDS_URI can pin one")));
  }
  waitset_ = dds_create_waitset(participant_);
  guard_ = dds_create_guardcondition(participant_);
  if (waitset_ < 0 || guard_ < 0 || dds_waitset_attach(waitset_, guard_, 0) != DDS_RETCODE_OK) {
    dds_delete(participant_);
    throw Error("ROS 2 bridge: Cyclone DDS could not create a waitset");
  }
}

DdsParticipant::~DdsParticipant() {
  // deleting the participant deletes every entity it owns (writers linger to deliver what is unacknowledged)
  dds_delete(participant_);
}

bool DdsParticipant::knows_type(const std::string& dds_type) { return descriptors().contains(dds_type); }

dds_entity_t DdsParticipant::make_topic(const std::string& topic, const std::string& dds_type, std::size_t gid_bytes) {
  const dds_topic_descriptor_t* desc = nullptr;
  if (dds_type == kDiscoveryType) {
    desc = gid_bytes == 16 ? &iron_discovery_descriptor() : &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc;
  } else if (const auto it = descriptors().find(dds_type); it != descriptors().end()) {
    desc = it->second;
  } else {
    throw Error("ROS 2 bridge: no DDS type " + dds_type + " for topic " + topic);
  }
  const dds_entity_t t = dds_create_topic(participant_, desc, topic.c_str(), nullptr, nullptr);
  if (t < 0) throw Error("ROS 2 bridge: cannot create DDS topic " + topic + " of type " + dds_type + ": " + why(t));
  return t;
}

int DdsParticipant::create_writer(const std::string& topic, const std::string& dds_type, const EndpointQos& qos) {
  const dds_entity_t t = make_topic(topic, dds_type);
  Qos q;
  apply(qos, q.q);
  const dds_entity_t w = dds_create_writer(participant_, t, q.q, nullptr);
  if (w < 0) throw Error("ROS 2 bridge: cannot create a DDS writer on " + topic + ": " + why(w));
  writers_.push_back({t, w});
  return static_cast<int>(writers_.size()) - 1;
}

int DdsParticipant::create_discovery_writer(std::size_t gid_bytes) {
  const dds_entity_t t = make_topic(kDiscoveryTopic, kDiscoveryType, gid_bytes);
  Qos q;
  apply(discovery_qos(), q.q);
  const dds_entity_t w = dds_create_writer(participant_, t, q.q, nullptr);
  if (w < 0) throw Error(std::string("ROS 2 bridge: cannot create the DDS writer on ") + kDiscoveryTopic + ": " + why(w));
  writers_.push_back({t, w});
  return static_cast<int>(writers_.size()) - 1;
}

int DdsParticipant::create_reader(const std::string& topic, const std::string& dds_type, const EndpointQos& qos) {
  const dds_entity_t t = make_topic(topic, dds_type);
  Qos q;
  apply(qos, q.q);
  const dds_entity_t r = dds_create_reader(participant_, t, q.q, nullptr);
  if (r < 0) throw Error("ROS 2 bridge: cannot create a DDS reader on " + topic + ": " + why(r));
  const dds_entity_t cond = dds_create_readcondition(r, DDS_ANY_STATE);
  if (cond < 0 || dds_waitset_attach(waitset_, cond, r) != DDS_RETCODE_OK) {
    throw Error("ROS 2 bridge: cannot wait for data on " + topic);
  }
  readers_.push_back({t, r});
  return static_cast<int>(readers_.size()) - 1;
}

bool DdsParticipant::write(int writer, std::span<const std::uint8_t> cdr, std::string* error) {
  RawSample sample;
  ddsi_serdata_init(&sample.base, &raw_sertype(), SDK_DATA);
  sample.bytes = cdr.data();
  sample.size = static_cast<std::uint32_t>(cdr.size());
  // dds_writecdr consumes the sample's one reference; the writer keeps its own converted copy
  const dds_return_t rc = dds_writecdr(writers_.at(static_cast<std::size_t>(writer)).entity, &sample.base);
  if (rc == DDS_RETCODE_OK) return true;
  if (error) {
    *error = rc == DDS_RETCODE_ERROR ? "Cyclone DDS refused the sample (its bytes do not fit the topic's type)" : why(rc);
  }
  return false;
}

void DdsParticipant::take(int reader, const std::function<void(std::span<const std::uint8_t>)>& f) {
  const dds_entity_t r = readers_.at(static_cast<std::size_t>(reader)).entity;
  constexpr std::uint32_t kBatch = 16;
  std::vector<std::uint8_t> bytes;
  for (;;) {
    std::array<ddsi_serdata*, kBatch> samples{};
    std::array<dds_sample_info_t, kBatch> infos{};
    const dds_return_t n = dds_takecdr(r, samples.data(), kBatch, infos.data(), DDS_ANY_STATE);
    if (n <= 0) return;
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[static_cast<std::size_t>(i)].valid_data) {
        ddsi_serdata* s = samples[static_cast<std::size_t>(i)];
        bytes.resize(ddsi_serdata_size(s));
        ddsi_serdata_to_ser(s, 0, bytes.size(), bytes.data());
        f(bytes);
      }
      ddsi_serdata_unref(samples[static_cast<std::size_t>(i)]);
    }
    if (static_cast<std::uint32_t>(n) < kBatch) return;
  }
}

void DdsParticipant::wait(std::chrono::milliseconds timeout) {
  dds_waitset_wait(waitset_, nullptr, 0, DDS_MSECS(timeout.count()));
  bool triggered = false;
  dds_take_guardcondition(guard_, &triggered);
}

void DdsParticipant::wake() { dds_set_guardcondition(guard_, true); }

Guid DdsParticipant::participant_guid() const { return guid_of(participant_); }
Guid DdsParticipant::writer_guid(int writer) const { return guid_of(writers_.at(static_cast<std::size_t>(writer)).entity); }
Guid DdsParticipant::reader_guid(int reader) const { return guid_of(readers_.at(static_cast<std::size_t>(reader)).entity); }

int DdsParticipant::matched_readers(int writer) const {
  dds_publication_matched_status_t st{};
  if (dds_get_publication_matched_status(writers_.at(static_cast<std::size_t>(writer)).entity, &st) != DDS_RETCODE_OK) return 0;
  return static_cast<int>(st.current_count);
}

int DdsParticipant::matched_writers(int reader) const {
  dds_subscription_matched_status_t st{};
  if (dds_get_subscription_matched_status(readers_.at(static_cast<std::size_t>(reader)).entity, &st) != DDS_RETCODE_OK) return 0;
  return static_cast<int>(st.current_count);
}

}  // namespace rescuesim::ros2
