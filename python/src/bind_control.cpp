// The simulation-control calls of an environment (EnvCore), on the same RunControl that serves
// the ROS 2, ROS 1 and Foxglove front ends (session/run_control.h): entities, their states,
// teleports, the state hash, the features. Python steps its environment itself, so it needs no
// pause: step() is the step. See docs/python.md.

#include <array>
#include <pybind11/stl.h>

#include "bindings.h"
#include "core/error.h"
#include "env_core.h"
#include "session/session.h"

namespace py = pybind11;

namespace rescuesim::python {

namespace {

using namespace control;

RunControl& control_of(EnvCore& e) {
  if (!e.session()) throw Error("call reset() first");
  RunControl* c = e.session()->control();
  if (!c) throw Error("this environment has no control surface");
  return *c;
}

/// A Result other than OK as rescuesim.Error, with the standard's code in the message.
void check(const Result& r) {
  if (!r.is_ok()) throw Error(r.error_message + " (simulation_interfaces result " + std::to_string(r.result) + ")");
}

py::tuple vec(const Vec3& v) { return py::make_tuple(v.x(), v.y(), v.z()); }

Vec3 vec_of(const py::object& o, const char* what) {
  const auto v = o.cast<std::vector<double>>();
  if (v.size() != 3) throw Error(std::string(what) + " takes 3 numbers (x, y, z)");
  return {v[0], v[1], v[2]};
}

}  // namespace

void add_control_methods(py::class_<EnvCore>& cls) {
  cls.def(
         "entities",
         [](EnvCore& e, const std::string& filter, const std::vector<std::uint8_t>& categories) {
           EntityFilters f;
           f.filter = filter;
           f.categories = categories;
           std::vector<std::string> names;
           check(control_of(e).entities(f, names));
           return names;
         },
         py::arg("filter") = "", py::arg("categories") = std::vector<std::uint8_t>{})
      .def("entity_state",
           [](EnvCore& e, const std::string& name) {
             EntityState s;
             check(control_of(e).entity_state(name, s));
             py::dict d;
             d["position"] = vec(s.pose.p);
             d["orientation"] = py::make_tuple(s.pose.q.x(), s.pose.q.y(), s.pose.q.z(), s.pose.q.w());
             d["linear"] = vec(s.linear);
             d["angular"] = vec(s.angular);
             d["linear_acceleration"] = vec(s.linear_acc);
             d["angular_acceleration"] = vec(s.angular_acc);
             d["time"] = static_cast<double>(s.stamp_ns) * 1e-9;
             return d;
           },
           py::arg("name"))
      .def("entity_category",
           [](EnvCore& e, const std::string& name) {
             EntityInfo info;
             check(control_of(e).entity_info(name, info));
             return info.category;
           },
           py::arg("name"))
      .def(
          "set_entity_state",
          [](EnvCore& e, const std::string& name, const py::object& position, const py::object& orientation,
             const py::object& linear, const py::object& angular) {
            RunControl& c = control_of(e);
            EntityState s;
            check(c.entity_state(name, s));  // what is not given stays
            const bool set_pose = !position.is_none() || !orientation.is_none();
            const bool set_twist = !linear.is_none() || !angular.is_none();
            if (!position.is_none()) s.pose.p = vec_of(position, "position");
            if (!orientation.is_none()) {
              const auto q = orientation.cast<std::vector<double>>();
              if (q.size() != 4) throw Error("orientation takes 4 numbers (x, y, z, w)");
              s.pose.q = Quat(q[3], q[0], q[1], q[2]);
            }
            if (!linear.is_none()) s.linear = vec_of(linear, "linear");
            if (!angular.is_none()) s.angular = vec_of(angular, "angular");
            check(c.set_entity_state(name, s, set_pose, set_twist, false));
          },
          py::arg("name"), py::arg("position") = py::none(), py::arg("orientation") = py::none(), py::arg("linear") = py::none(),
          py::arg("angular") = py::none())
      .def("state_hash", [](EnvCore& e) { return control_of(e).state_hash(); })
      .def("simulator_features",
           [](EnvCore& e) {
             const SimulatorFeatures f = control_of(e).features();
             py::dict d;
             d["features"] = f.features;
             d["spawn_formats"] = f.spawn_formats;
             d["custom_info"] = f.custom_info;
             return d;
           })
      .def(
          "spawn",
          [](EnvCore& e, const std::string& name, const std::string& uri, const std::string& resource_string,
             const std::array<double, 3>& position, const std::array<double, 4>& orientation, const std::string& ns,
             bool allow_renaming) {
            SpawnRequest r;
            r.name = name;
            r.uri = uri;
            r.resource_string = resource_string;
            r.pose =
                Pose3{Vec3(position[0], position[1], position[2]), Quat(orientation[3], orientation[0], orientation[1], orientation[2])};
            r.entity_namespace = ns;
            r.allow_renaming = allow_renaming;
            std::string given;
            check(control_of(e).spawn(r, given));
            return given;
          },
          py::arg("name"), py::arg("uri"), py::arg("resource_string"), py::arg("position"), py::arg("orientation"), py::arg("namespace"),
          py::arg("allow_renaming"))
      .def("delete", [](EnvCore& e, const std::string& name) { check(control_of(e).remove(name)); }, py::arg("name"));
}

}  // namespace rescuesim::python
