#pragma once
/// The seed corpus of the control_cdr fuzz target (fuzz/corpus/control_cdr), written by
/// fuzz_make_seeds: for every case of control_cdr_cases.h the bytes of a default body, and for
/// the bodies with nested sequences a value with something in them; each file starts with the
/// case's byte.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "control_cdr_cases.h"

namespace rescuesim::fuzz {

inline void write_control_cdr_seeds(const std::filesystem::path& corpus) {
  using namespace control;
  const std::filesystem::path dir = corpus / "control_cdr";
  std::filesystem::create_directories(dir);
  auto write = [&](const std::string& name, const std::vector<std::uint8_t>& body, int index) {
    if (index < 0) {
      std::fprintf(stderr, "control_cdr seeds: no case for %s\n", name.c_str());
      std::abort();
    }
    std::ofstream out(dir / name, std::ios::binary | std::ios::trunc);
    const char first = static_cast<char>(index);
    out.write(&first, 1);
    out.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
  };
  const auto& cases = control_cases();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::vector<std::uint8_t> body;
    cases[i].encode_default(body);
    write(cases[i].name, body, static_cast<int>(i));
  }

  // values with strings and sequences filled in, in both versions where they differ
  EntityState state;
  state.stamp_ns = 1'500'000'000;
  state.frame_id = "world";
  state.pose.p = Vec3(1, 2, 0.1);
  state.linear = Vec3(0.5, 0, 0);
  for (const auto v : {WireVersion::v1, WireVersion::v2}) {
    const std::string suffix = v == WireVersion::v1 ? "_v1" : "_v2";
    std::vector<std::uint8_t> b;
    encode_request<iface::SetEntityState>({"r1", state, true, false, true}, v, b);
    write("SetEntityState_Request" + suffix + "_teleport", b, control_case_index("SetEntityState_Request" + suffix));
    b.clear();
    SpawnRequest spawn;
    spawn.name = "p3at";
    spawn.uri = "package://p3at/p3at.urdf";
    spawn.entity_namespace = "team";
    spawn.frame_id = "world";
    encode_request<iface::SpawnEntity>(spawn, v, b);
    write("SpawnEntity_Request" + suffix + "_urdf", b, control_case_index("SpawnEntity_Request" + suffix));
    b.clear();
    GetSpawnablesResponse spawnables;
    const Bounds box{Bounds::kBox, {Vec3(-1, -1, 0), Vec3(1, 1, 1)}};
    spawnables.spawnables.push_back({"package://p3at.urdf", "<robot/>", "P3-AT", box});
    encode_response<iface::GetSpawnables>(spawnables, v, b);
    write("GetSpawnables_Response" + suffix + "_one", b, control_case_index("GetSpawnables_Response" + suffix));
  }
  std::vector<std::uint8_t> b;
  EntityFilters filters{"^r[0-9]+$", {category::kRobot}, {{"team"}, 1}, {Bounds::kSphere, {Vec3(0, 0, 0), Vec3(5, 0, 0)}}};
  encode_request<iface::GetEntities>(filters, WireVersion::v1, b);
  write("GetEntities_Request_v1_filters", b, control_case_index("GetEntities_Request_v1"));
  b.clear();
  SetParametersRequest set;
  set.parameters.push_back({"realtime_rate", {}});
  set.parameters[0].value.type = ParameterValue::kDouble;
  set.parameters[0].value.double_value = 2.0;
  set.parameters.push_back({"tags", {}});
  set.parameters[1].value.type = ParameterValue::kStringArray;
  set.parameters[1].value.string_array_value = {"a", "bc"};
  set.parameters[1].value.integer_array_value = {1, -2};
  encode_request<iface::SetParameters>(set, WireVersion::v1, b);
  write("SetParameters_Request_v1_two", b, control_case_index("SetParameters_Request_v1"));
  b.clear();
  DescribeParametersResponse described;
  described.descriptors.push_back({"realtime_rate", ParameterValue::kDouble, "x", "", false, false, {{0, 100, 0}}, {}});
  described.descriptors.push_back({"seed", ParameterValue::kInteger, "", "", true, false, {}, {{0, 9, 1}}});
  encode_response<iface::DescribeParameters>(described, WireVersion::v1, b);
  write("DescribeParameters_Response_v1_ranges", b, control_case_index("DescribeParameters_Response_v1"));
  b.clear();
  GoalStatusArray status;
  status.status_list.push_back({{GoalId{1, 2, 3}, 5}, goal_status::kExecuting});
  encode_message<iface::SimulateStepsStatus>(status, WireVersion::v1, b);
  write("GoalStatusArray_v1_one", b, control_case_index("GoalStatusArray_v1"));
}

}  // namespace rescuesim::fuzz
