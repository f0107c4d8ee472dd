#pragma once
/// A batch folder's `results.jsonl`: one TrialRecord per line, appended with O_APPEND and an
/// fsync per line, so a killed batch loses at most the trials still running, never a recorded
/// one. Reading it back tells which trials are done; corrupt lines (a torn last line, a line
/// edited by hand) are reported, moved aside to `results.rejected.jsonl`, and their trials run
/// again. A lock file keeps two batches from writing one folder at once.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "batch/batch_record.h"

namespace rescuesim {

/// What reading a results file found.
struct LoadedResults {
  std::map<int, TrialRecord> records;   ///< by trial: the first valid line of each
  std::vector<std::string> notices;     ///< one per corrupt or duplicate line: "results.jsonl:7: ..."
  std::vector<std::string> rejected;    ///< the corrupt lines themselves
  int duplicates = 0;                   ///< valid lines repeating a trial already read
};

/// Parses the text of a results file (`name` is used in notices).
LoadedResults parse_results(const std::string& text, const std::string& name);

/// Throws Error unless every record belongs to batch `fingerprint` with base seed `base_seed`
/// (trial i with seed base_seed + i): resuming must not mix in trials of another batch.
void check_same_batch(const LoadedResults& results, const std::filesystem::path& file, const std::string& fingerprint,
                      std::uint64_t base_seed);

/// A batch folder's results file, open for appending, locked against other batches.
class ResultsFile {
 public:
  /// Creates `dir` if needed and takes its lock; throws Error when another process holds it.
  explicit ResultsFile(const std::filesystem::path& dir);
  ~ResultsFile();
  ResultsFile(const ResultsFile&) = delete;
  ResultsFile& operator=(const ResultsFile&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path path() const { return dir_ / "results.jsonl"; }

  /// Reads the file. When it has corrupt lines, they are appended to results.rejected.jsonl and
  /// the file is rewritten without them and without repeated trials (atomically), so later
  /// appends start on a clean line.
  LoadedResults load();
  /// Replaces the whole file with these records, in trial order (atomically).
  void rewrite(const std::map<int, TrialRecord>& records);
  /// Appends one record as a single write, then fsyncs. Throws Error when the disk refuses.
  void append(const TrialRecord& record);

 private:
  void release_hold();

  std::filesystem::path dir_;
  std::string hold_;  // this process's claim on the folder ("" when none)
  int lock_fd_ = -1;
  int fd_ = -1;
};

/// Merges the results of several batch folders (shards, or machines) into `out`, which may
/// already hold results of its own: the first record of each trial wins. Throws Error when the
/// folders hold different batches or give one trial different seeds. Returns notices (corrupt
/// lines skipped, duplicates, duplicates whose outcomes differ).
std::vector<std::string> merge_results(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out,
                                       std::map<int, TrialRecord>* merged = nullptr);

}  // namespace rescuesim
