#pragma once
/// A Cyclone DDS type ("sertype") for any DDS type name whose samples are nothing but their
/// serialised bytes, encapsulation header included: no IDL, no descriptor, no checks. Topics of
/// service and action types use it, so that the bridge needs no IDL for them (the codecs above
/// validate what arrives). Internal to dds_participant.cpp; Cyclone's types stay in .cpp files.

#include <string>

struct ddsi_sertype;
struct ddsi_serdata;

namespace rescuesim::ros2::detail {

/// A new raw sertype named `dds_type` ("simulation_interfaces::srv::dds_::ResetSimulation_Request_"),
/// keyless, holding one reference that dds_create_topic_sertype takes over (Cyclone
/// then shares one sertype among all equal ones: same name, same raw operations).
ddsi_sertype* make_raw_sertype(const std::string& dds_type);

/// Drops one reference to a serdata (ddsi_serdata_unref), telling ThreadSanitizer that what this
/// thread did to it happens before its free, which Cyclone's uninstrumented atomics order
/// (core/tsan.h); the same as ddsi_serdata_unref in any other build. A thread that takes a
/// serdata from Cyclone calls tsan_acquire on it before reading it.
void unref_seen_by_tsan(ddsi_serdata* d);

}  // namespace rescuesim::ros2::detail
