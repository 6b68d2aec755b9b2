// ParseOptions; see options.h.
#include "cli/options.h"

#include <iostream>

namespace meshreuse::cli {

bool ParseOptions(const Args& args, const std::string& usage, const std::string& about,
                  po::options_description& desc, const po::positional_options_description& pos,
                  po::variables_map& vm) {
  desc.add_options()("help,h", "show this help");
  po::store(po::command_line_parser(args).options(desc).positional(pos).run(), vm);
  if (vm.count("help")) {
    std::cout << "usage: meshreuse " << usage << "\n\n" << about << "\n\n" << desc << "\n";
    return false;
  }
  po::notify(vm);
  return true;
}

}  // namespace meshreuse::cli
