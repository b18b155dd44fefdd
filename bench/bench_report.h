#pragma once
// What every benchmark's JSON records about where it ran: CPU, threads, host, commit, date, and
// with gpu the GPU's name and driver.
#include <nlohmann/json.hpp>

namespace rtrt {

nlohmann::json BenchMachine(bool gpu);

}  // namespace rtrt
