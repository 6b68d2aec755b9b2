// ParseOptions; see options.h.
#include "cli/options.h"

#include <algorithm>
#include <cctype>
#include <iostream>

#include "cli/common.h"
#include "core/error.h"

namespace meshreuse::cli {

namespace {

// The program as the user called it (meshreuse or meshreuse-mpi), for the usage line.
std::string Program() {
  const std::vector<std::string>& argv = FullCommandLine();
  if (argv.empty()) return "meshreuse";
  const std::string& a = argv[0];
  return a.substr(a.find_last_of('/') + 1);
}

}  // namespace

bool ParseOptions(const Args& args, const std::string& usage, const std::string& about,
                  po::options_description& desc, const po::positional_options_description& pos,
                  po::variables_map& vm) {
  desc.add_options()("help,h", "show this help");
  po::store(po::command_line_parser(args).options(desc).positional(pos).run(), vm);
  if (vm.count("help")) {
    std::cout << "usage: " << Program() << " " << usage << "\n\n"
              << about << "\n\n"
              << desc << "\n";
    return false;
  }
  try {
    po::notify(vm);
  } catch (const po::required_option& e) {
    // A missing positional argument is named as the usage line shows it (INPUT), not as the
    // option boost keeps behind it (--input).
    std::string name = e.get_option_name();
    name.erase(0, name.find_first_not_of('-'));
    for (unsigned i = 0; i < pos.max_total_count() && i < 8; ++i)
      if (pos.name_for_position(i) == name) {
        std::transform(name.begin(), name.end(), name.begin(),
                       [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
        throw UsageError("no " + name + " given: " + Program() + " " + usage);
      }
    throw;
  }
  return true;
}

}  // namespace meshreuse::cli
