#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

namespace rtrt {

class Stopwatch {
  public:
    Stopwatch() : start_(Clock::now()) {}
    void Restart() { start_ = Clock::now(); }
    double Milliseconds() const {
        return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
    }

  private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
};

// Median of a sample (copied, since nth_element reorders): of an even count, the mean of the two
// middle values (the upper one alone had been reported: of two runs, the slower).
inline double Median(std::vector<double> samples) {
    if (samples.empty()) return 0.0;
    auto mid = samples.begin() + samples.size() / 2;
    std::nth_element(samples.begin(), mid, samples.end());
    if (samples.size() % 2 != 0) return *mid;
    const double lower = *std::max_element(samples.begin(), mid);  // the largest below mid
    return 0.5 * (lower + *mid);
}

// Mean of a sample: what a stage costs over many frames when some frames cost more than others
// (a TLAS rebuilt on some frames and refit on the rest).
inline double Mean(const std::vector<double>& samples) {
    if (samples.empty()) return 0.0;
    double sum = 0.0;
    for (double x : samples) sum += x;
    return sum / double(samples.size());
}

}  // namespace rtrt
