#include "harness/run/system_load.h"

#include <fstream>
#include <sstream>
#include <string>

namespace oit {

OtherProcessLoad::Sample OtherProcessLoad::sample() {
  Sample s;
  std::ifstream stat("/proc/stat");
  std::string cpu;
  uint64_t user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(stat >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) || cpu != "cpu") return s;
  s.busy_ticks = user + nice + system + irq + softirq + steal;
  s.total_ticks = s.busy_ticks + idle + iowait;
  std::ifstream self("/proc/self/stat");
  std::string line;
  if (!std::getline(self, line)) return s;
  // Fields after the parenthesised command name; utime and stime are 14 and 15.
  std::istringstream fields(line.substr(line.rfind(')') + 2));
  std::string field;
  uint64_t utime = 0, stime = 0;
  for (int index = 3; fields >> field; ++index) {
    if (index == 14) utime = std::stoull(field);
    if (index == 15) {
      stime = std::stoull(field);
      break;
    }
  }
  s.self_ticks = utime + stime;
  s.valid = true;
  return s;
}

void OtherProcessLoad::start() { begin_ = sample(); }

double OtherProcessLoad::stop() const {
  const Sample end = sample();
  if (!begin_.valid || !end.valid || end.total_ticks <= begin_.total_ticks) return -1.0;
  const double busy = double(end.busy_ticks - begin_.busy_ticks);
  const double self = double(end.self_ticks - begin_.self_ticks);
  const double total = double(end.total_ticks - begin_.total_ticks);
  const double other = (busy - self) / total;
  return other < 0.0 ? 0.0 : (other > 1.0 ? 1.0 : other);
}

}  // namespace oit
