// Serialised samples through Cyclone DDS 0.10. Topics are created from idlc descriptors (so the
// DDS type name, the matching and Cyclone's checks follow the hand-written IDL), or, for raw
// endpoints, from a sertype of our own that only carries bytes (dds_raw_type.h). Cyclone 0.10
// has no public way to get a topic's sertype (dds_get_entity_sertype came later), so a sample
// is written as a serdata of a minimal "raw bytes" sertype of our own: dds_writecdr sees the
// type differs from the writer's and converts it with the writer's own from_ser_iov, which
// copies and validates the bytes. Received samples are the default serdata of the reader's
// type; their bytes come out through ddsi_serdata_to_ser.

#include "bridges/ros2/dds_participant.h"

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <mutex>
#include <string_view>

#include "bridges/ros2/dds_raw_type.h"
#include "core/error.h"
#include "core/tsan.h"

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

dds_entity_t DdsParticipant::make_raw_topic(const std::string& topic, const std::string& dds_type) {
  if (dds_type.empty()) throw Error("ROS 2 bridge: no DDS type name for topic " + topic);
  // Cyclone takes over the sertype's reference, and may swap in an equal one it already has;
  // on failure the reference is still ours
  ddsi_sertype* st = detail::make_raw_sertype(dds_type);
  const dds_entity_t t = dds_create_topic_sertype(participant_, topic.c_str(), &st, nullptr, nullptr, nullptr);
  if (t < 0) {
    ddsi_sertype_unref(st);
    throw Error("ROS 2 bridge: cannot create DDS topic " + topic + " of type " + dds_type + ": " + why(t));
  }
  return t;
}

int DdsParticipant::add_writer(const std::string& topic, dds_entity_t t, const EndpointQos& qos, const std::string& user_data) {
  Qos q;
  apply(qos, q.q);
  if (!user_data.empty()) dds_qset_userdata(q.q, user_data.data(), user_data.size());
  const dds_entity_t w = dds_create_writer(participant_, t, q.q, nullptr);
  if (w < 0) throw Error("ROS 2 bridge: cannot create a DDS writer on " + topic + ": " + why(w));
  std::lock_guard lock(mutex_);
  writers_.push_back({t, w});
  return static_cast<int>(writers_.size()) - 1;
}

int DdsParticipant::add_reader(const std::string& topic, dds_entity_t t, const EndpointQos& qos, const std::string& user_data,
                               Wake wake) {
  Qos q;
  apply(qos, q.q);
  if (!user_data.empty()) dds_qset_userdata(q.q, user_data.data(), user_data.size());
  const dds_entity_t r = dds_create_reader(participant_, t, q.q, nullptr);
  if (r < 0) throw Error("ROS 2 bridge: cannot create a DDS reader on " + topic + ": " + why(r));
  const dds_entity_t cond = dds_create_readcondition(r, DDS_ANY_STATE);
  Endpoint e{t, r};
  bool attached = false;
  if (cond >= 0 && wake == Wake::participant) {
    attached = dds_waitset_attach(waitset_, cond, r) == DDS_RETCODE_OK;
  } else if (cond >= 0) {
    // a waitset of the reader's own, so that its data wakes only wait_reader()
    e.own_waitset = dds_create_waitset(participant_);
    attached = e.own_waitset >= 0 && dds_waitset_attach(e.own_waitset, cond, r) == DDS_RETCODE_OK;
  }
  if (!attached) throw Error("ROS 2 bridge: cannot wait for data on " + topic);
  std::lock_guard lock(mutex_);
  readers_.push_back(e);
  return static_cast<int>(readers_.size()) - 1;
}

int DdsParticipant::create_writer(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                                  const std::string& user_data) {
  return add_writer(topic, make_topic(topic, dds_type), qos, user_data);
}

int DdsParticipant::create_discovery_writer(std::size_t gid_bytes) {
  return add_writer(kDiscoveryTopic, make_topic(kDiscoveryTopic, kDiscoveryType, gid_bytes), discovery_qos(), {});
}

int DdsParticipant::create_reader(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                                  const std::string& user_data) {
  return add_reader(topic, make_topic(topic, dds_type), qos, user_data, Wake::participant);
}

int DdsParticipant::create_raw_writer(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                                      const std::string& user_data) {
  return add_writer(topic, make_raw_topic(topic, dds_type), qos, user_data);
}

int DdsParticipant::create_raw_reader(const std::string& topic, const std::string& dds_type, const EndpointQos& qos,
                                      const std::string& user_data, Wake wake) {
  return add_reader(topic, make_raw_topic(topic, dds_type), qos, user_data, wake);
}

DdsParticipant::Endpoint DdsParticipant::writer(int index) const {
  std::lock_guard lock(mutex_);
  return writers_.at(static_cast<std::size_t>(index));
}

DdsParticipant::Endpoint DdsParticipant::reader(int index) const {
  std::lock_guard lock(mutex_);
  return readers_.at(static_cast<std::size_t>(index));
}

void DdsParticipant::delete_writer(int index) {
  dds_entity_t e = 0;
  {
    std::lock_guard lock(mutex_);
    std::swap(e, writers_.at(static_cast<std::size_t>(index)).entity);
  }
  if (e > 0) dds_delete(e);
}

void DdsParticipant::delete_reader(int index) {
  dds_entity_t e = 0, waitset = 0;
  {
    std::lock_guard lock(mutex_);
    Endpoint& r = readers_.at(static_cast<std::size_t>(index));
    std::swap(e, r.entity);
    std::swap(waitset, r.own_waitset);
  }
  // its read condition goes with it, and with that its place in the participant's waitset
  if (e > 0) dds_delete(e);
  if (waitset > 0) dds_delete(waitset);
}

bool DdsParticipant::write(int writer_index, std::span<const std::uint8_t> cdr, std::string* error) {
  RawSample sample;
  ddsi_serdata_init(&sample.base, &raw_sertype(), SDK_DATA);
  sample.bytes = cdr.data();
  sample.size = static_cast<std::uint32_t>(cdr.size());
  // dds_writecdr consumes the sample's one reference; the writer keeps its own converted copy
  const dds_return_t rc = dds_writecdr(writer(writer_index).entity, &sample.base);
  if (rc == DDS_RETCODE_OK) return true;
  if (error) {
    *error = rc == DDS_RETCODE_ERROR ? "Cyclone DDS refused the sample (its bytes do not fit the topic's type)" : why(rc);
  }
  return false;
}

void DdsParticipant::take(int reader_index, const std::function<void(std::span<const std::uint8_t>)>& f) {
  take_with_info(reader_index, [&](std::span<const std::uint8_t> bytes, const SampleInfo&) { f(bytes); });
}

void DdsParticipant::take_with_info(int reader_index,
                                    const std::function<void(std::span<const std::uint8_t>, const SampleInfo&)>& f) {
  const dds_entity_t r = reader(reader_index).entity;
  constexpr std::uint32_t kBatch = 16;
  std::vector<std::uint8_t> bytes;
  for (;;) {
    std::array<ddsi_serdata*, kBatch> samples{};
    std::array<dds_sample_info_t, kBatch> infos{};
    const dds_return_t n = dds_takecdr(r, samples.data(), kBatch, infos.data(), DDS_ANY_STATE);
    if (n <= 0) return;
    // every taken sample is released, also when `f` throws
    dds_return_t released = 0;
    try {
      for (; released < n; ++released) {
        const dds_sample_info_t& info = infos[static_cast<std::size_t>(released)];
        ddsi_serdata* s = samples[static_cast<std::size_t>(released)];
        tsan_acquire(s);  // made on one of Cyclone's threads (dds_raw_type.h)
        if (info.valid_data) {
          bytes.resize(ddsi_serdata_size(s));
          ddsi_serdata_to_ser(s, 0, bytes.size(), bytes.data());
          f(bytes, SampleInfo{info.publication_handle, info.source_timestamp});
        }
        detail::unref_seen_by_tsan(s);
      }
    } catch (...) {
      for (dds_return_t i = released; i < n; ++i) detail::unref_seen_by_tsan(samples[static_cast<std::size_t>(i)]);
      throw;
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

bool DdsParticipant::wait_reader(int reader_index, std::chrono::milliseconds timeout) {
  const Endpoint e = reader(reader_index);
  if (e.own_waitset <= 0) throw Error("ROS 2 bridge: wait_reader() on a reader that wakes the participant's wait()");
  return dds_waitset_wait(e.own_waitset, nullptr, 0, DDS_MSECS(std::max<std::int64_t>(0, timeout.count()))) > 0;
}

Guid DdsParticipant::participant_guid() const { return guid_of(participant_); }
Guid DdsParticipant::writer_guid(int w) const { return guid_of(writer(w).entity); }
Guid DdsParticipant::reader_guid(int r) const { return guid_of(reader(r).entity); }

std::uint64_t DdsParticipant::writer_instance_handle(int w) const {
  dds_instance_handle_t ih = 0;
  if (dds_get_instance_handle(writer(w).entity, &ih) != DDS_RETCODE_OK) return 0;
  return ih;
}

int DdsParticipant::matched_readers(int w) const {
  dds_publication_matched_status_t st{};
  if (dds_get_publication_matched_status(writer(w).entity, &st) != DDS_RETCODE_OK) return 0;
  return static_cast<int>(st.current_count);
}

int DdsParticipant::matched_writers(int r) const {
  dds_subscription_matched_status_t st{};
  if (dds_get_subscription_matched_status(reader(r).entity, &st) != DDS_RETCODE_OK) return 0;
  return static_cast<int>(st.current_count);
}

namespace {

// USER_DATA of a matched endpoint's discovery data, which this frees
std::optional<std::string> user_data_of(dds_builtintopic_endpoint_t* ep) {
  if (ep == nullptr) return std::nullopt;
  std::string out;
  void* ud = nullptr;
  size_t size = 0;
  if (ep->qos != nullptr && dds_qget_userdata(ep->qos, &ud, &size) && ud != nullptr) {
    out.assign(static_cast<const char*>(ud), size);
    dds_free(ud);
  }
  dds_builtintopic_free_endpoint(ep);
  return out;
}

// the instance handles of what `entity` is matched with (dds_get_matched_subscriptions/_publications)
template <class Get>
std::vector<dds_instance_handle_t> matched(dds_entity_t entity, Get get) {
  std::vector<dds_instance_handle_t> handles(8);
  for (;;) {
    const dds_return_t n = get(entity, handles.data(), handles.size());
    if (n < 0) return {};
    if (static_cast<std::size_t>(n) <= handles.size()) {
      handles.resize(static_cast<std::size_t>(n));
      return handles;
    }
    handles.resize(static_cast<std::size_t>(n));  // more than fitted: ask again with room for all
  }
}

}  // namespace

std::vector<Guid> DdsParticipant::matched_reader_guids(int w) const {
  const dds_entity_t e = writer(w).entity;
  std::vector<Guid> out;
  for (const dds_instance_handle_t h : matched(e, dds_get_matched_subscriptions)) {
    if (dds_builtintopic_endpoint_t* ep = dds_get_matched_subscription_data(e, h)) {
      Guid g{};
      std::memcpy(g.data(), ep->key.v, g.size());
      out.push_back(g);
      dds_builtintopic_free_endpoint(ep);
    }
  }
  return out;
}

std::vector<std::string> DdsParticipant::matched_reader_user_data(int w) const {
  const dds_entity_t e = writer(w).entity;
  std::vector<std::string> out;
  for (const dds_instance_handle_t h : matched(e, dds_get_matched_subscriptions)) {
    if (auto ud = user_data_of(dds_get_matched_subscription_data(e, h))) out.push_back(std::move(*ud));
  }
  return out;
}

std::vector<std::string> DdsParticipant::matched_writer_user_data(int r) const {
  const dds_entity_t e = reader(r).entity;
  std::vector<std::string> out;
  for (const dds_instance_handle_t h : matched(e, dds_get_matched_publications)) {
    if (auto ud = user_data_of(dds_get_matched_publication_data(e, h))) out.push_back(std::move(*ud));
  }
  return out;
}

std::optional<std::string> DdsParticipant::matched_writer_user_data(int r, std::uint64_t publication_handle) const {
  return user_data_of(dds_get_matched_publication_data(reader(r).entity, publication_handle));
}

std::uint32_t DdsParticipant::next_client_service_counter() {
  std::lock_guard lock(mutex_);
  return ++client_service_counter_;
}

}  // namespace rescuesim::ros2
