#include "batch/batch_results.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "batch/batch_trial.h"

namespace rescuesim {

namespace fs = std::filesystem;

namespace {

// POSIX record locks keep other processes out but not this one: folders held open here are
// listed too, so two ResultsFile objects (two Python batches, say) cannot share a folder
std::mutex g_held_mutex;
std::set<std::string> g_held;

// the folder and this process's id: a forked child does not inherit its parent's holds
std::string held_key(const fs::path& dir) {
  std::error_code ec;
  const fs::path p = fs::canonical(dir, ec);
  return std::to_string(::getpid()) + ":" + (ec ? fs::absolute(dir).lexically_normal().string() : p.string());
}

}  // namespace

LoadedResults parse_results(const std::string& text, const std::string& name) {
  LoadedResults out;
  std::map<int, int> line_of;  // trial -> line it was first read from
  std::size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    ++line_no;
    const std::size_t end = text.find('\n', pos);
    const bool complete = end != std::string::npos;
    const std::string line = text.substr(pos, complete ? end - pos : std::string::npos);
    pos = complete ? end + 1 : text.size();
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = name + ":" + std::to_string(line_no) + ": ";
    if (!complete) {
      // a line without its newline was cut short while being written
      out.notices.push_back(where + "incomplete last line (the batch was killed while writing it); its trial runs again");
      out.rejected.push_back(line);
      continue;
    }
    try {
      TrialRecord r = parse_trial_line(line);
      const auto [it, fresh] = line_of.emplace(r.trial, line_no);
      if (!fresh) {
        ++out.duplicates;
        out.notices.push_back(where + "trial " + std::to_string(r.trial) + " again (first on line " + std::to_string(it->second) +
                              "); keeping the first");
        continue;
      }
      out.records.emplace(r.trial, std::move(r));
    } catch (const Error& e) {
      out.notices.push_back(where + "corrupt line: " + e.message() + "; its trial runs again");
      out.rejected.push_back(line);
    }
  }
  return out;
}

void check_same_batch(const LoadedResults& results, const fs::path& file, const std::string& fingerprint, std::uint64_t base_seed) {
  for (const auto& [trial, r] : results.records) {
    if (r.batch != fingerprint) {
      throw Error({file.string(), 0, "trial " + std::to_string(trial)},
                  "recorded by another batch (" + r.batch + ", this one is " + fingerprint +
                      "): the scenario or the trial options changed; use another --out folder");
    }
    if (r.seed != trial_seed(base_seed, trial)) {
      throw Error({file.string(), 0, "trial " + std::to_string(trial)},
                  "ran with seed " + std::to_string(r.seed) + ", but this batch gives it seed " +
                      std::to_string(trial_seed(base_seed, trial)) + " (base seed " +
                      std::to_string(r.seed - static_cast<std::uint64_t>(trial)) + " then, " + std::to_string(base_seed) +
                      " now); use the same --seed or another --out folder");
    }
  }
}

ResultsFile::ResultsFile(const fs::path& dir) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw Error({dir_.string(), 0, ""}, "cannot create the batch folder: " + ec.message());
  {
    std::lock_guard guard(g_held_mutex);
    hold_ = held_key(dir_);
    if (!g_held.insert(hold_).second) {
      hold_.clear();
      throw Error({dir_.string(), 0, ""}, "this process already has this batch folder open; close it first or use another --out");
    }
  }
  const fs::path lock = dir_ / ".lock";
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) {
    const int err = errno;
    release_hold();
    throw Error({lock.string(), 0, ""}, std::string("cannot open the lock file: ") + std::strerror(err));
  }
  // a POSIX record lock belongs to this process only: child processes running trials do not
  // inherit it, and it goes away with the process however it ends
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  if (::fcntl(lock_fd_, F_SETLK, &fl) != 0) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    release_hold();
    throw Error({dir_.string(), 0, ""},
                "another batch is writing this folder (it holds " + lock.string() + "); wait for it or use another --out");
  }
}

ResultsFile::~ResultsFile() {
  if (fd_ >= 0) ::close(fd_);
  if (lock_fd_ >= 0) ::close(lock_fd_);
  release_hold();
}

void ResultsFile::release_hold() {
  std::lock_guard guard(g_held_mutex);
  if (!hold_.empty()) g_held.erase(hold_);
  hold_.clear();
}

LoadedResults ResultsFile::load() {
  std::error_code ec;
  if (!fs::exists(path(), ec)) return {};
  LoadedResults r = parse_results(read_file(path()), "results.jsonl");
  if (!r.rejected.empty()) {
    // keep the corrupt lines for inspection
    std::string rejected;
    const fs::path aside = dir_ / "results.rejected.jsonl";
    if (fs::exists(aside, ec)) rejected = read_file(aside);
    for (const auto& line : r.rejected) rejected += line + "\n";
    write_file_atomic(aside, rejected);
  }
  // drop corrupt and repeated lines, so the file holds one good line per trial again
  if (!r.rejected.empty() || r.duplicates > 0) rewrite(r.records);
  return r;
}

void ResultsFile::rewrite(const std::map<int, TrialRecord>& records) {
  std::string text;
  for (const auto& [trial, rec] : records) text += to_json_line(rec);
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  write_file_atomic(path(), text);
}

void ResultsFile::append(const TrialRecord& record) {
  if (fd_ < 0) {
    fd_ = ::open(path().c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error({path().string(), 0, ""}, std::string("cannot open for appending: ") + std::strerror(errno));
  }
  const std::string line = to_json_line(record);
  // one write of the whole line: O_APPEND places it at the end in one piece
  const char* p = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error({path().string(), 0, ""}, std::string("cannot append a result: ") + std::strerror(errno));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd_) != 0) throw Error({path().string(), 0, ""}, std::string("cannot flush a result to disk: ") + std::strerror(errno));
}

std::vector<std::string> merge_results(const std::vector<fs::path>& dirs, const fs::path& out, std::map<int, TrialRecord>* merged) {
  ResultsFile target(out);
  LoadedResults all = target.load();
  std::vector<std::string> notices = all.notices;
  std::string fingerprint;
  std::uint64_t base = 0;
  bool have_base = false;
  fs::path first_source = out / "results.jsonl";
  const auto check = [&](const TrialRecord& r, const fs::path& from) {
    if (fingerprint.empty()) {
      fingerprint = r.batch;
      first_source = from;
    }
    if (r.batch != fingerprint) {
      throw Error({from.string(), 0, "trial " + std::to_string(r.trial)},
                  "belongs to batch " + r.batch + " but " + first_source.string() + " holds batch " + fingerprint +
                      ": only shards of one batch (same scenario and options) can be merged");
    }
    const std::uint64_t b = r.seed - static_cast<std::uint64_t>(r.trial);
    if (!have_base) {
      base = b;
      have_base = true;
    } else if (b != base) {
      throw Error(
          {from.string(), 0, "trial " + std::to_string(r.trial)},
          "ran with base seed " + std::to_string(b) + ", other folders with " + std::to_string(base) + ": these are different batches");
    }
  };
  for (const auto& [trial, r] : all.records) check(r, out / "results.jsonl");
  for (const auto& dir : dirs) {
    const fs::path file = dir / "results.jsonl";
    std::error_code ec;
    if (fs::equivalent(dir, out, ec)) continue;
    if (!fs::exists(file, ec)) throw Error({file.string(), 0, ""}, "no results here (is this a batch folder?)");
    LoadedResults part = parse_results(read_file(file), file.string());
    notices.insert(notices.end(), part.notices.begin(), part.notices.end());
    for (auto& [trial, r] : part.records) {
      check(r, file);
      const auto it = all.records.find(trial);
      if (it == all.records.end()) {
        all.records.emplace(trial, std::move(r));
      } else if (!same_outcome(it->second, r)) {
        notices.push_back(file.string() + ": trial " + std::to_string(trial) +
                          " has a different outcome than the copy already merged; keeping the first");
      }
    }
  }
  target.rewrite(all.records);
  if (merged) *merged = all.records;
  return notices;
}

}  // namespace rescuesim
