#pragma once
/// A Cyclone DDS type ("sertype") for any DDS type name whose samples are nothing but their
/// serialised bytes, encapsulation header included: no IDL, no descriptor, no checks. Topics of
/// service and action types use it, so that the bridge needs no IDL for them (the codecs above
/// validate what arrives). Internal to dds_participant.cpp; Cyclone's types stay in .cpp files.

#include <string>

struct ddsi_sertype;

namespace rescuesim::ros2::detail {

/// A new raw sertype named `dds_type` ("simulation_interfaces::srv::dds_::ResetSimulation_Request_"),
/// keyless, holding one reference that dds_create_topic_sertype takes over (Cyclone
/// then shares one sertype among all equal ones: same name, same raw operations).
ddsi_sertype* make_raw_sertype(const std::string& dds_type);

}  // namespace rescuesim::ros2::detail
