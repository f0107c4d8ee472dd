// Parsing SDF with sdformat 12: model:// look-up (the resolver's folders, Gazebo's variables,
// then the built-in sun and ground_plane), model.config, version checks, and sdformat's errors
// turned into rescuesim Errors that name the file, the line and the element.
#include <sdf/Console.hh>
#include <tinyxml2.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <system_error>

#include "core/atomic_file.h"
#include "import/sdf/sdf_detail.h"

namespace rescuesim::sdf_detail {

namespace fs = std::filesystem;

namespace {

/// The models Gazebo ships and every world includes: users do not have them on disk.
const char* kSunSdf = R"(<?xml version="1.0"?>
<sdf version="1.9">
  <light type="directional" name="sun">
    <cast_shadows>true</cast_shadows>
    <pose>0 0 10 0 0 0</pose>
    <diffuse>0.8 0.8 0.8 1</diffuse>
    <specular>0.2 0.2 0.2 1</specular>
    <attenuation><range>1000</range><constant>0.9</constant><linear>0.01</linear><quadratic>0.001</quadratic></attenuation>
    <direction>-0.5 0.1 -0.9</direction>
  </light>
</sdf>
)";

const char* kGroundPlaneSdf = R"(<?xml version="1.0"?>
<sdf version="1.9">
  <model name="ground_plane">
    <static>true</static>
    <link name="link">
      <collision name="collision">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
      </collision>
      <visual name="visual">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
        <material><ambient>0.8 0.8 0.8 1</ambient><diffuse>0.8 0.8 0.8 1</diffuse></material>
      </visual>
    </link>
  </model>
</sdf>
)";

std::string model_config(const std::string& name) {
  return "<?xml version=\"1.0\"?>\n<model>\n  <name>" + name +
         "</name>\n  <version>1.0</version>\n  <sdf version=\"1.9\">model.sdf</sdf>\n</model>\n";
}

/// The folder holding the built-in models (sdformat reads includes from files only, so the texts
/// compiled in here are put on disk for it). One folder per user and text version, rewritten
/// atomically by each process that needs it: nothing piles up in /tmp, and processes running at
/// once only ever see complete files.
const fs::path& builtin_folder() {
  static fs::path folder;
  static std::once_flag once;
  std::call_once(once, [] {
    folder = fs::temp_directory_path() / ("rescuesim-sdf-builtin-v1-" + std::to_string(::getuid()));
    for (const auto& [name, text] : {std::pair{"sun", kSunSdf}, std::pair{"ground_plane", kGroundPlaneSdf}}) {
      fs::create_directories(folder / name);
      write_file_atomic(folder / name / "model.sdf", text);
      write_file_atomic(folder / name / "model.config", model_config(name));
    }
  });
  return folder;
}

bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

/// "major.minor" as a pair of numbers ({0, 0} when it is not one).
std::pair<int, int> version_of(const std::string& v) {
  int major = 0, minor = 0;
  char dot = 0;
  std::istringstream in(v);
  if (!(in >> major >> dot >> minor) || dot != '.') return {0, 0};
  return {major, minor};
}

std::string listed(const std::vector<fs::path>& paths) {
  std::string out;
  for (const auto& p : paths) out += "\n  " + p.string();
  return out.empty() ? "\n  (nowhere)" : out;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n"), t = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, t - b + 1);
}

/// True for the file name sdformat gives text parsed from memory ("<data-string>"), or none.
bool is_in_memory(const std::string& path) { return path.empty() || path == "<data-string>" || path == "data-string"; }

/// The last element of an sdformat XML path (/sdf/world[@name="w"]/include[0]/uri → include/uri).
std::string element_of_xml_path(const std::string& xml_path) {
  const std::size_t last = xml_path.rfind('/');
  if (last == std::string::npos || last == 0) return xml_path;
  const std::size_t before = xml_path.rfind('/', last - 1);
  return xml_path.substr(before == std::string::npos ? 0 : before + 1);
}

/// What the find-file callback looked at for each URI it could not find, for the message.
using Misses = std::map<std::string, std::vector<fs::path>>;

/// Resolves a URI for sdformat (its <include>s): model:// through find_model_folder, other
/// paths relative to `base`. Returns "" when nothing matches and notes where it looked.
std::string find_for_sdformat(const std::string& uri, const fs::path& base, const SdfOptions& options, Misses& misses) {
  const std::string prefix = "model://";
  if (uri.compare(0, prefix.size(), prefix) == 0) {
    const std::string rest = uri.substr(prefix.size());
    const std::size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash);
    std::vector<fs::path> tried;
    const auto folder = find_model_folder(name, options, &tried);
    if (!folder) {
      misses[uri] = tried;
      return "";
    }
    // the model's SDF file itself, chosen by model_file_of's rule rather than sdformat's
    if (slash == std::string::npos || slash + 1 == rest.size()) return model_file_of(*folder, {}).string();
    return (*folder / rest.substr(slash + 1)).string();
  }
  if (uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0) {
    misses[uri] = {};  // a Fuel URL: nothing on disk to look at
    return "";
  }
  const fs::path p = uri.compare(0, 7, "file://") == 0 ? fs::path(uri.substr(7)) : fs::path(uri);
  const fs::path full = p.is_absolute() ? p : base / p;
  if (is_dir(full) && is_file(full / "model.config")) return model_file_of(full, {}).string();
  if (is_file(full)) return full.string();
  misses[uri] = {full};
  return "";
}

/// Throws the Error for sdformat's errors: the first one's place, every message.
[[noreturn]] void throw_errors(const sdf::Errors& errors, const std::string& file, const std::string& declared, const Misses& misses) {
  const sdf::Error& first = errors.front();
  SourceRef where{first.FilePath().value_or(file), first.LineNumber().value_or(0), element_of_xml_path(first.XmlPath().value_or(""))};
  if (is_in_memory(where.file)) where.file = file;
  std::string message;
  for (const auto& e : errors) {
    message += (message.empty() ? "" : "\n") + e.Message();
    for (const auto& [uri, tried] : misses) {
      if (e.Message().find(uri) == std::string::npos) continue;
      if (uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0) {
        message += " (rescuesim does not download models from Gazebo Fuel: download it once, e.g. `gz fuel download -u " + uri +
                   "`, put the model's folder on resource_paths and include it as model://<its name>)";
      } else {
        message += " (searched" + listed(tried) + "\nadd the folder holding the model to resource_paths or GZ_SIM_RESOURCE_PATH)";
      }
    }
  }
  const auto [major, minor] = version_of(declared);
  if (major == 1 && minor > 9) {
    message += "\n(the file declares SDF ";
    message += declared;
    message += "; sdformat 12 reads SDF up to 1.9)";
  }
  throw Error(where, "sdformat could not read it: " + message);
}

}  // namespace

std::string read_text(const fs::path& file) {
  try {
    return read_file(file, std::size_t(256) << 20);
  } catch (const Error& e) {
    throw Error({file.string(), 0, ""}, "cannot read the SDF file: " + e.message());
  }
}

std::optional<fs::path> find_model_folder(const std::string& name, const SdfOptions& options, std::vector<fs::path>* tried) {
  for (const auto& c : options.resolver.model_candidates(name)) {
    if (tried) tried->push_back(c);
    if (is_dir(c) && is_file(c / "model.config")) return c;
  }
  // Gazebo's own models, last: a user's folder of the same name wins
  if (name == "sun" || name == "ground_plane") return builtin_folder() / name;
  return std::nullopt;
}

fs::path model_file_of(const fs::path& folder, const SourceRef& where) {
  // sdf::getModelFilePath does this too, but compares versions as strings ("1.10" < "1.9") and
  // prints instead of throwing: read model.config here
  const fs::path config = folder / "model.config";
  const SourceRef at{config.string(), 0, "<sdf>"};
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(config.string().c_str()) != tinyxml2::XML_SUCCESS) {
    throw Error(where.file.empty() ? at : where,
                "cannot read " + config.string() + ": " + (doc.ErrorStr() ? doc.ErrorStr() : "no such file"));
  }
  const tinyxml2::XMLElement* model = doc.RootElement();
  std::pair<int, int> best{-1, -1};
  std::pair<int, int> best_any{-1, -1};
  std::string chosen, chosen_any;
  for (const tinyxml2::XMLElement* s = model ? model->FirstChildElement("sdf") : nullptr; s; s = s->NextSiblingElement("sdf")) {
    if (!s->GetText()) continue;
    const auto v = version_of(s->Attribute("version") ? s->Attribute("version") : "");
    const std::string name = trimmed(s->GetText());
    if (v > best_any) best_any = v, chosen_any = name;
    if (v <= std::pair{1, 9} && v > best) best = v, chosen = name;
  }
  if (chosen.empty()) chosen = chosen_any;
  if (chosen.empty()) throw Error({config.string(), model ? model->GetLineNum() : 0, "<model>"}, "model.config names no <sdf> file");
  const fs::path file = folder / chosen;
  if (!is_file(file)) throw Error({config.string(), 0, "<sdf>"}, "model.config names " + chosen + ", which is not in " + folder.string());
  return file;
}

fs::path resolve_model_uri(const std::string& uri, const SdfOptions& options, const SourceRef& where) {
  Misses misses;
  const fs::path base = where.file.empty() ? fs::current_path() : fs::path(where.file).parent_path();
  const std::string found = find_for_sdformat(uri, base, options, misses);
  if (!found.empty()) return found;
  const auto& tried = misses[uri];
  throw Error(where, "cannot find model '" + uri + "': searched" + listed(tried) +
                         "\n(add the folder holding the model to resource_paths or GZ_SIM_RESOURCE_PATH)");
}

void parse_sdf(const std::string& text, const std::string& file, const SdfOptions& options, Parsed& out, Diagnostics& diagnostics) {
  // tinyxml2 first: sdformat reports malformed XML without a line, and the declared version is
  // needed before sdformat converts it away
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw Error({file, doc.ErrorLineNum(), ""}, std::string("malformed XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* top = doc.RootElement();
  if (!top || std::string(top->Name()) != "sdf") {
    const std::string name = top ? top->Name() : "";
    throw Error({file, top ? top->GetLineNum() : 0, top ? "<" + name + ">" : ""},
                "not SDF: the root element must be <sdf version=\"...\">" + std::string(name == "robot" ? " (this is URDF)" : ""));
  }
  const SourceRef at_top{file, top->GetLineNum(), "<sdf>"};
  out.declared_version = top->Attribute("version") ? top->Attribute("version") : "";
  const auto [major, minor] = version_of(out.declared_version);
  if (major < 1) throw Error(at_top, "expected a version=\"1.x\" attribute, got '" + out.declared_version + "'");
  // sdformat 12 "reads" any version, converting with nothing to convert; a new major version is
  // a different format, so it is refused rather than half-read
  if (major > 1) {
    throw Error(at_top, "declares SDF " + out.declared_version + "; sdformat 12 reads SDF up to 1.9");
  }

  // sdformat prints its errors and warnings to the terminal too (in colour); they reach the user
  // once, as the Error or warnings made here from the same messages. It still logs to
  // ~/.sdformat/sdformat.log, as it does for Gazebo.
  static std::once_flag quiet;
  std::call_once(quiet, [] { sdf::Console::Instance()->SetQuiet(true); });
  auto misses = std::make_shared<Misses>();
  const fs::path base = fs::absolute(fs::path(file)).parent_path();
  sdf::ParserConfig config;
  config.SetFindCallback([misses, base, &options](const std::string& uri) { return find_for_sdformat(uri, base, options, *misses); });
  const auto t0 = std::chrono::steady_clock::now();
  const sdf::Errors errors = out.root.LoadSdfString(text, config);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!errors.empty()) throw_errors(errors, file, out.declared_version, *misses);
  if (minor > 9) diagnostics.warn(at_top, "declares SDF " + out.declared_version + "; read as 1.9 (sdformat 12 reads SDF up to 1.9)");
}

Pose3 pose_of(const ignition::math::Pose3d& p) {
  return {Vec3(p.Pos().X(), p.Pos().Y(), p.Pos().Z()), Quat(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()).normalized()};
}

Vec3 vec_of(const ignition::math::Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }

Vec3 color_of(const ignition::math::Color& c) { return {c.R(), c.G(), c.B()}; }

std::string describe(const sdf::ElementPtr& e) {
  if (!e) return "";
  std::string out = "<" + e->GetName();
  if (e->HasAttribute("name")) out += " name=\"" + e->GetAttribute("name")->GetAsString() + "\"";
  return out + ">";
}

SourceRef where_of(const sdf::ElementPtr& e, const std::string& fallback_file, const std::string& context) {
  SourceRef s{fallback_file, 0, context};
  if (!e) return s;
  const std::string& path = e->FilePath();
  if (!is_in_memory(path)) s.file = path;
  s.line = e->LineNumber().value_or(0);
  s.element = (context.empty() ? "" : context + " ") + describe(e);
  return s;
}

Pose3 resolve(const sdf::SemanticPose& pose, const std::string& to, const SourceRef& where) {
  ignition::math::Pose3d p;
  const sdf::Errors errors = pose.Resolve(p, to);
  if (!errors.empty())
    throw Error(where, "cannot resolve the pose" + (to.empty() ? "" : " in frame '" + to + "'") + ": " + errors.front().Message());
  return pose_of(p);
}

void check_pose(const Pose3& X, double max_extent, const SourceRef& where, const std::string& what) {
  if (!X.p.allFinite() || !X.q.coeffs().allFinite()) throw Error(where, what + " is not finite");
  if (X.p.norm() > max_extent) {
    throw Error(where, what + " is " + std::to_string(X.p.norm()) + " m away, beyond the largest sane extent (" +
                           std::to_string(max_extent) + " m, SdfOptions::max_extent)");
  }
}

std::vector<std::pair<std::string, sdf::ElementPtr>> plugins_of(const sdf::ElementPtr& parent) {
  std::vector<std::pair<std::string, sdf::ElementPtr>> out;
  if (!parent || !parent->HasElement("plugin")) return out;
  for (sdf::ElementPtr p = parent->GetElement("plugin"); p; p = p->GetNextElement("plugin")) {
    out.emplace_back(p->HasAttribute("filename") ? p->GetAttribute("filename")->GetAsString() : "", p);
  }
  return out;
}

}  // namespace rescuesim::sdf_detail
