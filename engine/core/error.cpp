#include "engine/core/error.h"

namespace rtrt {
namespace {
std::string Compose(const std::string& file, const std::string& field, const std::string& reason) {
    std::string message = file.empty() ? std::string("<input>") : file;
    if (!field.empty()) message += ": " + field;
    return message + ": " + reason;
}
}  // namespace

InputError::InputError(std::string file, std::string field, std::string reason)
    : std::runtime_error(Compose(file, field, reason)),
      file_(std::move(file)),
      field_(std::move(field)),
      reason_(std::move(reason)) {}

OutputError::OutputError(std::string file, std::string reason)
    : std::runtime_error(file + ": " + reason),
      file_(std::move(file)),
      reason_(std::move(reason)) {}

}  // namespace rtrt
