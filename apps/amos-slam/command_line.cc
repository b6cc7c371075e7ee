#include "commands.h"

#include <string>

namespace amos::app {

namespace {

std::string& storedCommandLine() {
  static std::string line;
  return line;
}

// `arg` as a POSIX shell reads it back: as it is when it has only safe characters, else in single quotes.
std::string shellQuoted(const std::string& arg) {
  if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                            "@%+=:,./_-") == std::string::npos)
    return arg;
  std::string out = "'";
  for (const char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void setCommandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i > 0 ? " " : "") + shellQuoted(argv[i]);
  storedCommandLine() = line;
}

const std::string& commandLine() { return storedCommandLine(); }

CLI::Validator nonNegativeWhole() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        if (!value.empty() && value.find_first_not_of("0123456789") == std::string::npos) return "";
        return "must be a whole number, 0 or more; got '" + value + "'";
      },
      "NUMBER>=0");
}

CLI::Validator portNumber() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        if (!value.empty() && value.size() <= 5 && value.find_first_not_of("0123456789") == std::string::npos &&
            std::stoi(value) <= 65535)
          return "";
        return "must be a port, 0 (any free one) to 65535; got '" + value + "'";
      },
      "PORT");
}

}  // namespace amos::app
