// PAPI counters; see papi_counters.h. Compiled with MESHREUSE_HAVE_PAPI when CMake finds PAPI.
#include "analysis/papi_counters.h"

#ifdef MESHREUSE_HAVE_PAPI
#include <papi.h>
#include <pthread.h>
#endif

#include <cstdlib>
#include <mutex>

namespace meshreuse {

std::vector<std::string> DefaultCounterEvents() {
  return {"PAPI_L1_DCM", "PAPI_L2_DCM", "PAPI_L3_TCM", "PAPI_TOT_CYC", "PAPI_TOT_INS"};
}

std::vector<long long> PapiCounters::Sum() const {
  std::vector<long long> s(events_.size(), 0);
  for (const auto& v : values_)
    for (size_t i = 0; i < v.size(); ++i) s[i] += v[i];
  return s;
}

#ifdef MESHREUSE_HAVE_PAPI

namespace {

unsigned long ThreadId() { return static_cast<unsigned long>(pthread_self()); }

// PAPI_library_init and PAPI_thread_init once per process; the error, if any.
const std::string& InitOnce() {
  static std::string error;
  static std::once_flag once;
  std::call_once(once, [] {
    const int v = PAPI_library_init(PAPI_VER_CURRENT);
    if (v != PAPI_VER_CURRENT) {
      error = v > 0 ? "PAPI library version mismatch" : std::string(PAPI_strerror(v));
      return;
    }
    const int t = PAPI_thread_init(ThreadId);
    if (t != PAPI_OK) error = std::string("PAPI_thread_init: ") + PAPI_strerror(t);
    std::atexit(PAPI_shutdown);  // frees PAPI's own state (LeakSanitizer checks the tests)
  });
  return error;
}

// Adds, starts and stops `name` in a fresh event set; empty on success, else PAPI's reason.
std::string Try(const std::string& name) {
  int set = PAPI_NULL;
  int rc = PAPI_create_eventset(&set);
  if (rc != PAPI_OK) return PAPI_strerror(rc);
  std::string why;
  long long v = 0;
  if ((rc = PAPI_add_named_event(set, name.c_str())) != PAPI_OK)
    why = PAPI_strerror(rc);
  else if ((rc = PAPI_start(set)) != PAPI_OK)
    why = PAPI_strerror(rc);
  else if ((rc = PAPI_stop(set, &v)) != PAPI_OK)
    why = PAPI_strerror(rc);
  PAPI_cleanup_eventset(set);
  PAPI_destroy_eventset(&set);
  return why;
}

}  // namespace

std::string PapiCounters::Version() {
  return "PAPI " + std::to_string(PAPI_VERSION_MAJOR(PAPI_VERSION)) + "." +
         std::to_string(PAPI_VERSION_MINOR(PAPI_VERSION)) + "." +
         std::to_string(PAPI_VERSION_REVISION(PAPI_VERSION));
}

PapiCounters::PapiCounters(const std::vector<std::string>& events, int threads) {
  const std::string& init = InitOnce();
  if (!init.empty()) {
    dropped_ = events;
    reason_ = Version() + " could not start: " + init;
    return;
  }
  std::string why;
  for (const std::string& e : events) {
    const std::string r = Try(e);
    if (r.empty()) {
      events_.push_back(e);
    } else {
      dropped_.push_back(e);
      why += (why.empty() ? "" : "; ") + e + ": " + r;
    }
  }
  if (!dropped_.empty()) {
    const PAPI_hw_info_t* hw = PAPI_get_hardware_info();
    std::string where;
    if (hw && hw->virtualized)
      where = std::string(", running in a VM (") + hw->virtual_vendor_string + ")";
    int presets = 0;
    for (int i = 0; i < PAPI_MAX_PRESET_EVENTS; ++i)
      if (PAPI_query_event(static_cast<int>(i | PAPI_PRESET_MASK)) == PAPI_OK) ++presets;
    // A disabled perf_event component (some hypervisors: "libpfm4 no default PMU found") leaves
    // even software events missing; say why, the user can do nothing else about it.
    std::string disabled;
    for (int i = 0; i < PAPI_num_components(); ++i) {
      const PAPI_component_info_t* c = PAPI_get_component_info(i);
      if (c && std::string(c->name) == "perf_event" && c->disabled)
        disabled = std::string(", perf_event component disabled (") + c->disabled_reason + ")";
    }
    reason_ = Version() + where + disabled + ", " + std::to_string(presets) +
              " preset events available: " + why;
  }
  sets_.assign(threads < 1 ? 1 : threads, PAPI_NULL);
  values_.assign(sets_.size(), std::vector<long long>(events_.size(), 0));
}

PapiCounters::~PapiCounters() {
  for (int& s : sets_)
    if (s != PAPI_NULL) {
      PAPI_cleanup_eventset(s);
      PAPI_destroy_eventset(&s);
    }
}

void PapiCounters::Enter(int thread) {
  if (events_.empty() || thread < 0 || thread >= static_cast<int>(sets_.size())) return;
  int& set = sets_[thread];
  int rc = PAPI_OK;
  if (set == PAPI_NULL) {
    PAPI_register_thread();
    rc = PAPI_create_eventset(&set);
    for (size_t i = 0; rc == PAPI_OK && i < events_.size(); ++i)
      rc = PAPI_add_named_event(set, events_[i].c_str());
  }
  if (rc == PAPI_OK) rc = PAPI_start(set);
  if (rc != PAPI_OK) {
#pragma omp critical(meshreuse_papi_error)
    if (error_.empty()) error_ = "thread " + std::to_string(thread) + ": " + PAPI_strerror(rc);
  }
}

void PapiCounters::Exit(int thread) {
  if (events_.empty() || thread < 0 || thread >= static_cast<int>(sets_.size())) return;
  std::vector<long long> v(events_.size(), 0);
  const int rc = PAPI_stop(sets_[thread], v.data());
  if (rc != PAPI_OK) {
#pragma omp critical(meshreuse_papi_error)
    if (error_.empty()) error_ = "thread " + std::to_string(thread) + ": " + PAPI_strerror(rc);
    return;
  }
  for (size_t i = 0; i < v.size(); ++i) values_[thread][i] += v[i];
}

#else  // built without PAPI

std::string PapiCounters::Version() { return "PAPI (not built in: libpapi-dev was missing)"; }

PapiCounters::PapiCounters(const std::vector<std::string>& events, int threads)
    : dropped_(events), reason_("built without PAPI (install libpapi-dev and rebuild)") {
  values_.assign(threads < 1 ? 1 : threads, {});
}
PapiCounters::~PapiCounters() = default;
void PapiCounters::Enter(int) {}
void PapiCounters::Exit(int) {}

#endif

CounterNote ProbeCounters(const std::vector<std::string>& events, int threads) {
  if (events.empty()) return {false, ""};
  const PapiCounters probe(events, threads);
  return {probe.available(), probe.reason()};
}

}  // namespace meshreuse
