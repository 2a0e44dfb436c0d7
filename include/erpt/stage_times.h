// Seconds spent per stage name, for the render summary and benchmarks.
#pragma once

#include <map>
#include <string>

namespace erpt {

class StageTimes {
 public:
  void add(const std::string& stage, double seconds) { seconds_[stage] += seconds; }
  const std::map<std::string, double>& all() const { return seconds_; }

 private:
  std::map<std::string, double> seconds_;
};

}  // namespace erpt
