#pragma once
/// Where an installed rescuesim finds what it ships (worlds, robots, examples, docs) and how
/// a relative scenario or world argument is looked for there (issue 19).
///
/// The data folder is, in this order: $RESCUESIM_DATA_DIR when set (it must be a folder with a
/// worlds/ folder inside, else an error naming it); <folder of the executable>/../share/rescuesim
/// (an installed copy, wherever its prefix was moved); the source tree the program was built
/// from (a build folder, when that tree is still there); the install prefix compiled in.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rescuesim::app {

/// Records argv[0], the program's path when /proc/self/exe cannot be read (a chroot or
/// container without /proc): a path with a slash is taken as it is, a bare name is looked up
/// in PATH as the shell did. Call first thing in main().
void set_program_path(const char* argv0);

/// `name` in the folder of the running executable (/proc/self/exe, else argv[0] as
/// set_program_path resolved it): how `rescuesim bench` finds rescuesim-bench and how the bench
/// finds the `rescuesim` it times, installed or in a build folder. Empty when the executable's
/// folder is unknown; the file itself may not exist.
std::filesystem::path sibling_program(const std::string& name);

/// The data folder, or nullopt when none of the places exists (then `looked` lists them).
/// Throws rescuesim::Error when RESCUESIM_DATA_DIR is set to something that is not a data folder.
std::optional<std::filesystem::path> data_dir(std::vector<std::string>* looked = nullptr);

/// `arg` itself when it exists (or is empty, or absolute); else, for a relative path, the same
/// path under the data folder, or under its worlds/ folder, when there (`rescuesim run
/// worlds/team.yaml` or `rescuesim run team.yaml` from any folder). Throws rescuesim::Error
/// naming every place it looked when the file is nowhere.
std::string locate_data_file(const std::string& arg);

}  // namespace rescuesim::app

#include <CLI/CLI.hpp>

namespace rescuesim::app {

/// A CLI11 transformer that applies locate_data_file to an option's value (an error becomes
/// the option's validation message, exit code 2).
CLI::Validator data_file();

}  // namespace rescuesim::app
