#pragma once
// Test support for DDS tests: pins Cyclone DDS (rescuesim) and Fast DDS (the interop peer) to the
// loopback interface without multicast, so tests never leave the machine or meet each other.

#include <cstdlib>
#include <filesystem>

#include "support/command.h"

namespace rescuesim::testing {

/// Pins Cyclone DDS of this process (rescuesim's participants and the tests' own) to 127.0.0.1
/// without multicast, with the configuration inline in CYCLONEDDS_URI.
inline void pin_cyclone_to_loopback() {
  ::setenv("CYCLONEDDS_URI",
           "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces><AllowMulticast>false</AllowMulticast></General>"
           "<Discovery><ParticipantIndex>auto</ParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>",
           1);
}

/// Pins Cyclone (rescuesim) and Fast DDS (the peer) to 127.0.0.1 without multicast.
inline void pin_dds_to_loopback(const std::filesystem::path& dir) {
  write_text(dir / "cyclonedds.xml",
             "<CycloneDDS><Domain Id=\"any\">\n"
             "  <General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces><AllowMulticast>false</AllowMulticast></General>\n"
             "  <Discovery><ParticipantIndex>auto</ParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>\n"
             "</Domain></CycloneDDS>\n");
  write_text(dir / "fastdds.xml",
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<profiles xmlns=\"http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles\">\n"
             "  <transport_descriptors><transport_descriptor>\n"
             "    <transport_id>loopback</transport_id><type>UDPv4</type>\n"
             "    <interfaceWhiteList><address>127.0.0.1</address></interfaceWhiteList>\n"
             "    <receiveBufferSize>4194304</receiveBufferSize>\n"
             "  </transport_descriptor></transport_descriptors>\n"
             "  <participant profile_name=\"ros2_peer\" is_default_profile=\"true\"><rtps>\n"
             "    <userTransports><transport_id>loopback</transport_id></userTransports>\n"
             "    <useBuiltinTransports>false</useBuiltinTransports>\n"
             "    <builtin><initialPeersList><locator><udpv4><address>127.0.0.1</address></udpv4></locator></initialPeersList></builtin>\n"
             "  </rtps></participant>\n"
             "</profiles>\n");
  ::setenv("CYCLONEDDS_URI", ("file://" + (dir / "cyclonedds.xml").string()).c_str(), 1);
  ::setenv("FASTRTPS_DEFAULT_PROFILES_FILE", (dir / "fastdds.xml").string().c_str(), 1);
}

}  // namespace rescuesim::testing
