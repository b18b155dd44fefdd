#pragma once
// Errors at the API boundary of loaders and the CLI. Never thrown from RT_HD code.
#include <stdexcept>
#include <string>
#include <string_view>

namespace rtrt {

// Bad input from a user: a file, a field inside it and the reason. what() reads
// "FILE: FIELD: REASON" (FIELD omitted when empty), the one line the CLI prints.
class InputError : public std::runtime_error {
  public:
    InputError(std::string file, std::string field, std::string reason);
    const std::string& File() const { return file_; }
    const std::string& Field() const { return field_; }
    const std::string& Reason() const { return reason_; }

  private:
    std::string file_, field_, reason_;
};

// A failed write of an output: the file the user named and the system's reason. what() reads
// "FILE: REASON". The CLI exits 1 (the work failed), not 2 (bad input).
class OutputError : public std::runtime_error {
  public:
    OutputError(std::string file, std::string reason);
    const std::string& File() const { return file_; }
    const std::string& Reason() const { return reason_; }

  private:
    std::string file_, reason_;
};

// TEXT with what a terminal would act on written as \xNN bytes, for messages that quote what a
// user or a file gave: control characters (C0, DEL, C1), bidirectional overrides and bytes that
// are not UTF-8. A newline in a path split the one-line error, an escape sequence reached the
// terminal, and a NUL ended the message. Other UTF-8 text passes unchanged.
std::string WithoutControlCharacters(std::string_view text);

}  // namespace rtrt
