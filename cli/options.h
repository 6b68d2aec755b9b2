// Option parsing shared by the subcommands: every one has --help and the same error handling.
#pragma once

#include <boost/program_options.hpp>
#include <string>

#include "cli/commands.h"

namespace meshreuse::cli {

namespace po = boost::program_options;

// Parses `args` into `vm`. Prints "usage: meshreuse USAGE" and the options and returns false when
// --help is given. Throws po::error on a bad option (main turns it into exit code 2).
bool ParseOptions(const Args& args, const std::string& usage, const std::string& about,
                  po::options_description& desc, const po::positional_options_description& pos,
                  po::variables_map& vm);

}  // namespace meshreuse::cli
