#include "output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace ibs::cli {

namespace {

std::filesystem::path temp_name(const std::filesystem::path& final_path) {
  return final_path.string() + ".ibs-partial-" + std::to_string(::getpid());
}

}  // namespace

OutputFiles::~OutputFiles() {
  if (committed_) return;
  std::error_code ec;
  for (File& f : files_) {
    f.stream.reset();
    if (!f.temp_path.empty()) std::filesystem::remove(f.temp_path, ec);
  }
  // Directories made for the outputs go again, deepest first, as far as they are empty.
  for (auto it = made_dirs_.rbegin(); it != made_dirs_.rend(); ++it) {
    if (std::filesystem::is_empty(*it, ec)) std::filesystem::remove(*it, ec);
  }
}

bool OutputFiles::make_directory(const std::filesystem::path& dir, std::string& error) {
  std::error_code ec;
  // Remember every level that does not exist yet, to remove it again on failure.
  std::vector<std::filesystem::path> missing;
  for (std::filesystem::path p = std::filesystem::absolute(dir, ec); !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    error = dir.string() + ": cannot create the directory" + (ec ? ": " + ec.message() : "");
    return false;
  }
  made_dirs_.insert(made_dirs_.end(), missing.rbegin(), missing.rend());
  return true;
}

bool OutputFiles::take_stdout(std::string& error) {
  if (stdout_used_) {
    error = "-: standard output is given for two outputs; nothing was written";
    return false;
  }
  stdout_used_ = true;
  return true;
}

std::ostream* OutputFiles::open(const std::filesystem::path& final_path, std::string& error) {
  if (final_path == "-") {
    if (!take_stdout(error)) return nullptr;
    File f;
    f.final_path = final_path;
    f.target = final_path;
    // Appended to, never truncated: a file the shell redirected stdout to is written from where
    // it stands, as a plain write(1, ...) would.
    f.stream = std::make_unique<std::ofstream>("/dev/stdout", std::ios::binary | std::ios::app);
    if (!*f.stream) {
      error = "-: cannot write to standard output: " + std::string(std::strerror(errno));
      return nullptr;
    }
    files_.push_back(std::move(f));
    return files_.back().stream.get();
  }
  if (!place(final_path, error)) return nullptr;
  File& f = files_.back();
  f.stream = std::make_unique<std::ofstream>(f.temp_path.empty() ? f.target : f.temp_path,
                                             f.temp_path.empty() ? std::ios::binary : std::ios::binary | std::ios::trunc);
  if (!*f.stream) {
    error = final_path.string() + ": cannot create the file: " + std::strerror(errno);
    files_.pop_back();
    return nullptr;
  }
  return f.stream.get();
}

std::optional<std::filesystem::path> OutputFiles::reserve(const std::filesystem::path& final_path, std::string& error) {
  if (final_path == "-") {  // libpcap's pcap_dump_open() takes "-" for standard output itself
    if (!take_stdout(error)) return std::nullopt;
    return final_path;
  }
  if (!place(final_path, error)) return std::nullopt;
  const File& f = files_.back();
  return f.temp_path.empty() ? f.target : f.temp_path;
}

bool OutputFiles::place(const std::filesystem::path& final_path, std::string& error) {
  std::error_code ec;
  File f;
  f.final_path = final_path;
  // A symbolic link is followed: its target is what gets written (weakly_canonical resolves the
  // links of the part that exists).
  f.target = std::filesystem::weakly_canonical(std::filesystem::absolute(final_path, ec), ec);
  if (ec) f.target = std::filesystem::absolute(final_path).lexically_normal();
  for (const File& other : files_) {
    if (other.target == f.target) {
      error = final_path.string() + ": the same file is given for two outputs (" + other.final_path.string() +
              "); nothing was written";
      return false;
    }
  }
  // The directory it goes into must be there (make_directory() makes --trace's): a writer that
  // opens by name would otherwise report its temporary's name.
  if (!std::filesystem::is_directory(f.target.parent_path(), ec)) {
    error = final_path.string() + ": cannot create the file: " + std::strerror(ENOENT) + " (no directory " +
            f.target.parent_path().string() + ")";
    return false;
  }
  const std::filesystem::file_status st = std::filesystem::status(f.target, ec);
  if (std::filesystem::is_directory(st)) {
    error = final_path.string() + ": is a directory; an output is written to a file";
    return false;
  }
  const bool special = std::filesystem::exists(st) && !std::filesystem::is_regular_file(st);
  if (special) {
    // A FIFO or a device is written through, never replaced. A FIFO without a reader would block
    // the command: it is refused at once.
    if (std::filesystem::is_fifo(st)) {
      const int fd = ::open(f.target.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
      if (fd < 0) {
        error = final_path.string() + (errno == ENXIO ? std::string(": a FIFO that no process reads")
                                                      : ": cannot open the FIFO: " + std::string(std::strerror(errno)));
        return false;
      }
      ::close(fd);
    }
  } else {
    f.temp_path = temp_name(f.target);
  }
  files_.push_back(std::move(f));
  return true;
}

bool OutputFiles::write(const std::filesystem::path& final_path, const std::string& text, std::string& error) {
  std::ostream* out = open(final_path, error);
  if (out == nullptr) return false;
  out->write(text.data(), static_cast<std::streamsize>(text.size()));
  out->flush();
  if (!*out) {
    error = final_path.string() + ": cannot write the file (disk full?)";
    return false;
  }
  return true;
}

bool OutputFiles::commit(std::string& error) {
  for (File& f : files_) {
    if (!f.stream) continue;  // reserve(): its writer has closed it
    f.stream->flush();
    f.stream->close();
    if (f.stream->fail()) {
      error = f.final_path.string() + ": cannot write the file (disk full?)";
      return false;
    }
  }
  // Every final name must still take a file before the first one is renamed: a directory that
  // appeared there during the run fails the whole commit, not the half of it.
  for (const File& f : files_) {
    std::error_code ec;
    if (!f.temp_path.empty() && std::filesystem::is_directory(f.target, ec)) {
      error = f.final_path.string() + ": is a directory now; nothing was renamed into place";
      return false;
    }
  }
  for (File& f : files_) {
    if (f.temp_path.empty()) {  // written through in place
      f.renamed = true;
      continue;
    }
    std::error_code ec;
    std::filesystem::rename(f.temp_path, f.target, ec);
    if (ec) {
      error = f.final_path.string() + ": cannot rename the written file into place: " + ec.message();
      // What was renamed already is complete; the rest is removed.
      return false;
    }
    f.renamed = true;
  }
  committed_ = true;
  return true;
}

}  // namespace ibs::cli
