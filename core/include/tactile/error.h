#pragma once
// The one error type thrown at boundaries (files, packets, command-line input).
// It carries what was wrong and where, so a program can print one clear line.

#include <stdexcept>
#include <string>

namespace tactile {

class Error : public std::runtime_error {
 public:
  // `where` names the place: a file, "file.csv:12", "file.h5:/streams/skin/samples",
  // "--rate", "layout nao taxel 7". `message` says what was wrong there.
  Error(std::string where, std::string message)
      : std::runtime_error(where.empty() ? message : where + ": " + message),
        where_(std::move(where)),
        message_(std::move(message)) {}

  const std::string& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  std::string where_;
  std::string message_;
};

// "WHAT: REASON", with the reason errno names now ("cannot bind: Address already in use"):
// the message of an Error about a failed system call.
std::string system_error(const std::string& what);

}  // namespace tactile
