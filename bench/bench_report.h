#pragma once
// What every benchmark's JSON records about where it ran: CPU, threads, host, commit, date, and
// with gpu the GPU's name and driver.
#include <nlohmann/json.hpp>
#include <string>

namespace rtrt {

nlohmann::json BenchMachine(bool gpu);

// Writes a report (JSON, CSV) as every output is written: whole or not at all, every write
// checked (OutputFile; a failure is an OutputError naming the file).
void WriteReportFile(const std::string& path, const std::string& text);
inline void WriteReport(const std::string& path, const nlohmann::json& report) {
    WriteReportFile(path, report.dump(2) + "\n");
}
// The report to the file a user named (-o), with a line that says so; an empty path asks for none.
void WriteReportIfNamed(const std::string& path, const nlohmann::json& report);

}  // namespace rtrt
