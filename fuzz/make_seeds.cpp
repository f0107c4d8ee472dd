// Writes the generated seed corpora (cdr, ros1, mcap_reader, foxglove_client, batch_record, control_cdr) into fuzz/corpus:
// one small, valid input per message type and encoding, and MCAP files in each compression.
// Run once after a message type is added: build-fuzz/bin/fuzz_make_seeds fuzz/corpus

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "batch/batch_record.h"
#include "bridges/mcap/byte_sink.h"
#include "bridges/mcap/mcap_writer.h"
#include "control_cdr_seeds.h"
#include "msgs/serialize.h"

namespace {

using namespace rescuesim;
namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// Alternative i of msg::Message, default-constructed, with a little content in the types
/// whose arrays and strings matter most.
template <std::size_t I = 0>
msg::Message message_at(std::size_t i) {
  if constexpr (I < std::variant_size_v<msg::Message>) {
    if (i == I) {
      msg::Message m{std::in_place_index<I>};
      std::visit([](auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, msg::LaserScan>) {
          v.header.frame_id = "laser";
          v.angle_min = -0.5f;
          v.angle_max = 0.5f;
          v.ranges = {1.5f, 2.0f, 0.25f};
        } else if constexpr (std::is_same_v<T, msg::JointState>) {
          v.name = {"lift", "arm"};
          v.position = {0.15, -0.5};
        } else if constexpr (std::is_same_v<T, msg::Twist>) {
          v.linear.x() = 0.5;
          v.angular.z() = -0.25;
        } else if constexpr (std::is_same_v<T, msg::Float64MultiArray>) {
          v.data = {1.0, 2.5};
        }
      }, m);
      return m;
    }
    return message_at<I + 1>(i);
  } else {
    return msg::Message{};
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds <fuzz/corpus>\n");
    return 2;
  }
  const fs::path corpus = argv[1];
  const auto& types = msg::all_types();

  // decoders: first byte = type index, then the bytes
  for (std::size_t i = 0; i < types.size(); ++i) {
    const msg::Message m = message_at(i);
    std::string name = types[i].ros1_name;
    for (char& c : name) c = c == '/' ? '_' : c;
    std::vector<std::uint8_t> cdr{std::uint8_t(i)}, ros1{std::uint8_t(i)};
    msg::to_cdr(m, cdr);
    msg::to_ros1(m, ros1, 7);
    write_file(corpus / "cdr" / name, cdr);
    write_file(corpus / "ros1" / name, ros1);
  }

  // MCAP: a few messages on two channels, with metadata and an attachment, in each compression
  for (const auto& [compression, name] : {std::pair{mcap::Compression::none, "none.mcap"},
                                           std::pair{mcap::Compression::zstd, "zstd.mcap"},
                                           std::pair{mcap::Compression::lz4, "lz4.mcap"}}) {
    const fs::path path = corpus / "mcap_reader" / name;
    fs::create_directories(path.parent_path());
    mcap::WriterOptions options;
    options.compression = compression;
    options.chunk_size = 200;  // several chunks
    mcap::McapWriter w(std::make_unique<mcap::FileSink>(path), options);
    const msg::TypeSupport& twist = *msg::find_type("geometry_msgs/Twist");
    const msg::TypeSupport& scan = *msg::find_type("sensor_msgs/LaserScan");
    const auto s1 = w.add_schema(twist.ros2_name, "ros2msg", twist.ros2_definition);
    const auto s2 = w.add_schema(scan.ros2_name, "ros2msg", scan.ros2_definition);
    const auto c1 = w.add_channel(s1, "/cmd_vel", "cdr");
    const auto c2 = w.add_channel(s2, "/scan", "cdr", {{"qos", "reliable"}});
    for (std::uint32_t k = 0; k < 4; ++k) {
      std::vector<std::uint8_t> a, b;
      msg::to_cdr(message_at(twist.variant_index), a);
      msg::to_cdr(message_at(scan.variant_index), b);
      w.write_message(c1, k, 1000 * k, 1000 * k, a);
      w.write_message(c2, k, 1000 * k + 500, 1000 * k + 500, b);
    }
    w.write_metadata(mcap::Metadata{"run", {{"seed", "7"}}});
    w.write_attachment(mcap::Attachment{0, 0, "scenario.yaml", "application/yaml", {'a', ':', ' ', '1'}});
    w.close();
  }

  // Foxglove client frames: first byte even = text, odd = binary
  auto text = [&](const char* name, const std::string& json) {
    std::vector<std::uint8_t> b{0};
    b.insert(b.end(), json.begin(), json.end());
    write_file(corpus / "foxglove_client" / name, b);
  };
  text("subscribe", R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":3},{"id":2,"channelId":4}]})");
  text("unsubscribe", R"({"op":"unsubscribe","subscriptionIds":[1,2]})");
  text("advertise", R"({"op":"advertise","channels":[{"id":1,"topic":"/cmd_vel","encoding":"json","schemaName":"geometry_msgs/Twist"},{"id":2,"topic":"/joint_command","encoding":"cdr","schemaName":"sensor_msgs/JointState"}]})");
  text("unadvertise", R"({"op":"unadvertise","channelIds":[1]})");
  text("get_parameters", R"({"op":"getParameters","parameterNames":[],"id":"x"})");
  auto binary = [&](const char* name, const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> b{1, 0x01, 1, 0, 0, 0};
    b.insert(b.end(), payload.begin(), payload.end());
    write_file(corpus / "foxglove_client" / name, b);
  };
  auto json_bytes = [](const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
  std::vector<std::uint8_t> cdr;
  msg::to_cdr(message_at(msg::find_type("geometry_msgs/Twist")->variant_index), cdr);
  binary("twist_cdr", cdr);
  cdr.clear();
  msg::to_cdr(message_at(msg::find_type("sensor_msgs/JointState")->variant_index), cdr);
  binary("joint_state_cdr", cdr);
  cdr.clear();
  msg::to_cdr(message_at(msg::find_type("std_msgs/Float64MultiArray")->variant_index), cdr);
  binary("multi_array_cdr", cdr);
  binary("twist_json", json_bytes(R"({"linear":{"x":0.5,"y":0,"z":0},"angular":{"x":0,"y":0,"z":-0.25}})"));
  binary("joint_state_json", json_bytes(R"({"name":["lift"],"position":[0.15],"velocity":[],"effort":[]})"));
  binary("multi_array_json", json_bytes(R"({"layout":{"dim":[],"data_offset":0},"data":[1.0,2.5]})"));
  // a mission's inputs (a report, a map) as a publish panel writes them: some fields left out
  binary("report_json", json_bytes(R"({"header":{"stamp":{"sec":3,"nanosec":5},"frame_id":"map"},"pose":{"position":{"x":1.5,"y":-2}}})"));
  binary("map_json", json_bytes(R"({"info":{"resolution":0.1,"width":2,"height":1,"origin":{"position":{"x":0}}},"data":[-1,100]})"));
  // service call requests (0x02 | u32 service | u32 call | u32 encoding length | "json" | request),
  // one per Simulation Interfaces service as the Service Call panel sends them, and a frame
  // whose encoding length runs past its end
  auto call = [&](const char* name, std::uint32_t service, const std::string& request) {
    std::vector<std::uint8_t> b{1, 0x02, static_cast<std::uint8_t>(service), 0, 0, 0, 1, 0, 0, 0, 4, 0, 0, 0, 'j', 's', 'o', 'n'};
    b.insert(b.end(), request.begin(), request.end());
    write_file(corpus / "foxglove_client" / name, b);
  };
  call("service_reset", 1, R"({"scope":0})");
  call("service_get_state", 2, "{}");
  call("service_set_state", 3, R"({"state":{"state":2}})");
  call("service_step", 4, R"({"steps":5})");
  call("service_entities", 5, R"({"filters":{"filter":"rob.*","categories":[{"category":1}],"tags":{"tags":["a"],"filter_mode":1},"bounds":{"type":3,"points":[{"x":0,"y":0,"z":0},{"x":2}]}}})");
  call("service_get_entity", 6, R"({"entity":"robot"})");
  call("service_set_entity", 7, R"({"entity":"robot","state":{"header":{"stamp":{"sec":1,"nanosec":5},"frame_id":""},"pose":{"position":{"x":1,"y":2,"z":0},"orientation":{"z":0.6,"w":0.8}},"twist":{"linear":{"x":0.3},"angular":{"z":null}}},"set_pose":true,"set_twist":true})");
  call("service_features", 8, "{}");
  write_file(corpus / "foxglove_client" / "service_bad_length", {1, 0x02, 1, 0, 0, 0, 1, 0, 0, 0, 0xff, 0xff, 0xff, 0xff, '{', '}'});
  binary("image_json", json_bytes(R"({"height":1,"width":2,"encoding":"rgb8","step":6,"data":"AQIDBAUG"})"));

  // results.jsonl lines: a success, a failure
  TrialRecord ok;
  ok.trial = 3;
  ok.seed = 1234;
  ok.batch = "0123456789abcdef";
  ok.scenario = "arena";
  ok.success = true;
  ok.success_time = 42.5;
  ok.stop_reason = "all victims found";
  ok.victims_total = ok.victims_found = 2;
  ok.victims = {{"victim_1", true, 3.25}, {"victim_2", true, 42.5}};
  ok.coverage = 0.625;
  ok.distance = 12.75;
  ok.collisions = 1;
  ok.sim_time = 42.5;
  ok.wall_time = 2.0;
  ok.real_time_factor = 21.25;
  ok.state_hash = "00ff00ff00ff00ff";
  ok.host = "ci";
  TrialRecord failed;
  failed.trial = 0;
  failed.status = "failed";
  failed.error = "arena.svg:3: bad path";
  failed.stop_reason = failed.error;
  for (const auto& [name, record] : {std::pair{"ok.jsonl", ok}, std::pair{"failed.jsonl", failed}}) {
    const std::string line = to_json_line(record);
    write_file(corpus / "batch_record" / name, std::vector<std::uint8_t>(line.begin(), line.end()));
  }

  // the control interfaces' CDR bodies (control_cdr_seeds.h)
  fuzz::write_control_cdr_seeds(corpus);
  return 0;
}
