// Output files are complete or absent: a file-size limit (standing in for a full disk) fails
// the write with an error naming the file, and neither the file nor a temporary is left;
// several files staged together appear all or none.
#include "core/file_commit.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "test_util.h"

namespace tandem {
namespace {
namespace fs = std::filesystem;

// Lowers the soft file-size limit for one scope (SIGXFSZ ignored, so write() fails with EFBIG
// instead of killing the test), restoring both afterwards.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit r = saved_;
    r.rlim_cur = bytes;
    ok_ = setrlimit(RLIMIT_FSIZE, &r) == 0;
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_);
  }
  bool ok() const { return ok_; }

 private:
  rlimit saved_{};
  void (*old_)(int) = nullptr;
  bool ok_ = false;
};

size_t filesIn(const fs::path& dir) {
  size_t n = 0;
  for (auto& e : fs::directory_iterator(dir)) n += e.is_regular_file() ? 1 : 0;
  return n;
}

Buffer noiseImage(int w, int h) {
  Buffer img(w, h, 3);
  uint32_t x = 12345;
  for (float& v : img.data) {
    x = x * 1664525u + 1013904223u;
    v = float(x >> 8) / float(1 << 24);  // incompressible, so the PNG is large
  }
  return img;
}

TEST(FileCommit, WritesCompleteFilesAndLeavesNoTemporaries) {
  fs::path dir = test::scratchDir("file_commit_ok");
  Buffer img = noiseImage(64, 32);
  writePng((dir / "a.png").string(), img);
  writeExr((dir / "a.exr").string(), img);
  EXPECT_EQ(filesIn(dir), 2u);
  Buffer png = loadImage((dir / "a.png").string());
  Buffer exr = loadImage((dir / "a.exr").string());
  ASSERT_EQ(png.width, 64);
  ASSERT_EQ(exr.height, 32);
  for (size_t i = 0; i < img.data.size(); ++i) {
    EXPECT_NEAR(png.data[i], img.data[i], 0.5f / 255.0f + 1e-6f);
    EXPECT_EQ(exr.data[i], img.data[i]);
  }
}

TEST(FileCommit, ShortWriteFailsAndLeavesNothing) {
  fs::path dir = test::scratchDir("file_commit_short");
  const std::string path = (dir / "big.png").string();
  std::vector<unsigned char> bytes = encodePng(path, noiseImage(256, 256));  // ~190 kB
  ASSERT_GT(bytes.size(), 100000u);
  FileSizeLimit limit(16384);
  ASSERT_TRUE(limit.ok());
  try {
    writeFileAtomically(path, bytes);
    FAIL() << "a write past the file-size limit succeeded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("big.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("write failed"), std::string::npos) << e.what();
  }
  EXPECT_EQ(filesIn(dir), 0u) << "no file and no temporary";
}

TEST(FileCommit, SeveralFilesAreCommittedAllOrNone) {
  fs::path dir = test::scratchDir("file_commit_batch");
  const std::string small = (dir / "small.png").string(), big = (dir / "big.exr").string();
  Buffer tiny = noiseImage(4, 4);
  std::vector<unsigned char> bigBytes = encodeExr(big, noiseImage(128, 128));  // ~200 kB
  {
    FileSizeLimit limit(32768);
    ASSERT_TRUE(limit.ok());
    FileCommit files;
    files.stage(small, encodePng(small, tiny));  // fits
    EXPECT_THROW(files.stage(big, bigBytes), InputError);
  }  // never committed: the destructor removes the staged PNG
  EXPECT_EQ(filesIn(dir), 0u);

  FileCommit files;
  files.stage(small, encodePng(small, tiny));
  files.stage(big, bigBytes);
  EXPECT_EQ(filesIn(dir), 2u);  // two temporaries
  EXPECT_FALSE(fs::exists(small));
  files.commit();
  EXPECT_TRUE(fs::exists(small));
  EXPECT_EQ(fs::file_size(big), bigBytes.size());
  EXPECT_EQ(filesIn(dir), 2u);
}

TEST(FileCommit, FailedRenameUndoesTheOthers) {
  fs::path dir = test::scratchDir("file_commit_rename");
  const std::string first = (dir / "first.txt").string(), second = (dir / "second").string();
  FileCommit files;
  files.stage(first, std::string("one\n"));
  files.stage(second, std::string("two\n"));
  fs::create_directories(fs::path(second) / "occupied");  // a non-empty folder blocks rename
  EXPECT_THROW(files.commit(), InputError);
  EXPECT_FALSE(fs::exists(first)) << "the first file was renamed, then removed again";
  fs::remove_all(second);
}

TEST(FileCommit, RefusesMissingFolderAndFolderTargets) {
  fs::path dir = test::scratchDir("file_commit_errors");
  EXPECT_THROW(writeTextFile((dir / "nope" / "x.txt").string(), "x"), InputError);
  fs::create_directories(dir / "x.png");
  EXPECT_THROW(writePng((dir / "x.png").string(), noiseImage(2, 2)), InputError);
  EXPECT_THROW(writePng((dir / "y.png").string(), Buffer()), InputError);
}

}  // namespace
}  // namespace tandem
