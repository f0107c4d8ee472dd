// The raw sertype: a serdata owns a copy of the sample's serialised bytes and gives them back
// unchanged. Received samples come from the fragments Cyclone reassembled (from_ser), written
// ones from the bytes the bridge hands in (from_ser_iov, through dds_writecdr's conversion).
// Samples have no key, so every key operation is trivial, and there is no deserialised form:
// the bridge only ever uses dds_writecdr and dds_takecdr on these topics. The same shape as
// rmw_cyclonedds's serdata_rmw, minus its type support.

#include "bridges/ros2/dds_raw_type.h"

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>
#include <dds/ddsi/q_radmin.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>

#include "core/tsan.h"

namespace rescuesim::ros2::detail {

namespace {

struct RawSerdata : ddsi_serdata {
  RawSerdata(const ddsi_sertype* type, ddsi_serdata_kind kind) : ddsi_serdata{} { ddsi_serdata_init(this, type, kind); }

  // Cyclone may read up to the next multiple of 4 past the size (ddsi_serdata_to_ser_t), so the
  // buffer is that long and the padding is zero
  void resize(std::size_t n) {
    size = static_cast<std::uint32_t>(n);
    bytes.reset(new std::uint8_t[(n + 3) & ~std::size_t{3}]());
  }

  std::uint32_t size = 0;
  std::unique_ptr<std::uint8_t[]> bytes;
};

const RawSerdata& raw(const ddsi_serdata* d) { return *static_cast<const RawSerdata*>(d); }

// A serdata passes between Cyclone's threads and ours by a reference count kept with Cyclone's
// own atomics, which TSan cannot see in Debian's build: an operation that writes or reads the
// bytes acquires the serdata first and releases it after, and freeing it acquires, so TSan
// sees the order the count gives (core/tsan.h; no-ops outside TSan).
struct SeenByTsan {
  explicit SeenByTsan(const ddsi_serdata* d) : d(d) { tsan_acquire(d); }
  ~SeenByTsan() { tsan_release(d); }
  SeenByTsan(const SeenByTsan&) = delete;
  SeenByTsan& operator=(const SeenByTsan&) = delete;
  const ddsi_serdata* d;
};

bool raw_eqkey(const ddsi_serdata*, const ddsi_serdata*) { return true; }  // keyless: one instance
uint32_t raw_get_size(const ddsi_serdata* d) {
  const SeenByTsan seen(d);
  return raw(d).size;
}

ddsi_serdata* raw_from_ser(const ddsi_sertype* type, ddsi_serdata_kind kind, const nn_rdata* fragchain, size_t size) {
  auto d = std::unique_ptr<RawSerdata>(new (std::nothrow) RawSerdata(type, kind));
  if (!d) return nullptr;
  const SeenByTsan seen(d.get());
  d->resize(size);
  // fragments may overlap: copy only what each adds beyond the bytes already copied
  std::size_t off = 0;
  for (; fragchain != nullptr; fragchain = fragchain->nextfrag) {
    if (fragchain->maxp1 <= off) continue;
    const unsigned char* payload = NN_RMSG_PAYLOADOFF(fragchain->rmsg, NN_RDATA_PAYLOAD_OFF(fragchain));
    const std::size_t end = std::min<std::size_t>(fragchain->maxp1, size);
    if (end > off) std::memcpy(d->bytes.get() + off, payload + (off - fragchain->min), end - off);
    off = fragchain->maxp1;
  }
  return d.release();
}

ddsi_serdata* raw_from_ser_iov(const ddsi_sertype* type, ddsi_serdata_kind kind, ddsrt_msg_iovlen_t niov,
                               const ddsrt_iovec_t* iov, size_t size) {
  auto d = std::unique_ptr<RawSerdata>(new (std::nothrow) RawSerdata(type, kind));
  if (!d) return nullptr;
  const SeenByTsan seen(d.get());
  d->resize(size);
  std::size_t off = 0;
  for (ddsrt_msg_iovlen_t i = 0; i < niov && off < size; ++i) {
    const std::size_t n = std::min<std::size_t>(iov[i].iov_len, size - off);
    std::memcpy(d->bytes.get() + off, iov[i].iov_base, n);
    off += n;
  }
  return d.release();
}

ddsi_serdata* raw_from_keyhash(const ddsi_sertype* type, const ddsi_keyhash*) {
  auto* d = new (std::nothrow) RawSerdata(type, SDK_KEY);
  tsan_release(d);
  return d;
}

// writing goes through dds_writecdr only: there is no in-memory sample to serialise
ddsi_serdata* raw_from_sample(const ddsi_sertype*, ddsi_serdata_kind, const void*) { return nullptr; }

void raw_to_ser(const ddsi_serdata* d, size_t off, size_t sz, void* buf) {
  const SeenByTsan seen(d);
  std::memcpy(buf, raw(d).bytes.get() + off, sz);
}

ddsi_serdata* raw_to_ser_ref(const ddsi_serdata* d, size_t off, size_t sz, ddsrt_iovec_t* ref) {
  const SeenByTsan seen(d);
  ref->iov_base = raw(d).bytes.get() + off;
  ref->iov_len = static_cast<ddsrt_iov_len_t>(sz);
  const TsanIgnoreAccesses count;  // Cyclone's count, inlined from its header
  return ddsi_serdata_ref(d);
}

void raw_to_ser_unref(ddsi_serdata* d, const ddsrt_iovec_t*) { unref_seen_by_tsan(d); }

// nor is there one to deserialise into: readers take the bytes (dds_takecdr)
bool raw_to_sample(const ddsi_serdata*, void*, void**, void*) { return false; }

ddsi_serdata* raw_to_untyped(const ddsi_serdata* d) {
  auto* u = new (std::nothrow) RawSerdata(d->type, SDK_KEY);
  if (u) u->type = nullptr;  // an untyped serdata has no type (ddsi_serdata_to_untyped_t)
  tsan_release(u);
  return u;
}

bool raw_untyped_to_sample(const ddsi_sertype*, const ddsi_serdata*, void*, void**, void*) { return true; }

void raw_free(ddsi_serdata* d) {
  tsan_acquire(d);
  delete static_cast<RawSerdata*>(d);
}

size_t raw_print(const ddsi_sertype*, const ddsi_serdata* d, char* buf, size_t size) {
  const SeenByTsan seen(d);
  const int n = std::snprintf(buf, size, "(%u serialised bytes)", static_cast<unsigned>(raw(d).size));
  return n < 0 ? 0 : static_cast<size_t>(n);
}

void raw_get_keyhash(const ddsi_serdata*, ddsi_keyhash* buf, bool) { std::memset(buf, 0, sizeof *buf); }

const ddsi_serdata_ops kRawSerdataOps = [] {
  ddsi_serdata_ops o{};
  o.eqkey = raw_eqkey;
  o.get_size = raw_get_size;
  o.from_ser = raw_from_ser;
  o.from_ser_iov = raw_from_ser_iov;
  o.from_keyhash = raw_from_keyhash;
  o.from_sample = raw_from_sample;
  o.to_ser = raw_to_ser;
  o.to_ser_ref = raw_to_ser_ref;
  o.to_ser_unref = raw_to_ser_unref;
  o.to_sample = raw_to_sample;
  o.to_untyped = raw_to_untyped;
  o.untyped_to_sample = raw_untyped_to_sample;
  o.free = raw_free;
  o.print = raw_print;
  o.get_keyhash = raw_get_keyhash;
  return o;
}();

void raw_type_free(ddsi_sertype* t) {
  tsan_acquire(t);  // made by make_raw_sertype, maybe on another thread
  ddsi_sertype_fini(t);
  delete t;
}
void raw_zero_samples(const ddsi_sertype*, void*, size_t) {}
void raw_realloc_samples(void** ptrs, const ddsi_sertype*, void*, size_t, size_t count) {
  // never called on the paths the bridge uses (loans, dispose by handle, content filters)
  for (size_t i = 0; i < count; ++i) ptrs[i] = nullptr;
}
void raw_free_samples(const ddsi_sertype*, void**, size_t, dds_free_op_t) {}
// two raw sertypes are equal when Cyclone's generic checks pass (same name and operations)
bool raw_type_equal(const ddsi_sertype*, const ddsi_sertype*) { return true; }
uint32_t raw_type_hash(const ddsi_sertype*) { return 0; }
size_t raw_serialized_size(const ddsi_sertype*, const void*) { return SIZE_MAX; }  // the documented error value
bool raw_serialize_into(const ddsi_sertype*, const void*, void*, size_t) { return false; }

const ddsi_sertype_ops kRawSertypeOps = [] {
  ddsi_sertype_ops o{};
  o.version = ddsi_sertype_v0;
  o.free = raw_type_free;
  o.zero_samples = raw_zero_samples;
  o.realloc_samples = raw_realloc_samples;
  o.free_samples = raw_free_samples;
  o.equal = raw_type_equal;
  o.hash = raw_type_hash;
  o.get_serialized_size = raw_serialized_size;
  o.serialize_into = raw_serialize_into;
  return o;
}();

}  // namespace

void unref_seen_by_tsan(ddsi_serdata* d) {
  tsan_release(d);
  const TsanIgnoreAccesses count;  // Cyclone's count, inlined from its header (may free d here)
  ddsi_serdata_unref(d);
}

ddsi_sertype* make_raw_sertype(const std::string& dds_type) {
  auto* t = new ddsi_sertype{};
  ddsi_sertype_init_flags(t, dds_type.c_str(), &kRawSertypeOps, &kRawSerdataOps, DDSI_SERTYPE_FLAG_TOPICKIND_NO_KEY);
  // what an idlc type allows too: a topic's QoS gets its data representations from its type,
  // and Cyclone refuses a second type on a topic name when the topic QoS differs (TwistStamped
  // beside Twist on cmd_vel). The endpoints themselves ask for XCDR1 (dds_participant.cpp).
  t->allowed_data_representation = DDS_DATA_REPRESENTATION_RESTRICT_DEFAULT;
  tsan_release(t);  // Cyclone frees it on whichever thread drops the last reference
  return t;
}

}  // namespace rescuesim::ros2::detail
