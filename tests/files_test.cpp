// The crash-safe writer (encoder/io/files): temporaries are created exclusively beside the
// output and never through a link, outputs that are links or special files are refused,
// and a SIGTERM during a write removes the temporary and the registered staging folder.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "encoder/io/signal_cleanup.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

namespace fs = std::filesystem;

size_t entries(const TempDir& dir) {
  size_t n = 0;
  for (auto it = fs::directory_iterator(dir.path); it != fs::directory_iterator(); ++it) ++n;
  return n;
}

TEST(Files, WritesReplaceRegularFilesAndLeaveNoTemporary) {
  TempDir dir;
  std::string err;
  ASSERT_TRUE(write_file_atomic(dir / "a.bin", "first", 5, &err)) << err;
  ASSERT_TRUE(write_file_atomic(dir / "a.bin", "second", 6, &err)) << err;
  EXPECT_EQ(file_text(dir / "a.bin"), "second");
  EXPECT_EQ(entries(dir), 1u);
}

TEST(Files, LinksAndSpecialFilesAtTheOutputAreRefused) {
  TempDir dir;
  std::ofstream(dir / "victim.txt") << "precious";
  fs::create_symlink(dir / "victim.txt", dir / "link.bin");
  ASSERT_EQ(mkfifo((dir / "fifo.bin").c_str(), 0644), 0);
  fs::create_directory(dir / "folder.bin");
  std::string err;
  for (const char* name : {"link.bin", "fifo.bin", "folder.bin"}) {
    EXPECT_FALSE(check_output_path(dir / name, true, &err)) << name;
    EXPECT_FALSE(write_file_atomic(dir / name, "x", 1, &err)) << name;
    EXPECT_NE(err.find(name), std::string::npos) << err;
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.bin"));
  EXPECT_TRUE(fs::is_fifo(dir / "fifo.bin"));
  EXPECT_EQ(file_text(dir / "victim.txt"), "precious");
  EXPECT_EQ(entries(dir), 4u);  // no temporary left
  EXPECT_TRUE(check_output_path(dir / "absent.bin", false, &err)) << err;
}

TEST(Files, SameFileIsFoundThroughLinks) {
  TempDir dir;
  std::ofstream(dir / "a.obj") << "v 0 0 0\n";
  fs::create_symlink(dir / "a.obj", dir / "b.obj");
  EXPECT_TRUE(is_one_of(dir / "b.obj", {dir / "x.obj", dir / "a.obj"}));
  EXPECT_FALSE(is_one_of(dir / "x.obj", {dir / "a.obj"}));
}

// Waits until `ready` holds (20 s at most), sends SIGTERM to the child, and expects it to
// have held and the child to die of the signal.
template <class Ready>
void expect_terminated_when(pid_t child, Ready ready) {
  bool seen = false;
  const auto start = std::chrono::steady_clock::now();
  while (!seen && std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
    seen = ready();
    if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  kill(child, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(seen);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
}

// A child writes a large file; the parent sends SIGTERM as soon as the temporary appears.
// The child dies of the signal and the folder is left empty.
TEST(Files, TermSignalDuringAWriteRemovesTheTemporary) {
  TempDir dir;
  const std::string out = dir / "big.bin";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_temporary_on_signal();
    std::vector<char> data(size_t(1) << 28, 'x');  // long enough to write that the signal lands first
    for (;;) write_file_atomic(out, data.data(), data.size(), nullptr);
  }
  expect_terminated_when(child, [&] { return entries(dir) > 0; });
  EXPECT_EQ(entries(dir), 0u);
}

// A child fills a registered staging folder with files, one written at a time; the parent
// sends SIGTERM once a few are there. The folder goes with its files, finished or not.
TEST(Files, TermSignalRemovesTheStagingFolderAndItsFiles) {
  TempDir dir;
  const std::string staging = dir / "staging";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_temporary_on_signal();
    fs::create_directory(staging);
    set_temporary_folder(staging);
    std::vector<char> data(size_t(1) << 20, 'x');
    for (int i = 0;; ++i) write_file_atomic(staging + "/f" + std::to_string(i), data.data(), data.size(), nullptr);
  }
  expect_terminated_when(child, [&] {
    std::error_code ec;
    size_t n = 0;
    for (auto it = fs::directory_iterator(staging, ec); !ec && it != fs::directory_iterator(); ++it) ++n;
    return n >= 3;
  });
  EXPECT_EQ(entries(dir), 0u);
}

}  // namespace
}  // namespace dcurve::test
