// What every meshreuse program's main shares (meshreuse, meshreuse-mpi): the command line as given
// (for run.json) and the error taxonomy of core/error.h mapped to messages and exit codes, here
// and only here.
#include <boost/program_options/errors.hpp>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/common.h"
#include "core/error.h"

namespace meshreuse::cli {

namespace {
std::vector<std::string> g_argv;
}  // namespace

void SetFullCommandLine(int argc, char** argv) { g_argv.assign(argv, argv + argc); }
const std::vector<std::string>& FullCommandLine() { return g_argv; }

int RunReportingErrors(const char* name, const std::function<int()>& body, const std::string& who) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", who.c_str(), e.what());
    return kExitBadInput;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s %s: %s (see --help)\n", who.c_str(), name, e.what());
    return kExitBadInput;
  } catch (const boost::program_options::error& e) {
    std::fprintf(stderr, "%s %s: %s (see --help)\n", who.c_str(), name, e.what());
    return kExitBadInput;
  } catch (const EnvironmentError& e) {
    std::fprintf(stderr, "%s: error: %s\n", who.c_str(), e.what());
    return kExitEnvironment;
  } catch (const std::bad_alloc&) {
    // Readers never size anything from a header before its records arrive, and option products
    // are checked up front: the input is larger than this machine can hold.
    std::fprintf(stderr,
                 "%s: error: out of memory (the input is larger than this machine can hold)\n",
                 who.c_str());
    return kExitEnvironment;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error (a bug, please report it): %s\n", who.c_str(),
                 e.what());
    return kExitBug;
  }
}

}  // namespace meshreuse::cli
