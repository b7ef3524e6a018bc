// Output files written completely or not at all. Each file's bytes go to a temporary sibling
// (every write checked to the last byte, then flushed to disk and closed, each step checked);
// only when every staged file is complete are they renamed into place. A disk that fills, a
// file-size limit or a failed encoder leaves no partial file and no temporary behind.
#pragma once
#include <string>
#include <vector>

namespace tandem {

class FileCommit {
 public:
  FileCommit() = default;
  FileCommit(const FileCommit&) = delete;
  FileCommit& operator=(const FileCommit&) = delete;
  ~FileCommit();  // removes whatever was staged but not committed

  // Writes `bytes` to a temporary file beside `path`; throws InputError naming `path` on any
  // failure (and removes that temporary; earlier staged files stay staged until destruction).
  void stage(const std::string& path, const std::vector<unsigned char>& bytes);
  void stage(const std::string& path, const std::string& text);
  // Renames every staged file into place. If a rename fails, the files this commit already
  // renamed are removed again and InputError names the failing path: all or none.
  void commit();

 private:
  struct Staged {
    std::string tmp, path;
  };
  std::vector<Staged> staged_;
  void stageBytes(const std::string& path, const void* data, size_t size);
};

// One file, committed alone.
void writeFileAtomically(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace tandem
