// Batch trials from Python: the same trial code, JSON line format, results file and summaries
// as `rescuesim batch`, so a batch run through Python or Dask resumes and merges like one run
// by the CLI.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>

#include "bindings.h"
#include "core/error.h"
#include "robots/rescue_robot.h"
#include "batch/batch_results.h"
#include "batch/batch_summary.h"
#include "batch/batch_trial.h"

namespace py = pybind11;

namespace rescuesim::python {

namespace {

/// A results file held open from Python, with what the last load() found.
struct PyResults {
  std::unique_ptr<ResultsFile> file;
  LoadedResults loaded;
  std::filesystem::path dir;

  ResultsFile& open() {
    if (!file) throw Error("rescuesim.ResultsFile: closed");
    return *file;
  }
};

}  // namespace

void bind_batch(py::module_& m) {
  py::class_<TrialOptions>(m, "TrialOptions", "How every trial of a batch runs beyond its scenario (see docs/batch.md)")
      .def(py::init<>())
      .def_readwrite("duration", &TrialOptions::duration, "time limit per trial (s of sim time); None: the scenario's")
      .def_readwrite("controller", &TrialOptions::controller, "explorer or wall_follower for every robot; '' keeps the scenario's")
      .def_readwrite("cameras", &TrialOptions::cameras, "render the cameras")
      .def_readwrite("stop_when_all_found", &TrialOptions::stop_when_all_found, "end a trial once every victim is found");

  m.def(
      "batch_fingerprint", [](const BatchScenario& s, const TrialOptions& o) { return batch_fingerprint(s.text, o); }, py::arg("scenario"),
      py::arg("options"), "the batch's identity: trials of different batches never mix in one results file");
  m.def("trial_seed", &trial_seed, py::arg("base_seed"), py::arg("trial"), "run seed of a trial: base_seed + trial");
  m.def(
      "shard_trials",
      [](int trials, const std::string& shard) { return shard_trials(trials, shard.empty() ? Shard{} : parse_shard(shard)); },
      py::arg("trials"), py::arg("shard") = "", "the trials of shard 'K/M' (every M-th from K) among `trials`");
  m.def(
      "run_trial",
      [](const BatchScenario& s, int trial, std::uint64_t seed, const TrialOptions& o, const std::string& fingerprint) {
        py::gil_scoped_release release;
        return to_json_line(run_trial(s.scenario, builtin_models(), trial, seed, o, fingerprint));
      },
      py::arg("scenario"), py::arg("trial"), py::arg("seed"), py::arg("options"), py::arg("fingerprint"),
      "runs one trial in this process; returns its results.jsonl line (never raises for a failing trial)");
  m.def(
      "failed_trial",
      [](const BatchScenario& s, int trial, std::uint64_t seed, const std::string& fingerprint, const std::string& error) {
        return to_json_line(failed_trial(s.scenario, trial, seed, fingerprint, error));
      },
      py::arg("scenario"), py::arg("trial"), py::arg("seed"), py::arg("fingerprint"), py::arg("error"),
      "the results.jsonl line of a trial that produced none (its worker died, say)");
  m.def(
      "check_trial_line", [](const std::string& line) { (void)parse_trial_line(line); }, py::arg("line"),
      "raises rescuesim.Error saying what is wrong with a results.jsonl line");
  m.def(
      "same_outcome", [](const std::string& a, const std::string& b) { return same_outcome(parse_trial_line(a), parse_trial_line(b)); },
      py::arg("a"), py::arg("b"), "True when two result lines agree on everything but wall time, real-time factor and host");
  m.def(
      "merge_results",
      [](const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out) {
        std::map<int, TrialRecord> merged;
        auto notices = merge_results(dirs, out, &merged);
        write_batch_summary(out, merged);
        return notices;
      },
      py::arg("dirs"), py::arg("out"), "merges batch folders into `out` (as rescuesim batch merge); returns the notices");

  py::class_<PyResults>(m, "ResultsFile", "A batch folder's results.jsonl, locked against other batches while open")
      .def(py::init([](const std::filesystem::path& dir) {
             auto r = std::make_unique<PyResults>();
             r->file = std::make_unique<ResultsFile>(dir);
             r->dir = dir;
             return r;
           }),
           py::arg("dir"))
      .def_property_readonly("path", [](PyResults& r) { return r.dir / "results.jsonl"; })
      .def(
          "load",
          [](PyResults& r) {
            r.loaded = r.open().load();
            std::map<int, std::string> lines;
            for (const auto& [t, rec] : r.loaded.records) lines.emplace(t, to_json_line(rec));
            return py::make_tuple(lines, r.loaded.notices);
          },
          "-> ({trial: line}, notices); moves corrupt lines aside so their trials run again")
      .def(
          "check_same_batch",
          [](PyResults& r, const std::string& fingerprint, std::uint64_t base_seed) {
            check_same_batch(r.loaded, r.open().path(), fingerprint, base_seed);
          },
          py::arg("fingerprint"), py::arg("base_seed"), "raises rescuesim.Error when the loaded records belong to another batch")
      .def(
          "append", [](PyResults& r, const std::string& line) { r.open().append(parse_trial_line(line)); }, py::arg("line"),
          "appends one result line (validated) with one write and an fsync")
      .def(
          "rewrite",
          [](PyResults& r, const std::vector<std::string>& lines) {
            std::map<int, TrialRecord> records;
            for (const auto& l : lines) {
              TrialRecord rec = parse_trial_line(l);
              records.emplace(rec.trial, std::move(rec));
            }
            r.open().rewrite(records);
          },
          py::arg("lines"), "replaces the file with these lines (atomically, in trial order)")
      .def(
          "write_summary",
          [](PyResults& r, int jobs, int trials_run, double wall_time) {
            const LoadedResults all = r.open().load();
            write_batch_summary(r.dir, all.records, BatchRunInfo{jobs, trials_run, wall_time});
          },
          py::arg("jobs") = 0, py::arg("trials_run") = 0, py::arg("wall_time") = 0.0,
          "writes summary.json, summary.csv and summary.png from the file")
      .def("close", [](PyResults& r) { r.file.reset(); }, "releases the folder's lock")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PyResults& r, py::args) {
        r.file.reset();
        return false;
      });
}

}  // namespace rescuesim::python
