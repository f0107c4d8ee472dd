// JSON of messages (Foxglove's json encoding) and the JSON Schema of each type.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "msgs/serialize.h"
#include "samples.h"

namespace rescuesim::msg {
namespace {

using Json = nlohmann::json;

TEST(JsonSerialize, LaserScanText) {
  EXPECT_EQ(to_json(test::laser_scan()),
            R"({"header":{"stamp":{"sec":2,"nsec":250000000},"frame_id":"laser"},"angle_min":-0.5,"angle_max":0.5,)"
            R"("angle_increment":1,"time_increment":0.25,"scan_time":0.125,"range_min":0.0625,"range_max":8,)"
            R"("ranges":[1.5,null],"intensities":[]})");
}

TEST(JsonSerialize, ImageBytesAreBase64) {
  EXPECT_EQ(to_json(test::image()),
            R"({"header":{"stamp":{"sec":1,"nsec":0},"frame_id":"cam"},"height":1,"width":2,"encoding":"rgb8",)"
            R"("is_bigendian":0,"step":6,"data":"AQIDBAUG"})");
  // RFC 4648 padding for 1 and 2 trailing bytes
  Image im = test::image();
  const std::pair<std::vector<std::uint8_t>, const char*> cases[] = {
      {{}, "\"\""}, {{0x01}, "\"AQ==\""}, {{0x01, 0x02}, "\"AQI=\""}, {{0xff, 0xfe, 0xfd}, "\"//79\""}};
  for (const auto& [data, text] : cases) {
    im.data = data;
    const std::string j = to_json(im);
    EXPECT_EQ(j.substr(j.find("\"data\":") + 7), std::string(text) + "}");
  }
}

TEST(JsonSerialize, NestedMessagesAndFlattenedFields) {
  EXPECT_EQ(to_json(test::twist()), R"({"linear":{"x":0.5,"y":0,"z":0},"angular":{"x":0,"y":0,"z":-0.25}})");
  EXPECT_EQ(to_json(test::float64_multi_array()), R"({"layout":{"dim":[],"data_offset":0},"data":[1.5,-2]})");
  EXPECT_EQ(to_json(test::clock_msg()), R"({"clock":{"sec":1,"nsec":500000000}})");
  EXPECT_EQ(to_json(test::string_msg()), R"({"data":"ab"})");
  EXPECT_EQ(to_json(test::tf_message()),
            R"({"transforms":[{"header":{"stamp":{"sec":2,"nsec":0},"frame_id":"odom"},"child_frame_id":"base_link",)"
            R"("transform":{"translation":{"x":1,"y":-1,"z":0},"rotation":{"x":0,"y":0,"z":0,"w":1}}}]})");
  const std::string cam = to_json(test::camera_info());
  EXPECT_NE(cam.find(R"("D":[0.5,-0.25,0,0,0.125],"K":[500,0,320,0,500,240,0,0,1],"R":[1,0,0,0,1,0,0,0,1],)"),
            std::string::npos)
      << cam;
  EXPECT_NE(cam.find(R"("roi":{"x_offset":0,"y_offset":0,"height":0,"width":8,"do_rectify":true}})"), std::string::npos)
      << cam;
  const std::string grid = to_json(test::occupancy_grid());
  EXPECT_NE(grid.find(R"("info":{"map_load_time":{"sec":6,"nsec":0},"resolution":0.5,"width":2,"height":1,)"),
            std::string::npos)
      << grid;
  EXPECT_NE(grid.find(R"("data":[-1,100]})"), std::string::npos) << grid;
  EXPECT_NE(to_json(test::range_msg()).find(R"("radiation_type":1,)"), std::string::npos);
}

TEST(JsonSerialize, StringsAreEscapedAndNumbersShortest) {
  Contacts c = test::contacts();
  c.header.frame_id = "a\"b\\c\nd\x01";
  c.touching = {"\t"};
  EXPECT_EQ(to_json(c), R"({"header":{"stamp":{"sec":1,"nsec":0},"frame_id":"a\"b\\c\nd\u0001"},"touching":["\t"]})");
  LaserScan s;
  s.angle_min = 0.1f;  // the float nearest 0.1 prints as 0.1, not 0.100000001490116
  s.ranges = {-std::numeric_limits<float>::infinity(), std::nanf("")};
  const std::string j = to_json(s);
  EXPECT_NE(j.find(R"("angle_min":0.1,)"), std::string::npos) << j;
  EXPECT_NE(j.find(R"("ranges":[null,null])"), std::string::npos) << j;
  JointState js;
  js.position = {0.1, 1e300, -2.5e-8};
  const std::string k = to_json(js);
  EXPECT_NE(k.find(R"("position":[0.1,1e+300,-2.5e-08])"), std::string::npos) << k;
}

// a structural check of a value against our schemas: type, properties, required, items and
// their counts, base64 strings. Numbers may be null: non-finite floats are written as null.
void expect_valid(const Json& schema, const Json& v, const std::string& path) {
  const std::string type = schema.at("type");
  if (type == "object") {
    ASSERT_TRUE(v.is_object()) << path;
    for (const auto& r : schema.at("required")) EXPECT_TRUE(v.contains(r.get<std::string>())) << path << "." << r;
    for (const auto& [key, value] : v.items()) {
      ASSERT_TRUE(schema.at("properties").contains(key)) << path << "." << key << " is not in the schema";
      expect_valid(schema.at("properties").at(key), value, path + "." + key);
    }
  } else if (type == "array") {
    ASSERT_TRUE(v.is_array()) << path;
    if (schema.contains("minItems")) {
      EXPECT_GE(v.size(), schema.at("minItems").get<std::size_t>()) << path;
    }
    if (schema.contains("maxItems")) {
      EXPECT_LE(v.size(), schema.at("maxItems").get<std::size_t>()) << path;
    }
    for (std::size_t i = 0; i < v.size(); ++i) expect_valid(schema.at("items"), v[i], path + "[" + std::to_string(i) + "]");
  } else if (type == "string") {
    ASSERT_TRUE(v.is_string()) << path;
    if (schema.value("contentEncoding", "") == "base64") {
      const std::string s = v;
      EXPECT_EQ(s.size() % 4, 0u) << path;
      EXPECT_EQ(s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/="), std::string::npos) << path;
    }
  } else if (type == "number") {
    EXPECT_TRUE(v.is_number() || v.is_null()) << path << " = " << v;
  } else if (type == "integer") {
    EXPECT_TRUE(v.is_number_integer()) << path << " = " << v;
  } else if (type == "boolean") {
    EXPECT_TRUE(v.is_boolean()) << path;
  } else {
    ADD_FAILURE() << path << ": unexpected schema type " << type;
  }
}

// from_json reads what to_json writes: every sample type reads back to the same JSON and, where
// it has no non-finite value (JSON's null cannot tell inf from NaN), to the same CDR bytes
TEST(JsonRead, EveryTypeRoundTripsThroughToJson) {
  for (const Message& m : test::all_samples()) {
    const TypeSupport& t = type_of(m);
    const std::string text = to_json(m);
    const Message back = from_json(t, text);
    EXPECT_EQ(to_json(back), text) << t.ros1_name;
    if (text.find("null") != std::string::npos) continue;
    std::vector<std::uint8_t> a, b;
    to_cdr(m, a);
    to_cdr(back, b);
    EXPECT_EQ(a, b) << t.ros1_name << ": " << text;
  }
}

TEST(JsonRead, PartialMessagesKeepDefaultsAndRos2NamesAreTaken) {
  // a report as a Foxglove publish panel sends it: no header stamp, no orientation
  const Message m =
      from_json(*find_type("geometry_msgs/PoseStamped"), R"({"header":{"frame_id":"map"},"pose":{"position":{"x":1.5,"y":-2}}})");
  const auto& p = std::get<PoseStamped>(m);
  EXPECT_EQ(p.header.frame_id, "map");
  EXPECT_EQ(p.header.stamp.ns, 0);
  EXPECT_EQ(p.pose.p, Vec3(1.5, -2, 0));
  EXPECT_EQ(p.pose.q.w(), 1.0);  // the default, identity
  // ROS 2's nanosec, and ROS 1's seq (ignored)
  const auto s = std::get<PoseStamped>(from_json(*find_type("geometry_msgs/msg/PoseStamped"),
                                                 R"({"header":{"seq":7,"stamp":{"sec":3,"nanosec":250000000},"frame_id":""}})"));
  EXPECT_EQ(s.header.stamp.ns, 3'250'000'000);
  // CameraInfo's D/K/R/P are d/k/r/p in ROS 2
  const auto c = std::get<CameraInfo>(from_json(*find_type("sensor_msgs/CameraInfo"), R"({"k":[1,0,2,0,1,3,0,0,1]})"));
  EXPECT_EQ(c.k[2], 2.0);
  EXPECT_EQ(c.k[5], 3.0);
  // uint8[] as base64 or as numbers; int8[] as numbers
  EXPECT_EQ(std::get<Image>(from_json(*find_type("sensor_msgs/Image"), R"({"data":"AQID"})")).data, (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(std::get<Image>(from_json(*find_type("sensor_msgs/Image"), R"({"data":[1,2,255]})")).data,
            (std::vector<std::uint8_t>{1, 2, 255}));
  EXPECT_EQ(std::get<OccupancyGrid>(from_json(*find_type("nav_msgs/OccupancyGrid"), R"({"data":[-1,0,100]})")).data,
            (std::vector<std::int8_t>{-1, 0, 100}));
}

TEST(JsonRead, BadInputNamesTheFieldAndWhatWasExpected) {
  const auto error = [](const char* type, const char* text) {
    try {
      from_json(*find_type(type), text);
    } catch (const Error& e) {
      return e.message();
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error("geometry_msgs/Twist", "{"), "geometry_msgs/Twist: not valid JSON at byte 2 of 1");
  EXPECT_EQ(error("geometry_msgs/Twist", R"({"linear":{"x":4e999}})"), "geometry_msgs/Twist: not valid JSON: a number out of range");
  EXPECT_EQ(error("geometry_msgs/Twist", "[1]"), "geometry_msgs/Twist: expected an object, got [1]");
  EXPECT_EQ(error("geometry_msgs/Twist", R"({"linear":{"x":"fast"}})"), "geometry_msgs/Twist: linear.x: expected a number, got \"fast\"");
  EXPECT_EQ(error("geometry_msgs/Twist", R"({"linear":[1,2,3]})"), "geometry_msgs/Twist: linear: expected an object, got [1,2,3]");
  EXPECT_EQ(error("geometry_msgs/Twist", R"({"linear":{"x":1,"yy":2}})"), "geometry_msgs/Twist: linear.yy: no such field");
  EXPECT_EQ(error("geometry_msgs/PoseStamped", R"({"pose":{},"extra":1})"), "geometry_msgs/PoseStamped: extra: no such field");
  EXPECT_EQ(error("std_msgs/String", R"({"data":5})"), "std_msgs/String: data: expected a string, got 5");
  EXPECT_EQ(error("nav_msgs/OccupancyGrid", R"({"data":[1,200]})"),
            "nav_msgs/OccupancyGrid: data[1]: expected an integer from -128 to 127, got 200");
  EXPECT_EQ(error("nav_msgs/OccupancyGrid", R"({"info":{"width":-1}})"),
            "nav_msgs/OccupancyGrid: info.width: expected an integer from 0 to 4294967295, got -1");
  EXPECT_EQ(error("nav_msgs/OccupancyGrid", R"({"info":{"width":2.5}})"),
            "nav_msgs/OccupancyGrid: info.width: expected an integer, got 2.5");
  EXPECT_EQ(error("sensor_msgs/Image", R"({"data":"AQI"})"), "sensor_msgs/Image: data: a string here must be base64 (RFC 4648, padded)");
  EXPECT_EQ(error("sensor_msgs/CameraInfo", R"({"K":[1,2]})"), "sensor_msgs/CameraInfo: K: expected an array of 9 numbers, got [1,2]");
  EXPECT_EQ(error("tf2_msgs/TFMessage", R"({"transforms":[{},5]})"), "tf2_msgs/TFMessage: transforms[1]: expected an object, got 5");
  EXPECT_EQ(error("geometry_msgs/PoseStamped", R"({"header":{"stamp":{"sec":1,"nsec":1000000000}}})"),
            "geometry_msgs/PoseStamped: header.stamp.nsec: expected fewer than 1e9 nanoseconds, got 1000000000");
  EXPECT_EQ(error("sensor_msgs/Range", R"({"range":true})"), "sensor_msgs/Range: range: expected a number, got true");
}

TEST(JsonSchema, EveryTypesJsonMatchesItsSchema) {
  std::vector<Message> messages = test::all_samples();
  LaserScan s = test::laser_scan();
  s.ranges.push_back(std::nanf(""));
  messages.push_back(s);
  messages.push_back(TFMessage{});
  for (const Message& m : messages) {
    const TypeSupport& t = type_of(m);
    const Json schema = Json::parse(t.json_schema);
    EXPECT_EQ(schema.at("$schema"), "http://json-schema.org/draft-07/schema#");
    EXPECT_EQ(schema.at("title"), t.ros1_name);
    const Json value = Json::parse(to_json(m));
    expect_valid(schema, value, t.ros1_name);
    // every property of the schema is required and written
    EXPECT_EQ(schema.at("required").size(), schema.at("properties").size()) << t.ros1_name;
  }
}

TEST(JsonSchema, UsesOnlyWhatFoxgloveReads) {
  // Foxglove's JSON Schema reader takes one type name per property, objects with properties,
  // arrays with items, and "contentEncoding": "base64" strings for bytes
  const Json image = Json::parse(find_type("sensor_msgs/Image")->json_schema);
  EXPECT_EQ(image.at("properties").at("data"), Json::parse(R"({"type":"string","contentEncoding":"base64"})"));
  const Json cam = Json::parse(find_type("sensor_msgs/CameraInfo")->json_schema);
  EXPECT_EQ(cam.at("properties").at("K"),
            Json::parse(R"({"type":"array","items":{"type":"number"},"minItems":9,"maxItems":9})"));
  EXPECT_EQ(cam.at("properties").at("header").at("properties").at("stamp").at("required"), Json::parse(R"(["sec","nsec"])"));
}

}  // namespace
}  // namespace rescuesim::msg
