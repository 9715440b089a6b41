// The files a command writes, all or nothing: each is written under a temporary name beside its
// final one, and only when every one of them has been written in full are they renamed to their
// final names. Whatever fails, no partial or half-written file is left under a final name, the
// temporaries are removed, and a directory made for the outputs is removed again if it stays empty.
//
// `-` is standard output (tshark's `-w -`): written through as the run goes, at most one output
// per command; a command whose output goes there prints its own report on standard error.
//
// An output never replaces what is not a regular file (docs/robustness.md, "Output files"): a
// symbolic link is followed (its target is written, the link stays), a FIFO or a device is written
// through in place (no temporary, no rename; a FIFO nobody reads is refused at once instead of
// blocking), a directory is refused. One file given for two outputs is refused when the second is
// opened, and a final name that became a directory during the run fails the commit before anything
// is renamed.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ibs::cli {

class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  // Makes `dir` (and its parents) if missing; false with `error` set when it cannot.
  bool make_directory(const std::filesystem::path& dir, std::string& error);
  // A stream to write `final_path` through; nullptr with `error` set when it cannot be created.
  std::ostream* open(const std::filesystem::path& final_path, std::string& error);
  // Writes `text` as `final_path`.
  bool write(const std::filesystem::path& final_path, const std::string& text, std::string& error);
  // For a writer that opens files by name (libpcap): the path to write `final_path` through --
  // its temporary, or the FIFO or device itself -- under the same rules as open(); nullopt with
  // `error` set when it cannot be. The writer must have closed it before commit().
  std::optional<std::filesystem::path> reserve(const std::filesystem::path& final_path, std::string& error);
  // Closes every stream, checks that everything was written, then renames all to their final
  // names. False with `error` (naming the file) on the first failure; nothing is renamed then.
  bool commit(std::string& error);
  // Whether an output is `-`: the command's own report then goes to standard error.
  [[nodiscard]] bool uses_stdout() const { return stdout_used_; }

 private:
  struct File {
    std::filesystem::path final_path;
    std::filesystem::path target;     // final_path with its symbolic links resolved
    std::filesystem::path temp_path;  // empty: written through in place (a FIFO, a device)
    std::unique_ptr<std::ofstream> stream;
    bool renamed = false;
  };
  // Checks `final_path` and adds its File (no stream yet); false with `error` set.
  bool place(const std::filesystem::path& final_path, std::string& error);
  // `-`: standard output, once per command; false with `error` set when it is taken already.
  bool take_stdout(std::string& error);

  std::vector<File> files_;
  std::vector<std::filesystem::path> made_dirs_;  // deepest last
  bool committed_ = false;
  bool stdout_used_ = false;
};

}  // namespace ibs::cli
