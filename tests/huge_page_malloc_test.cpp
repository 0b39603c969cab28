// The host heap's page policy (harness/app/huge_page_malloc.h): oitbench
// re-executes itself so that glibc's malloc, which holds every llvmpipe
// buffer, gets transparent huge pages where the kernel gives them only on
// request. What is expected follows the kernel's THP mode of this machine.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "tests/oitbench_process.h"

namespace {

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/huge_page_malloc";
const std::string kProbe = std::string(OIT_BINARY_DIR) + "/tests/huge_page_probe";

std::string kernel_thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

// key=value lines of the probe's output.
std::map<std::string, std::string> run_probe(const std::string& environment) {
  std::filesystem::create_directories(kOut);
  const std::string log = kOut + "/probe_" + std::to_string(::getpid()) + ".txt";
  const int status = std::system(("env " + environment + " " + kProbe + " > " + log + " 2>&1").c_str());
  EXPECT_EQ(status, 0);
  std::ifstream in(log);
  std::map<std::string, std::string> fields;
  for (std::string line; std::getline(in, line);) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) fields[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return fields;
}

TEST(HugePageMalloc, HeapGetsHugePagesWhereTheKernelOffersThem) {
  const auto probe = run_probe("-u GLIBC_TUNABLES -u OIT_HUGE_PAGES");
  const std::string mode = kernel_thp_mode();
  const long huge_kb = std::stol(probe.at("anon_huge_kb"));
  if (mode == "madvise") {
    EXPECT_EQ(probe.at("policy"), "thp-malloc");
    EXPECT_EQ(probe.at("tunables"), "glibc.malloc.hugetlb=1");
    // 64 MiB touched: at least one 2 MiB page is the proof that it took effect
    // (the kernel may fall back to small pages for some when memory is fragmented).
    EXPECT_GE(huge_kb, 2048) << "THP mode madvise, tunable set, yet no huge page";
  } else if (mode == "always") {
    EXPECT_EQ(probe.at("policy"), "thp-always");
    EXPECT_EQ(probe.at("tunables"), "") << "no relaunch is needed when the kernel always gives huge pages";
    EXPECT_GE(huge_kb, 2048);
  } else {
    EXPECT_EQ(probe.at("policy"), "4k");
    EXPECT_EQ(probe.at("tunables"), "");
    EXPECT_EQ(huge_kb <= 0, true) << "THP mode '" << mode << "'";
  }
}

TEST(HugePageMalloc, OffMeansSmallPagesUnlessTheKernelForcesThem) {
  const auto probe = run_probe("-u GLIBC_TUNABLES OIT_HUGE_PAGES=off");
  const std::string mode = kernel_thp_mode();
  EXPECT_EQ(probe.at("tunables"), "");
  if (mode == "always") {
    EXPECT_EQ(probe.at("policy"), "thp-always");
  } else {
    EXPECT_EQ(probe.at("policy"), "4k");
    EXPECT_EQ(std::stol(probe.at("anon_huge_kb")), 0);
  }
}

TEST(HugePageMalloc, KeepsTheUsersOtherTunables) {
  const auto probe = run_probe("-u OIT_HUGE_PAGES GLIBC_TUNABLES=glibc.malloc.check=0");
  if (kernel_thp_mode() == "madvise") {
    EXPECT_EQ(probe.at("tunables"), "glibc.malloc.check=0:glibc.malloc.hugetlb=1");
  } else {
    EXPECT_EQ(probe.at("tunables"), "glibc.malloc.check=0");
  }
}

// The CSV's platform column and `list` name the policy of the run.
TEST(HugePageMalloc, OitbenchReportsThePolicy) {
  const std::string mode = kernel_thp_mode();
  const std::string expected = mode == "always" ? "thp-always" : mode == "madvise" ? "thp-malloc" : "4k";
  const auto listed = oit::test::run_oitbench(kOut, "list", "env -u GLIBC_TUNABLES -u OIT_HUGE_PAGES");
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_NE(listed.output.find("host pages " + expected + ","), std::string::npos) << listed.output;
  const auto off = oit::test::run_oitbench(kOut, "list", "env -u GLIBC_TUNABLES OIT_HUGE_PAGES=off");
  ASSERT_EQ(off.exit_code, 0) << off.output;
  EXPECT_NE(off.output.find(std::string("host pages ") + (mode == "always" ? "thp-always" : "4k") + ","),
            std::string::npos)
      << off.output;
}

}  // namespace
