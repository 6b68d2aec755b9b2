// Outputs; see output_file.h.
#include "core/output_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace meshreuse {

namespace {

// Temporaries of this process, for the signal handler: fixed slots of fixed size, so the handler
// only reads memory and calls unlink (async-signal-safe).
constexpr int kSlots = 64;
constexpr size_t kSlotBytes = PATH_MAX + 1;
char g_tmp[kSlots][kSlotBytes];
std::atomic<bool> g_used[kSlots];

int Register(const std::string& tmp) {
  if (tmp.size() >= kSlotBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (g_used[i].load() || !g_used[i].compare_exchange_strong(expected, true)) continue;
    std::memcpy(g_tmp[i], tmp.c_str(), tmp.size() + 1);
    return i;
  }
  return -1;  // more than 64 outputs open at once: not cleaned on a signal, still correct
}
void Unregister(int slot) {
  if (slot >= 0) g_used[slot].store(false);
}

extern "C" void CleanupAndReraise(int sig) {
  RemoveTemporaries();
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

std::string Dir(const std::string& p) {
  const size_t slash = p.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : p.substr(0, slash);
}
std::string Base(const std::string& p) {
  const size_t slash = p.rfind('/');
  return slash == std::string::npos ? p : p.substr(slash + 1);
}

// The path a write to `path` lands on: symbolic links followed (up to 40, as the kernel does).
std::string ResolveLinks(const std::string& path) {
  std::string p = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::string buf(PATH_MAX, '\0');
    const ssize_t n = ::readlink(p.c_str(), buf.data(), buf.size());
    if (n < 0) return p;
    buf.resize(static_cast<size_t>(n));
    p = !buf.empty() && buf[0] == '/' ? buf : Dir(p) + "/" + buf;
  }
  throw UsageError(path + ": too many levels of symbolic links");
}

// Why `target` (links resolved) cannot be an output, or "" when it can.
std::string Refusal(const std::string& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) != 0) {
    if (errno == ENAMETOOLONG) return "the path is too long for the file system";
    if (errno != ENOENT) return std::strerror(errno);
    if (Base(target).size() > NAME_MAX) return "the file name is too long for the file system";
    struct stat dir {};
    if (::stat(Dir(target).c_str(), &dir) != 0)
      return "its folder " + Dir(target) + " does not exist";
    if (!S_ISDIR(dir.st_mode)) return Dir(target) + " is not a folder";
    return "";
  }
  if (S_ISDIR(st.st_mode)) return "it is a folder";
  if (S_ISREG(st.st_mode) || S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return "";
  return S_ISBLK(st.st_mode) ? "it is a block device" : "it is not a file, device or FIFO";
}

bool SameFile(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino && S_ISREG(sa.st_mode);
}

bool InPlace(const std::string& target) {
  struct stat st {};
  return ::stat(target.c_str(), &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode));
}

// The temporary beside `target` (a rename never crosses file systems); a name that would be too
// long with the suffix is shortened (the target's name is only a hint here).
std::string TemporaryOf(const std::string& target) {
  const std::string suffix = ".tmp." + std::to_string(::getpid());
  std::string base = Base(target);
  if (base.size() + suffix.size() > NAME_MAX) base = base.substr(0, NAME_MAX - suffix.size());
  return Dir(target) + "/" + base + suffix;
}

}  // namespace

std::string TemporaryPathFor(const std::string& path) {
  if (path.empty()) throw UsageError("the output path is empty");
  const std::string target = ResolveLinks(path);
  const std::string why = Refusal(target);
  if (!why.empty()) throw UsageError(path + ": cannot write: " + why);
  return InPlace(target) ? std::string() : TemporaryOf(target);
}

int RegisterTemporary(const std::string& path) { return Register(path); }
void UnregisterTemporary(int slot) { Unregister(slot); }

void RemoveTemporaries() {
  for (int i = 0; i < kSlots; ++i)
    if (g_used[i].load()) ::unlink(g_tmp[i]);
}

std::vector<std::string> StaleTemporaries(const std::string& path) {
  std::vector<std::string> stale;
  std::string target;
  try {
    target = ResolveLinks(path);
  } catch (const UsageError&) {
    return stale;
  }
  const std::string dir = Dir(target), prefix = Base(target) + ".tmp.";
  DIR* d = ::opendir(dir.c_str());
  if (!d) return stale;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string pid = name.substr(prefix.size());
    if (pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos)
      continue;
    if (::kill(static_cast<pid_t>(std::stol(pid)), 0) != 0 && errno == ESRCH)
      stale.push_back(dir + "/" + name);
  }
  ::closedir(d);
  return stale;
}

void CheckOutputPath(const std::string& path, const std::string& option,
                     const std::vector<std::string>& inputs) {
  const std::string who = option.empty() ? "output" : option;
  if (path.empty()) throw UsageError(who + ": the output path is empty");
  if (path.size() >= PATH_MAX) throw UsageError(who + ": the output path is too long");
  const std::string target = ResolveLinks(path);
  const std::string why = Refusal(target);
  if (!why.empty()) throw UsageError(who + " '" + path + "': cannot write: " + why);
  for (const std::string& in : inputs)
    if (SameFile(in, target))
      throw UsageError(who + " '" + path + "' is the input '" + in + "': give another output path");
}

AtomicOutput::AtomicOutput(const std::string& path) : path_(path) {
  if (path.empty()) throw UsageError("the output path is empty");
  target_ = ResolveLinks(path);
  const std::string why = Refusal(target_);
  if (!why.empty()) throw UsageError(path + ": cannot write: " + why);
  in_place_ = InPlace(target_);
  if (in_place_) {
    f_ = std::fopen(target_.c_str(), "wb");
    if (!f_) throw EnvironmentError(path, std::string("cannot write: ") + std::strerror(errno));
    return;
  }
  tmp_ = TemporaryOf(target_);
  slot_ = Register(tmp_);
  // O_EXCL: a leftover temporary of a killed process with our pid, or a link planted there, is
  // replaced, never written through.
  ::unlink(tmp_.c_str());
  const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0 || !(f_ = ::fdopen(fd, "wb"))) {
    const int e = errno;
    if (fd >= 0) ::close(fd);
    Unregister(slot_);
    throw EnvironmentError(path, std::string("cannot write: ") + std::strerror(e));
  }
}

AtomicOutput::~AtomicOutput() {
  if (f_) std::fclose(f_);
  if (!done_ && !in_place_ && !tmp_.empty()) ::unlink(tmp_.c_str());
  Unregister(slot_);
}

void AtomicOutput::Commit(bool defer_rename) {
  if (closed_) return;
  const bool bad = std::fflush(f_) != 0 || std::ferror(f_) != 0;
  const int e = errno;
  const bool close_failed = std::fclose(f_) != 0;
  f_ = nullptr;
  closed_ = true;
  if (bad || close_failed)
    throw EnvironmentError(
        path_, std::string("write failed: ") + std::strerror(bad ? e : errno) + " (disk full?)");
  if (in_place_) {
    done_ = true;
    return;
  }
  if (!defer_rename) Rename();
}

void AtomicOutput::Rename() {
  if (done_ || in_place_) return;
  if (!closed_) throw std::logic_error("AtomicOutput::Rename before Commit");
  if (std::rename(tmp_.c_str(), target_.c_str()) != 0)
    throw EnvironmentError(path_, std::string("cannot rename into place: ") + std::strerror(errno));
  done_ = true;
  Unregister(slot_);
  slot_ = -1;
}

void WriteAtomically(const std::string& path, const std::function<void(std::FILE*)>& body) {
  AtomicOutput out(path);
  body(out.file());
  out.Commit();
}

void WriteTextFile(const std::string& path, const std::string& text) {
  WriteAtomically(path, [&](std::FILE* f) { std::fwrite(text.data(), 1, text.size(), f); });
}

void WriteAtomicallyAll(
    const std::vector<std::pair<std::string, std::function<void(std::FILE*)>>>& files) {
  std::vector<std::unique_ptr<AtomicOutput>> outs;
  for (const auto& [path, body] : files) {
    outs.push_back(std::make_unique<AtomicOutput>(path));
    body(outs.back()->file());
    outs.back()->Commit(/*defer_rename=*/true);
  }
  for (auto& o : outs) o->Rename();
}

void InstallOutputCleanup() {
  static bool armed = false;
  if (armed) return;
  armed = true;
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction sa {};
    sa.sa_handler = CleanupAndReraise;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;
    ::sigaction(sig, &sa, nullptr);
  }
}

}  // namespace meshreuse
