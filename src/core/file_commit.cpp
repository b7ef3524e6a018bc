#include "core/file_commit.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

// A temporary sibling name unique to this process and call; hidden so a half-made file is
// never mistaken for output.
std::string tempName(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  fs::path p(path);
  // Built with append(): GCC 12 warns falsely (-Wrestrict) on a chain of string operator+.
  std::string name(".");
  name.append(p.filename().string())
      .append(".tmp")
      .append(std::to_string(getpid()))
      .append("_")
      .append(std::to_string(counter++));
  return (p.parent_path() / name).string();
}

std::string errnoText(const char* what) {
  return std::string(what) + ": " + std::strerror(errno);
}

}  // namespace

FileCommit::~FileCommit() {
  std::error_code ec;
  for (const Staged& s : staged_) fs::remove(s.tmp, ec);
}

void FileCommit::stage(const std::string& path, const std::vector<unsigned char>& bytes) {
  stageBytes(path, bytes.data(), bytes.size());
}

void FileCommit::stage(const std::string& path, const std::string& text) {
  stageBytes(path, text.data(), text.size());
}

void FileCommit::stageBytes(const std::string& path, const void* data, size_t size) {
  fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw InputError(path, "", "output folder does not exist");
  if (fs::is_directory(path)) throw InputError(path, "", "is a folder, not a file");
  const std::string tmp = tempName(path);
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(path, "", errnoText("cannot create file"));
  std::string problem;
  const char* p = static_cast<const char*>(data);
  size_t left = size;
  while (left > 0 && problem.empty()) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      problem = errnoText(("write failed after " + std::to_string(size - left) + " of " +
                           std::to_string(size) + " bytes")
                              .c_str());
      break;
    }
    p += n;
    left -= size_t(n);
  }
  // Delayed allocation can defer "disk full" to the flush or the close: check both.
  if (problem.empty() && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS)
    problem = errnoText("flush to disk failed");
  if (::close(fd) != 0 && problem.empty()) problem = errnoText("close failed");
  if (!problem.empty()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path, "", problem);
  }
  staged_.push_back({tmp, path});
}

void FileCommit::commit() {
  for (size_t i = 0; i < staged_.size(); ++i) {
    std::error_code ec;
    fs::rename(staged_[i].tmp, staged_[i].path, ec);
    if (ec) {
      std::error_code ignored;
      for (size_t j = 0; j < i; ++j) fs::remove(staged_[j].path, ignored);
      // The destructor removes the temporaries from i on; the ones before were renamed.
      std::string path = staged_[i].path;
      staged_.erase(staged_.begin(), staged_.begin() + long(i));
      throw InputError(path, "", "cannot rename temporary file into place: " + ec.message());
    }
  }
  staged_.clear();
}

void writeFileAtomically(const std::string& path, const std::vector<unsigned char>& bytes) {
  FileCommit c;
  c.stage(path, bytes);
  c.commit();
}

}  // namespace tandem
