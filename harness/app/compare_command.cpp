// `oitbench compare`: the statistics live in analysis/compare.py (scipy's
// bootstrap and Mann-Whitney U test, Debian's python3-scipy); this command
// runs it with Debian's python3 and the repository's analysis package.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "harness/app/commands.h"

namespace oit {

int run_compare(const std::vector<std::string>& arguments) {
  const std::string python = "/usr/bin/python3";
  const std::string root = OIT_SOURCE_ROOT;
  const char* outer = std::getenv("PYTHONPATH");
  const std::string path = root + (outer && *outer ? ":" + std::string(outer) : "");
  if (setenv("PYTHONPATH", path.c_str(), 1) != 0) {
    std::fprintf(stderr, "oitbench compare: cannot set PYTHONPATH: %s\n", std::strerror(errno));
    return 1;
  }
  std::vector<std::string> words = {python, "-m", "analysis.compare"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  execv(python.c_str(), argv.data());
  std::fprintf(stderr,
               "oitbench compare: cannot run %s (%s): install Debian's python3, python3-numpy and python3-scipy "
               "(bash setup.sh build does)\n",
               python.c_str(), std::strerror(errno));
  return 1;
}

}  // namespace oit
