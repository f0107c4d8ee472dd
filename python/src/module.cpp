// The `rescuesim._rescuesim` extension: scenarios, environments (single and vectorised) with
// observations as numpy views of the environments' own buffers, and the batch functions
// (bind_batch.cpp). The Python package (python/rescuesim) builds the friendly API on top.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>

#include "bindings.h"
#include "core/error.h"
#include "core/parallel.h"
#include "env_core.h"
#include "robots/rescue_robot.h"
#include "batch/batch_trial.h"
#include "vector_env_core.h"

namespace py = pybind11;

namespace rescuesim::python {

namespace {

/// A numpy array over `bytes` of field `f` at `data`, leading dimensions `lead` prepended; it
/// keeps `owner` alive (arr.base is owner) and is read-only.
py::array view(const ObsField& f, std::uint8_t* data, const std::vector<std::size_t>& lead, py::handle owner) {
  std::vector<py::ssize_t> shape, strides;
  for (std::size_t s : lead) shape.push_back(static_cast<py::ssize_t>(s));
  for (std::size_t s : f.shape) shape.push_back(static_cast<py::ssize_t>(s));
  strides.assign(shape.size(), 0);
  py::ssize_t stride = static_cast<py::ssize_t>(f.item);
  for (std::size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  py::array a(py::dtype(f.dtype), shape, strides, data, owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

py::dict info_dict(const EpisodeInfo& i) {
  py::dict d;
  d["seed"] = i.seed;
  d["sim_time"] = i.sim_time;
  d["steps"] = i.steps;
  d["victims_found"] = i.victims_found;
  d["victims_total"] = i.victims_total;
  d["collisions"] = i.collisions;
  d["distance"] = i.distance;
  d["coverage"] = i.coverage;
  d["pose"] = py::make_tuple(i.pose.x, i.pose.y, i.pose.yaw);
  d["new_victims"] = i.new_victims;
  d["trouble"] = i.trouble;
  return d;
}

py::list field_list(const std::vector<ObsField>& fields) {
  py::list out;
  for (const auto& f : fields) out.append(py::make_tuple(f.key, f.dtype, py::tuple(py::cast(f.shape))));
  return out;
}

}  // namespace

void bind_environments(py::module_& m) {
  py::class_<EnvOptions>(m, "EnvOptions", "Settings of an environment beyond its scenario (see rescuesim.Env).")
      .def(py::init<>())
      .def_readwrite("cameras", &EnvOptions::cameras)
      .def_readwrite("control_period", &EnvOptions::control_period)
      .def_readwrite("max_time", &EnvOptions::max_time)
      .def_readwrite("robot", &EnvOptions::robot)
      .def_readwrite("fixed_world", &EnvOptions::fixed_world)
      .def_readwrite("controller", &EnvOptions::controller)
      .def_readwrite("victim_reward", &EnvOptions::victim_reward)
      .def_readwrite("collision_penalty", &EnvOptions::collision_penalty)
      .def_readwrite("time_penalty", &EnvOptions::time_penalty)
      .def_readwrite("observations", &EnvOptions::observations);

  py::class_<EnvCore> env(m, "EnvCore", "One simulation stepped a control period at a time (use rescuesim.Env).");
  env.def(py::init([](const BatchScenario& s, const EnvOptions& o) { return std::make_unique<EnvCore>(s.scenario, builtin_models(), o); }),
          py::arg("scenario"), py::arg("options"))
      .def(
          "fields", [](const EnvCore& e) { return field_list(e.fields()); }, "[(key, dtype, shape)] of the observations")
      .def(
          "observation_arrays",
          [](py::object self) {
            EnvCore& e = self.cast<EnvCore&>();
            py::dict d;
            for (std::size_t k = 0; k < e.fields().size(); ++k) d[py::str(e.fields()[k].key)] = view(e.fields()[k], e.buffer(k), {}, self);
            return d;
          },
          "read-only numpy views of the observation buffers (overwritten in place by reset and step)")
      .def("reset", &EnvCore::reset, py::arg("seed"), py::call_guard<py::gil_scoped_release>())
      .def(
          "step",
          [](EnvCore& e, double linear, double angular) {
            StepOutcome o;
            {
              py::gil_scoped_release release;
              o = e.step(linear, angular);
            }
            return py::make_tuple(o.reward, o.terminated, o.truncated);
          },
          py::arg("linear"), py::arg("angular"), "-> (reward, terminated, truncated)")
      .def("info", [](const EnvCore& e) { return info_dict(e.info()); })
      .def_property_readonly("done", &EnvCore::done)
      .def_property_readonly("builds", &EnvCore::builds,
                             "how many times the simulation was built (a reset with the same seed restores instead)")
      .def_property_readonly("max_linear", &EnvCore::max_linear)
      .def_property_readonly("max_angular", &EnvCore::max_angular)
      .def(
          "native_steps",
          [](EnvCore& e, int n, double linear, double angular) {
            // the same steps as step(), looped in C++: the baseline for Python's overhead
            py::gil_scoped_release release;
            const auto t0 = std::chrono::steady_clock::now();
            for (int k = 0; k < n && !e.done(); ++k) e.step(linear, angular);
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          },
          py::arg("n"), py::arg("linear"), py::arg("angular"), "n steps looped in C++; returns the wall seconds they took");
  add_mission_methods(env);
  add_control_methods(env);

  py::class_<VecEnvCore>(m, "VecEnvCore", "K independent simulations stepped together (use rescuesim.VectorEnv).")
      .def(py::init([](const BatchScenario& s, const EnvOptions& o, int count, int threads) {
             return std::make_unique<VecEnvCore>(s.scenario, builtin_models(), o, count, threads);
           }),
           py::arg("scenario"), py::arg("options"), py::arg("count"), py::arg("threads") = 1)
      .def_property_readonly("size", &VecEnvCore::size)
      .def("fields", [](const VecEnvCore& v) { return field_list(v.fields()); })
      .def("observation_arrays",
           [](py::object self) {
             VecEnvCore& v = self.cast<VecEnvCore&>();
             py::dict d;
             for (std::size_t k = 0; k < v.fields().size(); ++k) {
               d[py::str(v.fields()[k].key)] = view(v.fields()[k], v.block(k), {static_cast<std::size_t>(v.size())}, self);
             }
             return d;
           })
      .def("reset", &VecEnvCore::reset, py::arg("seeds"), py::call_guard<py::gil_scoped_release>())
      .def(
          "step",
          [](VecEnvCore& v, py::array_t<double, py::array::c_style | py::array::forcecast> actions) {
            const auto n = static_cast<py::ssize_t>(v.size());
            if (actions.ndim() != 2 || actions.shape(0) != n || actions.shape(1) != 2) {
              throw Error("rescuesim.VectorEnv.step: actions must have shape (" + std::to_string(n) + ", 2)");
            }
            py::array_t<double> rewards(n);
            py::array_t<bool> terminated(n), truncated(n), was_reset(n);
            const double* a = actions.data();
            double* r = rewards.mutable_data();
            bool *te = terminated.mutable_data(), *tr = truncated.mutable_data(), *wr = was_reset.mutable_data();
            {
              py::gil_scoped_release release;
              v.step(a, r, te, tr, wr);
            }
            return py::make_tuple(rewards, terminated, truncated, was_reset);
          },
          py::arg("actions"), "-> (rewards, terminated, truncated, was_reset), arrays of size K")
      .def("info", [](VecEnvCore& v, int i) {
        if (i < 0 || i >= v.size()) throw py::index_error("environment index out of range");
        return info_dict(v.env(i).info());
      });
}

}  // namespace rescuesim::python

PYBIND11_MODULE(_rescuesim, m) {
  using namespace rescuesim;
  m.doc() = "rescuesim's C++ core: scenarios, environments and batch trials (use the rescuesim package)";
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.attr("__version__") = RESCUESIM_VERSION;
  python::bind_scenarios(m);
  python::bind_environments(m);
  python::bind_batch(m);
  m.def(
      "set_ray_threads", &set_worker_threads, py::arg("n"),
      "limit the worker threads of this process (ray casting, sensors, physics groups; 0 = all cores; 1 when running one trial per core)");
}
