// Outputs (core/output_file.h): a regular file replaced only when complete; a FIFO and a device
// written in place and never replaced (a device node made here with mknod, as root only: the
// system's /dev is never touched); a symbolic link's target written, the link kept; a pair
// written as a unit; temporaries removed on SIGTERM, and named before they exist as the one
// written; paths that can never be written refused before any work (empty, too long, a folder, an
// input of the same run).
#include "core/output_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/error.h"
#include "core/stdout_guard.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Files in `dir` other than those named: what a write left behind.
std::vector<std::string> Leftovers(const fs::path& dir, const std::vector<std::string>& keep) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (std::find(keep.begin(), keep.end(), n) == keep.end()) out.push_back(n);
  }
  return out;
}

TEST(OutputFile, ARegularFileIsReplacedOnlyWhenComplete) {
  testing::TempDir dir;
  WriteTextFile(dir / "a.txt", "old\n");
  EXPECT_THROW(WriteAtomically(dir / "a.txt",
                               [](std::FILE* f) {
                                 std::fputs("half", f);
                                 throw std::runtime_error("the writer failed");
                               }),
               std::runtime_error);
  EXPECT_EQ(Slurp(dir / "a.txt"), "old\n");
  EXPECT_TRUE(Leftovers(dir.path(), {"a.txt"}).empty());
  WriteTextFile(dir / "a.txt", "new\n");
  EXPECT_EQ(Slurp(dir / "a.txt"), "new\n");
  EXPECT_TRUE(Leftovers(dir.path(), {"a.txt"}).empty());
}

TEST(OutputFile, AFifoIsWrittenInPlaceAndStaysAFifo) {
  testing::TempDir dir;
  const std::string fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string got;
  std::thread reader([&] { got = Slurp(fifo); });
  WriteTextFile(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(got, "through the pipe\n");
  struct stat st;
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_TRUE(Leftovers(dir.path(), {"pipe"}).empty());
}

TEST(OutputFile, ADeviceIsWrittenInPlaceAndStaysADevice) {
  if (::geteuid() != 0) GTEST_SKIP() << "mknod needs root";
  testing::TempDir dir;
  const std::string dev = dir / "null";
  // The same device as /dev/null (1, 3), made here: the system's own is never touched.
  if (::mknod(dev.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "mknod refused here (a container without the capability)";
  WriteTextFile(dev, "into the void\n");
  CheckOutputPath(dev, "-o");
  struct stat st;
  ASSERT_EQ(::lstat(dev.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  EXPECT_EQ(major(st.st_rdev), 1u);
  EXPECT_TRUE(Leftovers(dir.path(), {"null"}).empty());
}

TEST(OutputFile, ASymbolicLinkKeepsItsLinkAndItsTargetIsWritten) {
  testing::TempDir dir;
  WriteTextFile(dir / "target.txt", "old\n");
  fs::create_symlink("target.txt", dir / "link.txt");
  WriteTextFile(dir / "link.txt", "new\n");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(Slurp(dir / "target.txt"), "new\n");
  EXPECT_TRUE(Leftovers(dir.path(), {"target.txt", "link.txt"}).empty());
  // A dangling link: its target is created.
  fs::create_symlink("made.txt", dir / "dangling.txt");
  WriteTextFile(dir / "dangling.txt", "made\n");
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.txt"));
  EXPECT_EQ(Slurp(dir / "made.txt"), "made\n");
}

TEST(OutputFile, APairIsReplacedOnlyWhenBothAreComplete) {
  testing::TempDir dir;
  WriteTextFile(dir / "m.node", "old node\n");
  WriteTextFile(dir / "m.ele", "old ele\n");
  EXPECT_THROW(
      WriteAtomicallyAll(
          {{dir / "m.node", [](std::FILE* f) { std::fputs("new", f); }},
           {dir / "m.ele", [](std::FILE*) { throw EnvironmentError("m.ele", "disk full"); }}}),
      EnvironmentError);
  EXPECT_EQ(Slurp(dir / "m.node"), "old node\n");
  EXPECT_EQ(Slurp(dir / "m.ele"), "old ele\n");
  EXPECT_TRUE(Leftovers(dir.path(), {"m.node", "m.ele"}).empty());
}

TEST(OutputFile, PathsThatCanNeverBeWrittenAreRefusedFirst) {
  testing::TempDir dir;
  WriteTextFile(dir / "in.node", "x\n");
  fs::create_symlink("in.node", dir / "alias.node");
  auto refused = [](const std::string& path, const std::vector<std::string>& inputs,
                    const std::string& words) {
    try {
      CheckOutputPath(path, "-o", inputs);
      ADD_FAILURE() << path << ": accepted";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused("", {}, "empty");
  refused(dir / std::string(300, 'n'), {}, "too long");
  refused(dir.path().string(), {}, "folder");
  refused(dir / "no/such/folder/x", {}, "");
  refused(dir / "in.node", {dir / "in.node"}, "");
  refused(dir / "alias.node", {dir / "in.node"}, "");  // the same file through a link
  CheckOutputPath(dir / "new.txt", "-o", {dir / "in.node"});
}

// The temporary a job's ranks are told before it exists (TemporaryPathFor) is the one its output
// then writes: beside a new file, beside an existing one, beside a link's target, shortened for a
// long name; none for a FIFO (written in place); a folder refused; nothing made by asking.
TEST(OutputFile, TheTemporaryNamedBeforeIsTheOneWritten) {
  testing::TempDir dir;
  WriteTextFile(dir / "old.txt", "old\n");
  fs::create_symlink("old.txt", dir / "link.txt");
  for (const std::string& name :
       std::vector<std::string>{"new.txt", "old.txt", "link.txt", std::string(250, 'n')}) {
    const std::string path = dir / name, told = TemporaryPathFor(path);
    EXPECT_LE(told.size() - told.rfind('/') - 1, 255u) << told;
    EXPECT_FALSE(fs::exists(told)) << told;
    AtomicOutput out(path);
    EXPECT_EQ(out.temporary(), told) << name;
    EXPECT_TRUE(fs::exists(told)) << told;
  }
  EXPECT_EQ(TemporaryPathFor(dir / "link.txt"),
            std::string(dir / "old.txt") + ".tmp." + std::to_string(::getpid()));
  const std::string fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(TemporaryPathFor(fifo), "");
  EXPECT_THROW(TemporaryPathFor(dir.path().string()), UsageError);
  EXPECT_THROW(TemporaryPathFor(""), UsageError);
}

// SIGTERM while an output is being written: the temporary is removed, the target untouched.
TEST(OutputFile, TemporariesAreRemovedOnSigterm) {
  testing::TempDir dir;
  WriteTextFile(dir / "big.txt", "old\n");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    InstallOutputCleanup();
    AtomicOutput out(dir / "big.txt");
    std::fputs("partial", out.file());
    std::fflush(out.file());
    ::raise(SIGTERM);
    ::_exit(0);  // not reached: the handler ends the process with the signal's status
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_EQ(Slurp(dir / "big.txt"), "old\n");
  EXPECT_TRUE(Leftovers(dir.path(), {"big.txt"}).empty());
}

// What a library prints while guarded (METIS's printf) reaches stderr, not stdout.
TEST(StdoutGuard, ALibrarysPrintfGoesToStderr) {
  testing::TempDir dir;
  const int out = ::open((dir / "out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  const int err = ::open((dir / "err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  std::fflush(stdout);
  std::fflush(stderr);
  const int saved_out = ::dup(1), saved_err = ::dup(2);
  ::dup2(out, 1), ::dup2(err, 2);
  std::printf("result\n");
  {
    const StdoutToStderr quiet;
    std::printf("chatter\n");
  }
  std::printf("more result\n");
  std::fflush(stdout);
  ::dup2(saved_out, 1), ::dup2(saved_err, 2);
  ::close(saved_out), ::close(saved_err), ::close(out), ::close(err);
  EXPECT_EQ(Slurp(dir / "out"), "result\nmore result\n");
  EXPECT_EQ(Slurp(dir / "err"), "chatter\n");
}

}  // namespace
}  // namespace meshreuse
